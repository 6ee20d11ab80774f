// Building blocks shared by the report's hand-written SVG charts: the plot frame, tick steps,
// axes, text and the colour palettes. Internal to tools/report/ (the chart files use them so
// every chart has the same margins, fonts and axis style).
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace gearpath::tools::svg {

// Plot rectangle inside an SVG of width x height.
struct Frame {
  double width = 560.0;
  double height = 320.0;
  double left = 70.0;
  double right = 20.0;
  double top = 40.0;
  double bottom = 55.0;
  double x0() const { return left; }
  double x1() const { return width - right; }
  double y0() const { return height - bottom; }  // bottom of the plot area
  double y1() const { return top; }
  double pw() const { return x1() - x0(); }
  double ph() const { return y0() - y1(); }
};

// Step of about `target` ticks over [0, range]: 1, 2 or 5 times a power of ten.
double NiceStep(double range, int target = 5);

// Line colour of shaft (or series) i: a fixed palette, repeated.
const char* ShaftColour(std::size_t i);

// Colour of t in [0, 1] on a perceptually ordered dark-blue -> yellow ramp (viridis stops).
std::string RampColour(double t);

// <svg ...> with a white background; the caller closes it with "</svg>\n".
void Open(std::string& s, const Frame& f, std::string_view css_class, std::string_view label);

// Escaped text at (x, y); `extra` is appended to the element's attributes verbatim.
void Text(std::string& s, double x, double y, std::string_view text,
          const char* anchor = "middle", int size = 12, std::string_view extra = "");

// Bold chart title centred above the plot.
void Title(std::string& s, const Frame& f, std::string_view title);

// Axis lines, ticks and labels of a linear plot [x_lo, x_hi] x [y_lo, y_hi]; no x ticks when
// `x_ticks` is false (the caller draws its own, e.g. clock times).
void Axes(std::string& s, const Frame& f, double x_lo, double x_hi, double y_lo, double y_hi,
          std::string_view x_label, std::string_view y_label, bool x_ticks = true,
          double min_x_step = 0.0);

// Right-hand y axis [y_lo, y_hi] (a second quantity overlaid, e.g. speed), in `colour`.
void RightAxis(std::string& s, const Frame& f, double y_lo, double y_hi, std::string_view label,
               const char* colour);

// Short horizontal legend line at (x, y) and its label; `dash` is a stroke-dasharray or "".
void LegendLine(std::string& s, double x, double y, const char* colour, std::string_view dash,
                std::string_view label, double width = 1.5);

}  // namespace gearpath::tools::svg
