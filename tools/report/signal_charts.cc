#include "tools/report/signal_charts.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <iterator>
#include <limits>

#include "tools/report/svg_primitives.h"
#include "tools/report/xml_text.h"

namespace gearpath::tools {
namespace {

using svg::Axes;
using svg::Frame;
using svg::LegendLine;
using svg::Open;
using svg::ShaftColour;
using svg::Text;
using svg::Title;

// Amplitude in dB re 1 unit; a floor keeps exact zeros (empty bins) drawable.
double Db(double amplitude) { return 20.0 * std::log10(std::max(std::abs(amplitude), 1e-12)); }

// Path through the largest bin of each pixel column of [lo_hz, hi_hz] (peak hold: a line
// narrower than a pixel keeps its height).
std::string PeakHoldPath(const ReportSpectrum& sp, const Frame& f, double lo_hz, double hi_hz,
                         double db_lo, double db_hi) {
  std::string d;
  if (!(sp.bin_hz > 0.0) || !(hi_hz > lo_hz)) return d;
  const auto columns = static_cast<std::size_t>(std::max(1.0, std::floor(f.pw())));
  std::vector<double> peak(columns, -std::numeric_limits<double>::infinity());
  for (std::size_t k = 0; k < sp.amplitude.size(); ++k) {
    const double hz = static_cast<double>(k) * sp.bin_hz;
    if (hz < lo_hz || hz > hi_hz) continue;
    const auto c = std::min(columns - 1, static_cast<std::size_t>((hz - lo_hz) / (hi_hz - lo_hz) *
                                                                  static_cast<double>(columns)));
    peak[c] = std::max(peak[c], Db(sp.amplitude[k]));
  }
  const double cw = f.pw() / static_cast<double>(columns);
  bool first = true;
  for (std::size_t c = 0; c < columns; ++c) {
    if (!std::isfinite(peak[c])) continue;
    const double y = f.y0() - std::clamp((peak[c] - db_lo) / (db_hi - db_lo), 0.0, 1.0) * f.ph();
    fmt::format_to(std::back_inserter(d), "{}{:.1f} {:.1f}", first ? "M" : "L",
                   f.x0() + cw * (static_cast<double>(c) + 0.5), y);
    first = false;
  }
  return d;
}

}  // namespace

std::string WaveformSvg(const ReportWaveform& wave, double y_abs_max) {
  Frame f;
  f.width = 1140.0;
  f.height = 300.0;
  std::string s;
  Open(s, f, "waveform", wave.title);
  Title(s, f, wave.title);
  const double n = static_cast<double>(wave.samples.size());
  const double duration_ms = wave.sample_rate_hz > 0.0 ? 1000.0 * n / wave.sample_rate_hz : 1.0;
  const double ymax = y_abs_max > 0.0 ? y_abs_max : 1.0;
  Axes(s, f, 0.0, duration_ms, -ymax, ymax, "time from the block's t0 (ms)",
       "acceleration (" + wave.unit + ")");
  const auto yof = [&](double v) {
    return f.y0() - std::clamp((v + ymax) / (2.0 * ymax), 0.0, 1.0) * f.ph();
  };
  // One vertical stroke per pixel column from its smallest to its largest sample.
  const auto columns = static_cast<std::size_t>(std::floor(f.pw()));
  std::string d;
  for (std::size_t c = 0; c < columns && !wave.samples.empty(); ++c) {
    const double per_column = n / static_cast<double>(columns);
    const auto a = static_cast<std::size_t>(static_cast<double>(c) * per_column);
    const auto b =
        std::max(a + 1, static_cast<std::size_t>(static_cast<double>(c + 1) * per_column));
    double lo = std::numeric_limits<double>::infinity();
    double hi = -lo;
    for (std::size_t i = a; i < std::min(b, wave.samples.size()); ++i) {
      if (!std::isfinite(wave.samples[i])) continue;
      lo = std::min(lo, wave.samples[i]);
      hi = std::max(hi, wave.samples[i]);
    }
    if (!(hi >= lo)) continue;
    const double x = f.x0() + static_cast<double>(c) + 0.5;
    fmt::format_to(std::back_inserter(d), "M{:.1f} {:.1f}V{:.1f}", x, yof(lo),
                   std::min(yof(hi), yof(lo) - 0.6));
  }
  fmt::format_to(std::back_inserter(s),
                 "<path class=\"waveform\" data-samples=\"{}\" d=\"{}\" stroke=\"#1f4e9a\" "
                 "stroke-width=\"1\" fill=\"none\"/>\n",
                 wave.samples.size(), d);
  s += "</svg>\n";
  return s;
}

std::string MeshZoomSvg(const ReportSpectrum& spectrum, const ReportMesh& mesh,
                        const std::vector<ReportShaft>& shafts, int orders) {
  Frame f;
  f.width = 560.0;
  f.height = 360.0;
  f.top = 84.0;  // title, legend, then one row of order labels per shaft
  const std::string title = fmt::format("Mesh {} at {} Hz: {}", mesh.name,
                                        DisplayNumber(mesh.mesh_hz, 5), spectrum.title);
  std::string s;
  Open(s, f, "mesh-zoom", title);
  Text(s, f.width / 2.0, 20.0, fmt::format("Mesh {} at {} Hz", mesh.name,
                                           DisplayNumber(mesh.mesh_hz, 5)),
       "middle", 14, " font-weight=\"bold\"");
  // The shafts whose rate modulates this mesh (one when both gears share a shaft's rate index).
  std::vector<std::size_t> mesh_shafts = {mesh.shaft_a};
  if (mesh.shaft_b != mesh.shaft_a) mesh_shafts.push_back(mesh.shaft_b);
  double fastest = 0.0;
  for (const std::size_t i : mesh_shafts) {
    if (i < shafts.size()) fastest = std::max(fastest, shafts[i].rate_hz);
  }
  const double half = (orders + 1) * (fastest > 0.0 ? fastest : 1.0);
  const double lo = std::max(0.0, mesh.mesh_hz - half);
  const double hi = mesh.mesh_hz + half;
  // Largest bin in the window: the dB scale runs from 60 dB below it to 6 dB above.
  std::size_t peak_bin = 0;
  double peak = -1.0;
  for (std::size_t k = 0; spectrum.bin_hz > 0.0 && k < spectrum.amplitude.size(); ++k) {
    const double hz = static_cast<double>(k) * spectrum.bin_hz;
    if (hz >= lo && hz <= hi && spectrum.amplitude[k] > peak) {
      peak = spectrum.amplitude[k];
      peak_bin = k;
    }
  }
  const double db_hi = std::ceil((Db(peak) + 6.0) / 10.0) * 10.0;
  const double db_lo = db_hi - 70.0;
  Axes(s, f, lo, hi, db_lo, db_hi, "frequency (Hz)",
       "amplitude (dB re 1 " + spectrum.unit + ")");
  const auto xof = [&](double hz) { return f.x0() + (hz - lo) / (hi - lo) * f.pw(); };
  const auto yof = [&](double db) {
    return f.y0() - std::clamp((db - db_lo) / (db_hi - db_lo), 0.0, 1.0) * f.ph();
  };
  // Cursors under the spectrum so the line stays readable.
  fmt::format_to(std::back_inserter(s),
                 "<line class=\"mesh-cursor\" data-hz=\"{}\" x1=\"{:.1f}\" y1=\"{:.1f}\" "
                 "x2=\"{:.1f}\" y2=\"{:.1f}\" stroke=\"#d62728\" stroke-width=\"1.5\"/>\n",
                 ExactNumber(mesh.mesh_hz), xof(mesh.mesh_hz), f.y0(), xof(mesh.mesh_hz), f.y1());
  for (std::size_t row = 0; row < mesh_shafts.size(); ++row) {
    const std::size_t i = mesh_shafts[row];
    if (i >= shafts.size() || !(shafts[i].rate_hz > 0.0)) continue;
    const ReportShaft& sh = shafts[i];
    for (int k = -orders; k <= orders; ++k) {
      if (k == 0) continue;
      const double hz = mesh.mesh_hz + k * sh.rate_hz;
      if (hz < lo || hz > hi) continue;
      const double x = xof(hz) + 1.5 * static_cast<double>(row);  // coincident shafts visible
      fmt::format_to(std::back_inserter(s),
                     "<line class=\"sideband-cursor\" data-shaft=\"{}\" data-order=\"{}\" "
                     "data-hz=\"{}\" x1=\"{:.1f}\" y1=\"{:.1f}\" x2=\"{:.1f}\" y2=\"{:.1f}\" "
                     "stroke=\"{}\" stroke-dasharray=\"3 3\" stroke-width=\"1\"/>\n",
                     XmlEscape(sh.name), k, ExactNumber(hz), x, f.y0(), x, f.y1(), ShaftColour(i));
      Text(s, x, f.y1() - 4.0 - 11.0 * static_cast<double>(row), fmt::format("{:+d}", k),
           "middle", 9, fmt::format(" fill=\"{}\"", ShaftColour(i)));
    }
    LegendLine(s, f.x0() + 235.0 * static_cast<double>(row), 54.0, ShaftColour(i), "3 3",
               fmt::format("mesh {} k x {} ({} Hz)", "\u00b1", sh.name,
                           DisplayNumber(sh.rate_hz, 4)));
  }
  // The spectrum, one point per bin (the zoom holds a few hundred bins at most).
  std::string d;
  for (std::size_t k = 0; spectrum.bin_hz > 0.0 && k < spectrum.amplitude.size(); ++k) {
    const double hz = static_cast<double>(k) * spectrum.bin_hz;
    if (hz < lo || hz > hi) continue;
    fmt::format_to(std::back_inserter(d), "{}{:.1f} {:.1f}", d.empty() ? "M" : "L", xof(hz),
                   yof(Db(spectrum.amplitude[k])));
  }
  fmt::format_to(std::back_inserter(s),
                 "<path class=\"spectrum-line\" data-series=\"measured\" d=\"{}\" "
                 "stroke=\"#222222\" stroke-width=\"1.2\" fill=\"none\"/>\n",
                 d);
  if (peak >= 0.0) {
    const double peak_hz = static_cast<double>(peak_bin) * spectrum.bin_hz;
    fmt::format_to(std::back_inserter(s),
                   "<circle class=\"spectrum-peak\" data-hz=\"{}\" data-value=\"{}\" "
                   "cx=\"{:.1f}\" cy=\"{:.1f}\" r=\"3.5\" fill=\"#d62728\"/>\n",
                   ExactNumber(peak_hz), ExactNumber(peak), xof(peak_hz), yof(Db(peak)));
    // Subtitle: which signal, and where its largest line in the window is.
    Text(s, f.width / 2.0, 36.0,
         fmt::format("{}; largest bin {} Hz, {} {} (red dot)", spectrum.title,
                     DisplayNumber(peak_hz, 5), DisplayNumber(peak, 3), spectrum.unit),
         "middle", 11, " fill=\"#555555\"");
  }
  s += "</svg>\n";
  return s;
}

std::string ContributionSpectraSvg(const ReportSpectrum& measured,
                                   const std::vector<ReportSpectrum>& paths,
                                   const std::vector<std::string>& path_names,
                                   const ReportSpectrum& sum, double lo_hz, double hi_hz) {
  Frame f;
  f.width = 1140.0;
  f.height = 380.0;
  f.right = 190.0;  // legend
  std::string s;
  const std::string title = "Contribution spectra at the indicator channel: " + measured.title;
  Open(s, f, "contribution-spectra", title);
  Title(s, f, title);
  double top = -1e300;
  for (const double a : measured.amplitude) top = std::max(top, Db(a));
  for (const double a : sum.amplitude) top = std::max(top, Db(a));
  const double db_hi = std::ceil((top + 6.0) / 10.0) * 10.0;
  const double db_lo = db_hi - 100.0;
  if (!(hi_hz > lo_hz)) hi_hz = lo_hz + 1.0;
  Axes(s, f, lo_hz, hi_hz, db_lo, db_hi, "frequency (Hz)",
       "amplitude (dB re 1 " + measured.unit + ")");
  const auto series = [&](const ReportSpectrum& sp, const std::string& name, const char* colour,
                          double width, const char* dash) {
    fmt::format_to(std::back_inserter(s),
                   "<path class=\"spectrum-line\" data-series=\"{}\" d=\"{}\" stroke=\"{}\" "
                   "stroke-width=\"{}\" fill=\"none\"{}/>\n",
                   XmlEscape(name), PeakHoldPath(sp, f, lo_hz, hi_hz, db_lo, db_hi), colour,
                   width, dash);
  };
  // Paths first (thin), then measured and the sum on top, so the comparison stays visible.
  for (std::size_t p = 0; p < paths.size(); ++p) {
    series(paths[p], p < path_names.size() ? path_names[p] : fmt::format("path {}", p),
           ShaftColour(p), 0.8, "");
  }
  series(measured, "measured", "#000000", 1.6, "");
  series(sum, "sum of contributions", "#d62728", 1.4, " stroke-dasharray=\"5 3\"");
  const double lx = f.x1() + 15.0;
  double ly = f.y1() + 10.0;
  LegendLine(s, lx, ly, "#000000", "", "measured", 1.6);
  LegendLine(s, lx, ly += 18.0, "#d62728", "5 3", "sum of contributions", 1.4);
  for (std::size_t p = 0; p < paths.size(); ++p) {
    LegendLine(s, lx, ly += 18.0, ShaftColour(p), "",
               "path " + (p < path_names.size() ? path_names[p] : std::to_string(p)), 1.0);
  }
  s += "</svg>\n";
  return s;
}

std::string ForceSpectraSvg(const std::vector<ReportSpectrum>& forces,
                            const std::vector<std::string>& path_names, double lo_hz,
                            double hi_hz) {
  Frame f;
  f.width = 1140.0;
  f.height = 360.0;
  f.right = 230.0;  // legend
  const std::string unit = forces.empty() ? std::string("N") : forces.front().unit;
  std::string s;
  Open(s, f, "force-spectra", "identified bearing-force spectra");
  Title(s, f, "Identified bearing-force spectra (one per path)");
  if (!(hi_hz > lo_hz)) hi_hz = lo_hz + 1.0;
  double top = -1e300;
  for (const auto& sp : forces) {
    for (std::size_t k = 0; k < sp.amplitude.size(); ++k) {
      const double hz = static_cast<double>(k) * sp.bin_hz;
      if (hz >= lo_hz && hz <= hi_hz) top = std::max(top, Db(sp.amplitude[k]));
    }
  }
  const double db_hi = std::ceil((top + 6.0) / 10.0) * 10.0;
  const double db_lo = db_hi - 100.0;
  Axes(s, f, lo_hz, hi_hz, db_lo, db_hi, "frequency (Hz)", "force amplitude (dB re 1 " + unit + ")");
  double ly = f.y1() + 10.0;
  for (std::size_t p = 0; p < forces.size(); ++p) {
    const ReportSpectrum& sp = forces[p];
    const std::string name = p < path_names.size() ? path_names[p] : fmt::format("path {}", p);
    fmt::format_to(std::back_inserter(s),
                   "<path class=\"spectrum-line force-line\" data-series=\"{}\" d=\"{}\" "
                   "stroke=\"{}\" stroke-width=\"1\" fill=\"none\"/>\n",
                   XmlEscape(name), PeakHoldPath(sp, f, lo_hz, hi_hz, db_lo, db_hi),
                   ShaftColour(p));
    std::size_t best = 0;
    double peak = -1.0;
    for (std::size_t k = 0; sp.bin_hz > 0.0 && k < sp.amplitude.size(); ++k) {
      const double hz = static_cast<double>(k) * sp.bin_hz;
      if (hz >= lo_hz && hz <= hi_hz && sp.amplitude[k] > peak) {
        peak = sp.amplitude[k];
        best = k;
      }
    }
    if (peak > 0.0) {
      const double hz = static_cast<double>(best) * sp.bin_hz;
      fmt::format_to(std::back_inserter(s),
                     "<circle class=\"force-peak\" data-path=\"{}\" data-hz=\"{}\" "
                     "data-value=\"{}\" cx=\"{:.1f}\" cy=\"{:.1f}\" r=\"3\" fill=\"{}\"/>\n",
                     XmlEscape(name), ExactNumber(hz), ExactNumber(peak),
                     f.x0() + (hz - lo_hz) / (hi_hz - lo_hz) * f.pw(),
                     f.y0() - std::clamp((Db(peak) - db_lo) / (db_hi - db_lo), 0.0, 1.0) * f.ph(),
                     ShaftColour(p));
      LegendLine(s, f.x1() + 15.0, ly, ShaftColour(p), "",
                 fmt::format("{}: max {} {} @ {} Hz", name, DisplayNumber(peak, 3), unit,
                             DisplayNumber(hz, 4)),
                 1.0);
      ly += 18.0;
    }
  }
  s += "</svg>\n";
  return s;
}

std::string SynchronousAverageSvg(const ReportSynchronousAverage& tsa, const std::string& unit,
                                  double y_abs_max) {
  Frame f;
  f.width = 560.0;
  f.height = 320.0;
  const std::string title =
      fmt::format("Synchronous average, {} shaft ({} Hz, {} revolutions)", tsa.shaft,
                  DisplayNumber(tsa.shaft_hz, 5), tsa.revolutions);
  std::string s;
  Open(s, f, "synchronous-average", title);
  Title(s, f, title);
  const double ymax = y_abs_max > 0.0 ? y_abs_max : 1.0;
  Axes(s, f, 0.0, 360.0, -ymax, ymax, "shaft angle from the block's first sample (degrees)",
       "acceleration (" + unit + ")", true, 45.0);
  const auto line = [&](const std::vector<double>& v, const char* name, const char* colour) {
    std::string d;
    for (std::size_t i = 0; i < v.size(); ++i) {
      const double x = f.x0() + static_cast<double>(i) / static_cast<double>(v.size()) * f.pw();
      const double y = f.y0() - std::clamp((v[i] + ymax) / (2.0 * ymax), 0.0, 1.0) * f.ph();
      fmt::format_to(std::back_inserter(d), "{}{:.1f} {:.1f}", i == 0 ? "M" : "L", x, y);
    }
    fmt::format_to(std::back_inserter(s),
                   "<path class=\"tsa-line\" data-series=\"{}\" d=\"{}\" stroke=\"{}\" "
                   "stroke-width=\"1.2\" fill=\"none\"/>\n",
                   name, d, colour);
  };
  line(tsa.raw, "measured", "#222222");
  line(tsa.reconstructed, "reconstructed", "#1f77b4");
  LegendLine(s, f.x0() + 10.0, f.y1() + 14.0, "#222222", "", "measured");
  LegendLine(s, f.x0() + 130.0, f.y1() + 14.0, "#1f77b4", "", "reconstructed (dominant path)");
  s += "</svg>\n";
  return s;
}

}  // namespace gearpath::tools
