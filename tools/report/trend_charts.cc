#include "tools/report/trend_charts.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <iterator>

#include "tools/report/svg_primitives.h"
#include "tools/report/utc_time.h"
#include "tools/report/xml_text.h"

namespace gearpath::tools {
namespace {

using svg::Axes;
using svg::Frame;
using svg::LegendLine;
using svg::NiceStep;
using svg::Open;
using svg::RightAxis;
using svg::ShaftColour;
using svg::Text;
using svg::Title;

constexpr const char* kSpeedColour = "#7f7f7f";

Frame TrendFrame() {
  Frame f;
  f.width = 1140.0;
  f.right = 270.0;  // speed axis, then the legend
  return f;
}

// Horizontal mapping of block times: seconds since the first block's t0.
struct TimeAxis {
  std::int64_t origin_ns = 0;
  double span_s = 1.0;
  double Seconds(std::int64_t t0_ns) const {
    return static_cast<double>(t0_ns - origin_ns) * 1e-9;
  }
  double X(const Frame& f, std::int64_t t0_ns) const {
    return f.x0() + Seconds(t0_ns) / span_s * f.pw();
  }
};

TimeAxis MakeTimeAxis(const std::vector<ReportTrendPoint>& trend) {
  TimeAxis t;
  t.origin_ns = trend.front().t0_ns;
  const double span = t.Seconds(trend.back().t0_ns);
  t.span_s = span > 0.0 ? span : 1.0;
  return t;
}

// Clock-time ticks (UTC) under the plot; the date is in the axis title.
void TimeTicks(std::string& s, const Frame& f, const TimeAxis& t) {
  const double step = std::max(1.0, NiceStep(t.span_s, 8));
  for (double v = 0.0; v <= t.span_s + 1e-9 * step; v += step) {
    const double x = f.x0() + v / t.span_s * f.pw();
    fmt::format_to(std::back_inserter(s),
                   "<line x1=\"{:.1f}\" y1=\"{:.1f}\" x2=\"{:.1f}\" y2=\"{:.1f}\" "
                   "stroke=\"#333333\"/>\n",
                   x, f.y0(), x, f.y0() + 5.0);
    Text(s, x, f.y0() + 18.0,
         FormatUtcClock(t.origin_ns + static_cast<std::int64_t>(std::llround(v * 1e9))), "middle",
         11);
  }
}

std::string TimeLabel(const TimeAxis& t) {
  return "time (UTC, hh:mm:ss), first block at " + FormatUtc(t.origin_ns);
}

// The speed on the right axis, scaled to its own range (+/-5 % margin, at least 0.1 Hz).
void SpeedOverlay(std::string& s, const Frame& f, const TimeAxis& t,
                  const std::vector<ReportTrendPoint>& trend) {
  double lo = 1e300;
  double hi = -1e300;
  for (const auto& p : trend) {
    if (p.speed_hz > 0.0) {
      lo = std::min(lo, p.speed_hz);
      hi = std::max(hi, p.speed_hz);
    }
  }
  if (!(hi >= lo)) return;
  const double margin = std::max(0.05 * (hi - lo), 0.05);
  lo = std::max(0.0, lo - margin);
  hi += margin;
  RightAxis(s, f, lo, hi, "input speed (Hz)", kSpeedColour);
  std::string pts;
  for (const auto& p : trend) {
    if (!(p.speed_hz > 0.0)) continue;
    fmt::format_to(std::back_inserter(pts), "{:.1f},{:.1f} ", t.X(f, p.t0_ns),
                   f.y0() - (p.speed_hz - lo) / (hi - lo) * f.ph());
  }
  fmt::format_to(std::back_inserter(s),
                 "<polyline class=\"trend-speed\" points=\"{}\" fill=\"none\" stroke=\"{}\" "
                 "stroke-width=\"1.2\" stroke-dasharray=\"1 2\"/>\n",
                 pts, kSpeedColour);
}

const char* StateColour(const std::string& state) {
  if (state == "alarm") return "#c00000";
  if (state == "suspected") return "#d07000";
  if (state == "no_fault") return "#2a8a2a";
  return "#5050a0";  // learning
}

}  // namespace

std::string TrendSvg(const std::vector<ReportTrendPoint>& trend,
                     const std::vector<std::string>& shaft_names) {
  Frame f = TrendFrame();
  std::string s;
  Open(s, f, "trend", "indicator trend");
  Title(s, f, "Fault indicators over the span (sum of five SES harmonics)");
  if (trend.empty()) {
    s += "</svg>\n";
    return s;
  }
  const TimeAxis t = MakeTimeAxis(trend);
  double y_hi = 0.0;
  for (const auto& p : trend) {
    for (const auto* v : {&p.raw, &p.reconstructed, &p.reconstructed_threshold}) {
      for (const double x : *v) {
        if (std::isfinite(x)) y_hi = std::max(y_hi, x);
      }
    }
  }
  y_hi = y_hi > 0.0 ? 1.1 * y_hi : 1.0;
  Axes(s, f, 0.0, t.span_s, 0.0, y_hi, TimeLabel(t), "indicator (normalised SES units)", false);
  TimeTicks(s, f, t);
  const auto yof = [&](double v) { return f.y0() - std::clamp(v / y_hi, 0.0, 1.0) * f.ph(); };
  for (std::size_t sh = 0; sh < shaft_names.size(); ++sh) {
    // Thresholds are 0 where the baseline was still being learned: those blocks are left out.
    const auto line = [&](auto member, const char* css, const char* dash, double width,
                          bool learned_only) {
      std::string pts;
      for (const auto& p : trend) {
        const auto& v = p.*member;
        if (sh >= v.size() || (learned_only && !(v[sh] > 0.0))) continue;
        fmt::format_to(std::back_inserter(pts), "{:.1f},{:.1f} ", t.X(f, p.t0_ns), yof(v[sh]));
      }
      if (pts.empty()) return;
      fmt::format_to(std::back_inserter(s),
                     "<polyline class=\"{}\" data-shaft=\"{}\" points=\"{}\" fill=\"none\" "
                     "stroke=\"{}\" stroke-width=\"{}\"{}/>\n",
                     css, XmlEscape(shaft_names[sh]), pts, ShaftColour(sh), width, dash);
    };
    line(&ReportTrendPoint::reconstructed, "trend-reconstructed", "", 2.0, false);
    line(&ReportTrendPoint::raw, "trend-raw", " stroke-dasharray=\"2 3\"", 1.5, false);
    line(&ReportTrendPoint::reconstructed_threshold, "trend-threshold",
         " stroke-dasharray=\"8 4\"", 1.0, true);
    const double y = f.y1() + 14.0 + 50.0 * static_cast<double>(sh);
    const double lx = f.x1() + 70.0;
    LegendLine(s, lx, y, ShaftColour(sh), "", shaft_names[sh] + ": reconstructed", 2.0);
    LegendLine(s, lx, y + 14.0, ShaftColour(sh), "2 3", "raw");
    LegendLine(s, lx, y + 28.0, ShaftColour(sh), "8 4", "reconstructed threshold", 1.0);
  }
  SpeedOverlay(s, f, t, trend);
  LegendLine(s, f.x1() + 70.0, f.y1() + 14.0 + 50.0 * static_cast<double>(shaft_names.size()),
             kSpeedColour, "1 2", "input speed (right axis)", 1.2);
  s += "</svg>\n";
  return s;
}

std::string ScoreTrendSvg(const std::vector<ReportTrendPoint>& trend) {
  Frame f = TrendFrame();
  std::string s;
  Open(s, f, "score-trend", "block score trend");
  Title(s, f, "Block score over the span (largest condition-indicator z / limit)");
  if (trend.empty()) {
    s += "</svg>\n";
    return s;
  }
  const TimeAxis t = MakeTimeAxis(trend);
  double y_hi = 1.5;  // the limit (1) always on the scale
  for (const auto& p : trend) {
    if (std::isfinite(p.score)) y_hi = std::max(y_hi, 1.1 * p.score);
  }
  Axes(s, f, 0.0, t.span_s, 0.0, y_hi, TimeLabel(t), "score (units of the limit)", false);
  const auto yof = [&](double v) { return f.y0() - std::clamp(v / y_hi, 0.0, 1.0) * f.ph(); };
  // Bands over each run of consecutive blocks with a limit in force, from half a block
  // interval before the run's first block to half after its last.
  const double half = trend.size() > 1 ? 0.5 * t.span_s / static_cast<double>(trend.size() - 1)
                                       : 0.5 * t.span_s;
  for (std::size_t i = 0; i < trend.size();) {
    if (!(trend[i].limit_z > 0.0)) {
      ++i;
      continue;
    }
    std::size_t j = i;
    while (j + 1 < trend.size() && trend[j + 1].limit_z > 0.0) ++j;
    const double xa = std::max(f.x0(), t.X(f, trend[i].t0_ns) - half / t.span_s * f.pw());
    const double xb = std::min(f.x1(), t.X(f, trend[j].t0_ns) + half / t.span_s * f.pw());
    const double clear = trend[j].clear_level > 0.0 ? trend[j].clear_level : 1.0;
    fmt::format_to(std::back_inserter(s),
                   "<rect class=\"score-band-alert\" data-from=\"{}\" data-to=\"{}\" x=\"{:.1f}\" "
                   "y=\"{:.1f}\" width=\"{:.1f}\" height=\"{:.1f}\" fill=\"#fde8c8\"/>\n"
                   "<rect class=\"score-band-alarm\" data-from=\"{}\" data-to=\"{}\" x=\"{:.1f}\" "
                   "y=\"{:.1f}\" width=\"{:.1f}\" height=\"{:.1f}\" fill=\"#f8d0d0\"/>\n"
                   "<line class=\"score-limit\" x1=\"{:.1f}\" y1=\"{:.1f}\" x2=\"{:.1f}\" "
                   "y2=\"{:.1f}\" stroke=\"#c00000\" stroke-dasharray=\"8 4\"/>\n",
                   trend[i].block_index, trend[j].block_index, xa, yof(1.0), xb - xa,
                   yof(clear) - yof(1.0), trend[i].block_index, trend[j].block_index, xa, f.y1(),
                   xb - xa, yof(1.0) - f.y1(), xa, yof(1.0), xb, yof(1.0));
    i = j + 1;
  }
  // Redraw the grid and axes lines over the bands would clutter; the score goes on top.
  TimeTicks(s, f, t);
  std::string pts;
  for (const auto& p : trend) {
    if (!(p.limit_z > 0.0)) continue;  // no score while learning
    fmt::format_to(std::back_inserter(pts), "{:.1f},{:.1f} ", t.X(f, p.t0_ns), yof(p.score));
  }
  if (!pts.empty()) {
    fmt::format_to(std::back_inserter(s),
                   "<polyline class=\"trend-score\" points=\"{}\" fill=\"none\" "
                   "stroke=\"#222222\" stroke-width=\"1.5\"/>\n",
                   pts);
  }
  for (const auto& p : trend) {
    const double y = p.limit_z > 0.0 ? yof(p.score) : f.y0();
    fmt::format_to(std::back_inserter(s),
                   "<circle class=\"trend-state\" data-state=\"{}\" data-t0-ns=\"{}\" "
                   "cx=\"{:.1f}\" cy=\"{:.1f}\" r=\"4\" fill=\"{}\"><title>block {} {}: {}"
                   "</title></circle>\n",
                   XmlEscape(p.state), p.t0_ns, t.X(f, p.t0_ns), y, StateColour(p.state),
                   p.block_index, FormatUtc(p.t0_ns), XmlEscape(p.state));
  }
  SpeedOverlay(s, f, t, trend);
  const double lx = f.x1() + 70.0;
  double ly = f.y1() + 14.0;
  LegendLine(s, lx, ly, "#222222", "", "block score", 1.5);
  fmt::format_to(std::back_inserter(s),
                 "<rect x=\"{:.1f}\" y=\"{:.1f}\" width=\"20\" height=\"10\" fill=\"#f8d0d0\"/>\n"
                 "<rect x=\"{:.1f}\" y=\"{:.1f}\" width=\"20\" height=\"10\" fill=\"#fde8c8\"/>\n",
                 lx, ly + 8.0, lx, ly + 26.0);
  Text(s, lx + 24.0, ly + 18.0, "alarm band: over the limit", "start", 11);
  Text(s, lx + 24.0, ly + 36.0, "alert band: clear level to limit", "start", 11);
  ly += 54.0;
  for (const char* st : {"learning", "no_fault", "suspected", "alarm"}) {
    fmt::format_to(std::back_inserter(s),
                   "<circle cx=\"{:.1f}\" cy=\"{:.1f}\" r=\"4\" fill=\"{}\"/>\n", lx + 10.0,
                   ly - 4.0, StateColour(st));
    Text(s, lx + 24.0, ly, fmt::format("state: {}", st), "start", 11);
    ly += 16.0;
  }
  Text(s, lx, ly + 4.0, "learning: no limit yet (dot on the axis)", "start", 10,
       " fill=\"#555555\"");
  LegendLine(s, lx, ly + 24.0, kSpeedColour, "1 2", "input speed (right axis)", 1.2);
  s += "</svg>\n";
  return s;
}

}  // namespace gearpath::tools
