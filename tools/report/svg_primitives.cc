#include "tools/report/svg_primitives.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <iterator>

#include "tools/report/xml_text.h"

namespace gearpath::tools::svg {

double NiceStep(double range, int target) {
  if (!(range > 0.0) || !std::isfinite(range)) return 1.0;
  const double raw = range / target;
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  const double norm = raw / mag;
  const double f = norm < 1.5 ? 1.0 : norm < 3.0 ? 2.0 : norm < 7.0 ? 5.0 : 10.0;
  return f * mag;
}

const char* ShaftColour(std::size_t i) {
  static constexpr std::array<const char*, 6> kColours = {"#1f77b4", "#ff7f0e", "#2ca02c",
                                                          "#9467bd", "#8c564b", "#e377c2"};
  return kColours[i % kColours.size()];
}

std::string RampColour(double t) {
  static constexpr std::array<std::array<double, 3>, 5> kStops = {
      {{68, 1, 84}, {59, 82, 139}, {33, 145, 140}, {94, 201, 98}, {253, 231, 37}}};
  t = std::clamp(std::isfinite(t) ? t : 0.0, 0.0, 1.0);
  const double pos = t * static_cast<double>(kStops.size() - 1);
  const auto i = std::min(static_cast<std::size_t>(pos), kStops.size() - 2);
  const double w = pos - static_cast<double>(i);
  std::array<int, 3> c{};
  for (std::size_t k = 0; k < 3; ++k) {
    c[k] = static_cast<int>(std::lround(kStops[i][k] + w * (kStops[i + 1][k] - kStops[i][k])));
  }
  return fmt::format("#{:02x}{:02x}{:02x}", c[0], c[1], c[2]);
}

void Open(std::string& s, const Frame& f, std::string_view css_class, std::string_view label) {
  fmt::format_to(std::back_inserter(s),
                 "<svg xmlns=\"http://www.w3.org/2000/svg\" class=\"{}\" width=\"{:.0f}\" "
                 "height=\"{:.0f}\" viewBox=\"0 0 {:.0f} {:.0f}\" role=\"img\" "
                 "aria-label=\"{}\">\n"
                 "<rect x=\"0\" y=\"0\" width=\"{:.0f}\" height=\"{:.0f}\" fill=\"#ffffff\"/>\n",
                 css_class, f.width, f.height, f.width, f.height, XmlEscape(label), f.width,
                 f.height);
}

void Text(std::string& s, double x, double y, std::string_view text, const char* anchor,
          int size, std::string_view extra) {
  fmt::format_to(
      std::back_inserter(s),
      "<text x=\"{:.1f}\" y=\"{:.1f}\" font-size=\"{}\" text-anchor=\"{}\"{}>{}</text>\n", x, y,
      size, anchor, extra, XmlEscape(text));
}

void Title(std::string& s, const Frame& f, std::string_view title) {
  Text(s, f.width / 2.0, 20.0, title, "middle", 14, " font-weight=\"bold\"");
}

void Axes(std::string& s, const Frame& f, double x_lo, double x_hi, double y_lo, double y_hi,
          std::string_view x_label, std::string_view y_label, bool x_ticks, double min_x_step) {
  fmt::format_to(std::back_inserter(s),
                 "<path class=\"axis\" d=\"M{:.1f} {:.1f} V{:.1f} H{:.1f}\" fill=\"none\" "
                 "stroke=\"#333333\"/>\n",
                 f.x0(), f.y1(), f.y0(), f.x1());
  if (x_ticks && x_hi > x_lo) {
    const double step = std::max(NiceStep(x_hi - x_lo, 8), min_x_step);
    for (double v = std::ceil(x_lo / step) * step; v <= x_hi + 1e-9 * step; v += step) {
      const double x = f.x0() + (v - x_lo) / (x_hi - x_lo) * f.pw();
      fmt::format_to(std::back_inserter(s),
                     "<line x1=\"{:.1f}\" y1=\"{:.1f}\" x2=\"{:.1f}\" y2=\"{:.1f}\" "
                     "stroke=\"#333333\"/>\n",
                     x, f.y0(), x, f.y0() + 5.0);
      Text(s, x, f.y0() + 18.0, DisplayNumber(std::abs(v) < 1e-9 * step ? 0.0 : v, 6), "middle",
           11);
    }
  }
  if (y_hi > y_lo) {
    const double step = NiceStep(y_hi - y_lo, 5);
    for (double v = std::ceil(y_lo / step) * step; v <= y_hi + 1e-9 * step; v += step) {
      const double y = f.y0() - (v - y_lo) / (y_hi - y_lo) * f.ph();
      fmt::format_to(std::back_inserter(s),
                     "<line x1=\"{:.1f}\" y1=\"{:.1f}\" x2=\"{:.1f}\" y2=\"{:.1f}\" "
                     "stroke=\"#dddddd\"/>\n",
                     f.x0(), y, f.x1(), y);
      Text(s, f.x0() - 6.0, y + 4.0, DisplayNumber(std::abs(v) < 1e-9 * step ? 0.0 : v, 4),
           "end", 11);
    }
  }
  Text(s, f.x0() + f.pw() / 2.0, f.height - 8.0, x_label, "middle", 12);
  const double yc = f.y1() + f.ph() / 2.0;
  fmt::format_to(std::back_inserter(s),
                 "<text x=\"16\" y=\"{:.1f}\" font-size=\"12\" text-anchor=\"middle\" "
                 "transform=\"rotate(-90 16 {:.1f})\">{}</text>\n",
                 yc, yc, XmlEscape(y_label));
}

void RightAxis(std::string& s, const Frame& f, double y_lo, double y_hi, std::string_view label,
               const char* colour) {
  fmt::format_to(std::back_inserter(s),
                 "<path class=\"axis right-axis\" d=\"M{:.1f} {:.1f} V{:.1f}\" fill=\"none\" "
                 "stroke=\"{}\"/>\n",
                 f.x1(), f.y1(), f.y0(), colour);
  if (!(y_hi > y_lo)) return;
  const double step = NiceStep(y_hi - y_lo, 5);
  const std::string fill = fmt::format(" fill=\"{}\"", colour);
  for (double v = std::ceil(y_lo / step) * step; v <= y_hi + 1e-9 * step; v += step) {
    const double y = f.y0() - (v - y_lo) / (y_hi - y_lo) * f.ph();
    fmt::format_to(std::back_inserter(s),
                   "<line x1=\"{:.1f}\" y1=\"{:.1f}\" x2=\"{:.1f}\" y2=\"{:.1f}\" "
                   "stroke=\"{}\"/>\n",
                   f.x1(), y, f.x1() + 5.0, y, colour);
    Text(s, f.x1() + 8.0, y + 4.0, DisplayNumber(v, 4), "start", 11, fill);
  }
  const double x = f.x1() + 50.0;
  const double yc = f.y1() + f.ph() / 2.0;
  fmt::format_to(std::back_inserter(s),
                 "<text x=\"{:.1f}\" y=\"{:.1f}\" font-size=\"12\" text-anchor=\"middle\" "
                 "fill=\"{}\" transform=\"rotate(90 {:.1f} {:.1f})\">{}</text>\n",
                 x, yc, colour, x, yc, XmlEscape(label));
}

void LegendLine(std::string& s, double x, double y, const char* colour, std::string_view dash,
                std::string_view label, double width) {
  fmt::format_to(std::back_inserter(s),
                 "<line x1=\"{:.1f}\" y1=\"{:.1f}\" x2=\"{:.1f}\" y2=\"{:.1f}\" stroke=\"{}\" "
                 "stroke-width=\"{}\"{}/>\n",
                 x, y - 4.0, x + 20.0, y - 4.0, colour, width,
                 dash.empty() ? std::string() : fmt::format(" stroke-dasharray=\"{}\"", dash));
  Text(s, x + 24.0, y, label, "start", 11);
}

}  // namespace gearpath::tools::svg
