#include "tools/report/report_charts.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <iterator>

#include "tools/report/svg_primitives.h"
#include "tools/report/xml_text.h"

namespace gearpath::tools {
using svg::Axes;
using svg::Frame;
using svg::NiceStep;
using svg::Open;
using svg::RampColour;
using svg::ShaftColour;
using svg::Text;
using svg::Title;

std::string PathBarsSvg(const std::vector<ReportPath>& paths, int dominant_path) {
  Frame f;
  f.height = 335.0;
  f.bottom = 70.0;  // path name and bearing under each bar, then the axis title
  std::string s;
  Open(s, f, "path-bars", "path contribution shares");
  Title(s, f, "Path contributions (share of contribution energy)");
  Axes(s, f, 0.0, 1.0, 0.0, 100.0, "transfer path (bearing force)", "share of energy (%)", false);
  const double slot = paths.empty() ? f.pw() : f.pw() / static_cast<double>(paths.size());
  for (std::size_t i = 0; i < paths.size(); ++i) {
    const ReportPath& p = paths[i];
    const double pct = 100.0 * std::clamp(std::isfinite(p.share) ? p.share : 0.0, 0.0, 1.0);
    const double h = pct / 100.0 * f.ph();
    const double x = f.x0() + slot * (static_cast<double>(i) + 0.2);
    const bool dominant = static_cast<int>(i) == dominant_path;
    fmt::format_to(std::back_inserter(s),
                   "<rect class=\"path-bar{}\" data-path=\"{}\" data-share=\"{}\" x=\"{:.1f}\" "
                   "y=\"{:.1f}\" width=\"{:.1f}\" height=\"{:.1f}\" fill=\"{}\"><title>{} "
                   "({}): {} %</title></rect>\n",
                   dominant ? " dominant" : "", XmlEscape(p.name), ExactNumber(p.share), x,
                   f.y0() - h, slot * 0.6, h, dominant ? "#d62728" : "#1f77b4", XmlEscape(p.name),
                   XmlEscape(p.bearing), DisplayNumber(pct, 3));
    Text(s, x + slot * 0.3, f.y0() - h - 5.0, DisplayNumber(pct, 3) + " %", "middle", 11);
    Text(s, x + slot * 0.3, f.y0() + 18.0, p.name + (dominant ? " (dominant)" : ""), "middle", 12);
    Text(s, x + slot * 0.3, f.y0() + 32.0, p.bearing, "middle", 10, " fill=\"#555555\"");
  }
  s += "</svg>\n";
  return s;
}

std::string KurtogramSvg(const ReportKurtogram& map, double sk_max) {
  Frame f;
  f.height = 340.0;
  f.right = 90.0;  // room for the colour legend
  std::string s;
  Open(s, f, "kurtogram", map.title);
  Title(s, f, map.title);
  // The scale is the caller's, so maps drawn side by side share one colour per SK value.
  const double scale = sk_max > 0.0 ? sk_max : 1.0;
  const std::size_t rows = map.rows.size();
  const double rh = rows == 0 ? f.ph() : f.ph() / static_cast<double>(rows);
  const double nyq = map.nyquist_hz > 0.0 ? map.nyquist_hz : 1.0;
  for (std::size_t r = 0; r < rows; ++r) {
    const auto& row = map.rows[r];
    const double bw = f.pw() / static_cast<double>(std::max<std::size_t>(row.size(), 1));
    const double y = f.y1() + rh * static_cast<double>(r);
    for (std::size_t b = 0; b < row.size(); ++b) {
      fmt::format_to(
          std::back_inserter(s),
          "<rect class=\"kurtogram-cell\" data-sk=\"{}\" x=\"{:.2f}\" y=\"{:.2f}\" width=\"{:.2f}\" "
          "height=\"{:.2f}\" fill=\"{}\"><title>level {} band {}: SK {}</title></rect>\n",
          ExactNumber(row[b]), f.x0() + bw * static_cast<double>(b), y, bw + 0.3, rh + 0.3, RampColour(row[b] / scale),
          DisplayNumber(map.row_level[r], 2), b, DisplayNumber(row[b], 3));
    }
    Text(s, f.x0() - 6.0, y + rh / 2.0 + 4.0, DisplayNumber(map.row_level[r], 2), "end", 11);
  }
  // The band the envelope used: the chosen kurtogram cell, or (no significant band) the
  // default analysis band drawn across the whole map.
  if (map.high_hz > map.low_hz) {
    double y = f.y1();
    double h = f.ph();
    if (map.chosen_row >= 0 && static_cast<std::size_t>(map.chosen_row) < rows) {
      y = f.y1() + rh * map.chosen_row;
      h = rh;
    }
    const double x = f.x0() + map.low_hz / nyq * f.pw();
    const double w = (map.high_hz - map.low_hz) / nyq * f.pw();
    fmt::format_to(std::back_inserter(s),
                   "<rect class=\"chosen-band\" data-low-hz=\"{}\" data-high-hz=\"{}\" "
                   "x=\"{:.2f}\" y=\"{:.2f}\" width=\"{:.2f}\" height=\"{:.2f}\" fill=\"none\" "
                   "stroke=\"#ff1a1a\" stroke-width=\"3\"{}/>\n",
                   ExactNumber(map.low_hz), ExactNumber(map.high_hz), x, y, w, h,
                   map.significant ? "" : " stroke-dasharray=\"6 4\"");
  }
  // Frequency axis and labels.
  fmt::format_to(std::back_inserter(s),
                 "<path class=\"axis\" d=\"M{:.1f} {:.1f} H{:.1f}\" stroke=\"#333333\"/>\n", f.x0(),
                 f.y0(), f.x1());
  const double step = NiceStep(nyq, 8);
  for (double v = 0.0; v <= nyq + 1e-9; v += step) {
    const double x = f.x0() + v / nyq * f.pw();
    fmt::format_to(std::back_inserter(s),
                   "<line x1=\"{:.1f}\" y1=\"{:.1f}\" x2=\"{:.1f}\" y2=\"{:.1f}\" "
                   "stroke=\"#333333\"/>\n",
                   x, f.y0(), x, f.y0() + 5.0);
    Text(s, x, f.y0() + 18.0, DisplayNumber(v, 6), "middle", 11);
  }
  std::string caption =
      map.significant
          ? fmt::format("chosen band {}-{} Hz, SK {} (solid outline)", DisplayNumber(map.low_hz),
                        DisplayNumber(map.high_hz), DisplayNumber(map.kurtosis, 3))
          : fmt::format("no significant band: default {}-{} Hz used (dashed outline)",
                        DisplayNumber(map.low_hz), DisplayNumber(map.high_hz));
  Text(s, f.x0() + f.pw() / 2.0, f.height - 8.0, "frequency (Hz); " + caption, "middle", 12);
  const double yc = f.y1() + f.ph() / 2.0;
  fmt::format_to(std::back_inserter(s),
                 "<text x=\"16\" y=\"{:.1f}\" font-size=\"12\" text-anchor=\"middle\" "
                 "transform=\"rotate(-90 16 {:.1f})\">level</text>\n",
                 yc, yc);
  // Colour legend: 20 steps, 0 at the bottom.
  constexpr int kSteps = 20;
  const double lx = f.x1() + 20.0;
  const double sh = f.ph() / kSteps;
  for (int i = 0; i < kSteps; ++i) {
    const double t = (i + 0.5) / kSteps;
    fmt::format_to(std::back_inserter(s),
                   "<rect class=\"legend-step\" x=\"{:.1f}\" y=\"{:.2f}\" width=\"16\" "
                   "height=\"{:.2f}\" fill=\"{}\"/>\n",
                   lx, f.y0() - sh * (i + 1), sh + 0.3, RampColour(t));
  }
  Text(s, lx + 20.0, f.y0() + 4.0, "0", "start", 11);
  Text(s, lx + 20.0, f.y1() + 8.0, DisplayNumber(scale, 3), "start", 11,
       fmt::format(" class=\"sk-scale-max\" data-value=\"{}\"", ExactNumber(scale)));
  Text(s, lx + 8.0, f.y1() - 8.0, "SK", "middle", 11);
  s += "</svg>\n";
  return s;
}

std::string SesSvg(const ReportSes& ses, const std::vector<ReportShaft>& shafts, double max_hz,
                   double y_max, bool reconstructed) {
  Frame f;
  f.height = 380.0;
  f.top = 96.0;  // title, band, legend row, then one row of harmonic labels per shaft
  std::string s;
  Open(s, f, reconstructed ? "ses ses-reconstructed" : "ses ses-raw", ses.title);
  Title(s, f, ses.title);
  Text(s, f.width / 2.0, 36.0,
       fmt::format("demodulated from {}-{} Hz", DisplayNumber(ses.band_low_hz),
                   DisplayNumber(ses.band_high_hz)),
       "middle", 11, " fill=\"#555555\"");
  const double ymax = y_max > 0.0 ? y_max : 1.0;
  Axes(s, f, 0.0, max_hz, 0.0, ymax, "envelope frequency (Hz)", "SES (normalised)");
  const auto xof = [&](double hz) { return f.x0() + hz / max_hz * f.pw(); };
  const auto yof = [&](double v) { return f.y0() - std::clamp(v / ymax, 0.0, 1.0) * f.ph(); };
  // The spectrum as stems (one per bin: the resolution of the indicator's reading).
  std::string d;
  for (std::size_t k = 1; k < ses.values.size(); ++k) {
    const double hz = static_cast<double>(k) * ses.bin_hz;
    if (hz > max_hz) break;
    fmt::format_to(std::back_inserter(d), "M{:.1f} {:.1f}V{:.1f}", xof(hz), f.y0(),
                   yof(ses.values[k]));
  }
  fmt::format_to(std::back_inserter(s),
                 "<path class=\"ses-line\" d=\"{}\" stroke=\"#222222\" stroke-width=\"1.5\" "
                 "fill=\"none\"/>\n",
                 d);
  // Harmonic markers and the readings the indicator summed.
  for (std::size_t i = 0; i < shafts.size(); ++i) {
    const ReportShaft& sh = shafts[i];
    const auto& read = reconstructed ? sh.reconstructed_harmonics : sh.raw_harmonics;
    for (std::size_t h = 1; h <= kReportHarmonics; ++h) {
      const double hz = static_cast<double>(h) * sh.rate_hz;
      if (!(hz > 0.0) || hz > max_hz) continue;
      const double x = xof(hz) + 2.0 * static_cast<double>(i);  // coincident shafts stay visible
      fmt::format_to(std::back_inserter(s),
                     "<line class=\"harmonic-marker\" data-shaft=\"{}\" data-harmonic=\"{}\" "
                     "data-hz=\"{}\" x1=\"{:.1f}\" y1=\"{:.1f}\" x2=\"{:.1f}\" y2=\"{:.1f}\" "
                     "stroke=\"{}\" stroke-dasharray=\"4 3\" stroke-width=\"1.2\"/>\n",
                     XmlEscape(sh.name), h, ExactNumber(hz), x, f.y0(), x, f.y1(), ShaftColour(i));
      Text(s, x, f.y1() - 4.0 - 10.0 * static_cast<double>(i), fmt::format("{}x", h), "middle", 9,
           fmt::format(" fill=\"{}\"", ShaftColour(i)));
      fmt::format_to(std::back_inserter(s),
                     "<circle class=\"harmonic-reading\" data-shaft=\"{}\" data-harmonic=\"{}\" "
                     "data-value=\"{}\" cx=\"{:.1f}\" cy=\"{:.1f}\" r=\"3.5\" fill=\"{}\"/>\n",
                     XmlEscape(sh.name), h, ExactNumber(read[h - 1]), x, yof(read[h - 1]),
                     ShaftColour(i));
    }
  }
  // Legend: one row above the plot (markers of coincident shafts are offset by 2 px).
  for (std::size_t i = 0; i < shafts.size(); ++i) {
    const double y = 54.0;
    const double x = f.x0() + 160.0 * static_cast<double>(i);
    fmt::format_to(std::back_inserter(s),
                   "<line x1=\"{:.1f}\" y1=\"{:.1f}\" x2=\"{:.1f}\" y2=\"{:.1f}\" stroke=\"{}\" "
                   "stroke-dasharray=\"4 3\" stroke-width=\"1.5\"/>\n",
                   x, y - 4.0, x + 20.0, y - 4.0, ShaftColour(i));
    Text(s, x + 24.0, y,
         fmt::format("{} shaft {} Hz", shafts[i].name, DisplayNumber(shafts[i].rate_hz)), "start",
         11);
  }
  s += "</svg>\n";
  return s;
}

}  // namespace gearpath::tools
