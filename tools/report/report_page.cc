#include "tools/report/report_page.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <iterator>
#include <vector>

#include "tools/report/report_charts.h"
#include "tools/report/signal_charts.h"
#include "tools/report/trend_charts.h"
#include "tools/report/utc_time.h"
#include "tools/report/xml_text.h"

namespace gearpath::tools {
namespace {

constexpr char kStyle[] = R"(
body { font-family: "DejaVu Sans", "Liberation Sans", Arial, sans-serif; margin: 24px;
       color: #222222; background: #fafafa; }
h1 { font-size: 22px; margin-bottom: 4px; }
h2 { font-size: 17px; margin: 22px 0 8px 0; border-bottom: 1px solid #cccccc; }
h3 { font-size: 14px; margin: 14px 0 6px 0; }
table { border-collapse: collapse; font-size: 13px; }
th, td { border: 1px solid #cccccc; padding: 4px 9px; text-align: right; }
th { background: #eeeeee; }
td.name, th.name { text-align: left; }
td.time { white-space: nowrap; }
.row { display: flex; flex-wrap: wrap; gap: 12px; align-items: flex-start; }
svg { border: 1px solid #dddddd; background: #ffffff; }
.verdict { font-size: 18px; font-weight: bold; padding: 10px 14px; border-radius: 4px; }
.state-alarm { background: #f8d0d0; border: 2px solid #c00000; }
.state-suspected { background: #fde8c8; border: 2px solid #d07000; }
.state-no_fault { background: #d8f0d8; border: 2px solid #2a8a2a; }
.state-learning { background: #e4e4f4; border: 2px solid #5050a0; }
.over { color: #c00000; font-weight: bold; }
.meta td { text-align: left; }
.note { font-size: 12px; color: #555555; }
)";

void Cell(std::string& s, double value, int digits = 4, bool over = false) {
  fmt::format_to(std::back_inserter(s), "<td data-value=\"{}\"{}>{}</td>", ExactNumber(value),
                 over ? " class=\"over\"" : "", XmlEscape(DisplayNumber(value, digits)));
}

// A threshold cell: the value once learned (or configured); while the baseline is being
// learned there is none, and a 0 would read as a limit everything exceeds.
void ThresholdCell(std::string& s, double threshold) {
  if (threshold > 0.0) {
    Cell(s, threshold);
  } else {
    s += "<td class=\"not-learned\">not learned yet</td>";
  }
}

void Meta(std::string& s, std::string_view key, std::string_view value) {
  fmt::format_to(std::back_inserter(s), "<tr><th class=\"name\">{}</th><td>{}</td></tr>\n",
                 XmlEscape(key), XmlEscape(value));
}

// Condition indicators, one table per shaft-rate group (the groups' indicator names differ by
// their meshes): a row per signal, a cell per indicator with its value and z; |z| over the
// limit in red. Shown only once the baseline is learned (no z before).
void ConditionSection(std::string& s, const ReportData& d) {
  const auto out = std::back_inserter(s);
  const ReportScore& sc = d.score;
  s += "<h2>Condition indicators (synchronous averages, judged against the healthy "
       "baseline)</h2>\n<section id=\"condition\">\n";
  if (!(sc.limit_z > 0.0)) {
    fmt::format_to(out,
                   "<p class=\"note\">Not judged yet: the healthy baseline is being learned "
                   "({} of {} blocks); indicators get z-scores and a limit once it is "
                   "complete.</p>\n</section>\n",
                   d.baseline_learned, d.baseline_needed);
    return;
  }
  s += "<table class=\"score meta\">\n";
  Meta(s, "block score",
       fmt::format("{} of the limit (z {}), {} on {} at {}", DisplayNumber(sc.score, 3),
                   DisplayNumber(sc.score * sc.limit_z, 3), sc.indicator, sc.signal, sc.shaft));
  Meta(s, "limit in force",
       fmt::format("|z| {} (from the false-alarm rate); an alarm clears below {} x the limit",
                   DisplayNumber(sc.limit_z, 4), DisplayNumber(sc.clear_level, 3)));
  Meta(s, "exceedances", fmt::format("{} of the last {} blocks over the limit", sc.exceed_count,
                                     sc.window));
  s += "</table>\n";
  std::size_t groups = 0;
  for (const auto& set : d.condition) groups = std::max(groups, set.group + 1);
  for (std::size_t g = 0; g < groups; ++g) {
    const ReportIndicatorSet* first = nullptr;
    for (const auto& set : d.condition) {
      if (set.group == g) {
        first = &set;
        break;
      }
    }
    if (first == nullptr) continue;
    fmt::format_to(out,
                   "<h3>{} shaft rate ({} Hz)</h3>\n<table class=\"condition\" "
                   "data-group=\"{}\">\n<tr><th class=\"name\">signal</th><th "
                   "class=\"name\">source</th><th>revolutions</th><th>set score</th>",
                   XmlEscape(first->shaft), XmlEscape(DisplayNumber(first->shaft_hz, 5)), g);
    for (const auto& v : first->values) {
      fmt::format_to(out, "<th>{}<br/>value</th><th>z</th>", XmlEscape(v.name));
    }
    s += "</tr>\n";
    for (const auto& set : d.condition) {
      if (set.group != g) continue;
      fmt::format_to(out,
                     "<tr data-signal=\"{}\" data-source=\"{}\" data-shaft=\"{}\"><td "
                     "class=\"name\">{}</td><td class=\"name\">{}</td><td>{}</td>",
                     XmlEscape(set.signal), XmlEscape(set.source), XmlEscape(set.shaft),
                     XmlEscape(set.signal), XmlEscape(set.source), set.revolutions);
      Cell(s, set.score, 3, set.score > 1.0);
      for (const auto& v : set.values) {
        const bool over = std::abs(v.z) > sc.limit_z;
        Cell(s, v.value, 4, over);
        Cell(s, v.z, 3, over);
      }
      s += "</tr>\n";
    }
    s += "</table>\n";
  }
  s += "<p class=\"note\">z: robust z-score against the machine's healthy baseline (median and "
       "scale). Red: |z| over the limit (set score: over 1 = over the limit). Units: "
       "docs/condition_indicators.md.</p>\n</section>\n";
}

// Largest |value| over the signals, for a y axis -m..m shared by the pictures side by side.
double AbsMax(std::initializer_list<const std::vector<double>*> signals) {
  double m = 0.0;
  for (const auto* v : signals) {
    for (const double x : *v) {
      if (std::isfinite(x)) m = std::max(m, std::abs(x));
    }
  }
  return m > 0.0 ? 1.05 * m : 1.0;
}

void StatisticsSection(std::string& s, const ReportData& d) {
  if (d.statistics.empty()) return;
  s += "<h2>Overall statistics of the block</h2>\n<section id=\"statistics\">\n"
       "<table class=\"statistics\">\n<tr><th class=\"name\">signal</th><th "
       "class=\"name\">unit</th><th>RMS</th><th>peak</th><th>crest factor</th><th>kurtosis</th>"
       "</tr>\n";
  for (const ReportSignalStatistics& st : d.statistics) {
    fmt::format_to(std::back_inserter(s),
                   "<tr data-statistics=\"{}\"><td class=\"name\">{}</td><td "
                   "class=\"name\">{}</td>",
                   XmlEscape(st.signal), XmlEscape(st.signal), XmlEscape(st.unit));
    Cell(s, st.rms);
    Cell(s, st.peak);
    Cell(s, st.crest_factor, 3);
    Cell(s, st.kurtosis, 3);
    s += "</tr>\n";
  }
  s += "</table>\n<p class=\"note\">About the block mean: RMS, peak = largest |x - mean|, "
       "crest factor = peak / RMS, kurtosis = mean (x - mean)^4 / RMS^4 (3 for Gaussian noise, "
       "1.5 for a sine; impacts raise it).</p>\n</section>\n";
}

void WaveformSection(std::string& s, const ReportData& d) {
  if (d.waveforms.empty()) return;
  double y = 0.0;
  for (const auto& w : d.waveforms) y = std::max(y, AbsMax({&w.samples}));
  s += "<h2>Time waveform (same scale)</h2>\n<section id=\"waveform\">\n";
  for (const auto& w : d.waveforms) s += WaveformSvg(w, y);
  s += "</section>\n";
}

void SpectraSection(std::string& s, const ReportData& d) {
  if (!d.meshes.empty() && !d.measured_spectrum.amplitude.empty()) {
    fmt::format_to(std::back_inserter(s),
                   "<h2>Spectrum around each mesh frequency (sideband cursors at mesh "
                   "&#177; k x shaft rate, k = 1..{})</h2>\n<section id=\"mesh-zoom\" "
                   "class=\"row\">\n",
                   d.sideband_orders);
    for (const ReportMesh& m : d.meshes) {
      s += MeshZoomSvg(d.measured_spectrum, m, d.shafts, d.sideband_orders);
    }
    s += "</section>\n<p class=\"note\">Hann-windowed amplitude spectrum of the measured "
         "indicator channel, amplitude-corrected (a sine on a bin reads its amplitude).</p>\n";
  }
  if (!d.path_spectra.empty()) {
    std::vector<std::string> names;
    for (const auto& p : d.paths) names.push_back(p.name);
    s += "<h2>Path contribution spectra and their sum against the measured response</h2>\n"
         "<section id=\"contribution-spectra\">\n";
    s += ContributionSpectraSvg(d.measured_spectrum, d.path_spectra, names, d.contribution_sum,
                                d.analysis_band_lo_hz, d.analysis_band_hi_hz);
    s += "<p class=\"note\">Contribution of each path = FRF x identified bearing force, at the "
         "indicator channel, over the analysis band. Where the sum follows the measured "
         "spectrum, the paths explain the response.</p>\n</section>\n";
  }
  if (!d.force_spectra.empty()) {
    std::vector<std::string> names;
    for (const auto& p : d.paths) names.push_back(p.name);
    s += "<h2>Identified bearing-force spectra</h2>\n<section id=\"force-spectra\">\n";
    // From half the lowest mesh frequency: the lowest bins of the identified forces are orders
    // of magnitude above the mesh region (seen on the simulated gearbox) and would flatten it.
    double lowest_mesh = 0.0;
    for (const auto& m : d.meshes) {
      if (m.mesh_hz > 0.0 && (lowest_mesh == 0.0 || m.mesh_hz < lowest_mesh)) {
        lowest_mesh = m.mesh_hz;
      }
    }
    const double lo = std::max(d.analysis_band_lo_hz, 0.5 * lowest_mesh);
    s += ForceSpectraSvg(d.force_spectra, names, lo, d.analysis_band_hi_hz);
    fmt::format_to(std::back_inserter(s),
                   "<p class=\"note\">Amplitude of each path's bearing force identified from all "
                   "measured channels (the inverse step), from {} Hz (half the lowest mesh "
                   "frequency; the bins below are left out of the picture) to the top of the "
                   "analysis band; zero outside the FRF range.</p>\n</section>\n",
                   XmlEscape(DisplayNumber(lo, 4)));
  }
}

void SynchronousAverageSection(std::string& s, const ReportData& d) {
  if (d.synchronous_averages.empty()) return;
  double y = 0.0;
  for (const auto& t : d.synchronous_averages) y = std::max(y, AbsMax({&t.raw, &t.reconstructed}));
  const std::string unit = d.waveforms.empty() ? std::string("m/s^2") : d.waveforms.front().unit;
  s += "<h2>Synchronous averages per shaft (indicator channel, same scale)</h2>\n"
       "<section id=\"synchronous-averages\" class=\"row\">\n";
  for (const auto& t : d.synchronous_averages) s += SynchronousAverageSvg(t, unit, y);
  s += "</section>\n";
}

std::string StateLabel(const std::string& state) {
  if (state == "no_fault") return "NO FAULT";
  if (state == "suspected") return "SUSPECTED";
  if (state == "alarm") return "ALARM";
  if (state == "learning") return "LEARNING (baseline not complete, no verdict yet)";
  return state;
}

}  // namespace

std::string RenderReportHtml(const ReportData& d) {
  std::string s;
  s.reserve(1 << 16);
  const auto out = std::back_inserter(s);
  fmt::format_to(
      out,
      "<!DOCTYPE html>\n<html xmlns=\"http://www.w3.org/1999/xhtml\" lang=\"en\">\n"
      "<head>\n<meta charset=\"utf-8\"/>\n<title>{}</title>\n<style>{}</style>\n"
      "</head>\n<body>\n",
      XmlEscape(fmt::format("gearpath report - {} block {}", d.machine_id, d.block_index)), kStyle);
  fmt::format_to(out, "<h1>gearpath report: machine {}, block {}{}</h1>\n", XmlEscape(d.machine_id),
                 d.block_index,
                 d.trend.size() > 1
                     ? XmlEscape(fmt::format(" (span {}-{})", d.trend.front().block_index,
                                             d.trend.back().block_index))
                     : std::string());

  // Summary of where the numbers come from.
  s += "<section id=\"summary\">\n<table class=\"meta\">\n";
  Meta(s, "recording", d.recording);
  Meta(s, "FRF set", d.frf_source);
  Meta(s, "block",
       fmt::format("{} of {} (sequence {})", d.block_index, d.block_count, d.sequence));
  fmt::format_to(out,
                 "<tr><th class=\"name\">block start (t0)</th><td class=\"t0\" "
                 "data-t0-ns=\"{}\">{}</td></tr>\n",
                 d.t0_ns, XmlEscape(FormatUtc(d.t0_ns)));
  Meta(s, "block shape",
       fmt::format("{} samples at {} Hz", d.samples_per_channel,
                   DisplayNumber(d.sample_rate_hz, 6)));
  Meta(s, "input speed", fmt::format("{} Hz ({})", DisplayNumber(d.speed_hz, 6), d.speed_source));
  Meta(s, "indicator channel", d.indicator_channel);
  Meta(s, "healthy baseline",
       d.baseline_needed > 0
           ? fmt::format("{} of {} blocks learned", d.baseline_learned, d.baseline_needed)
           : std::string("configured thresholds"));
  if (d.rejected_blocks > 0) {
    Meta(s, "rejected blocks",
         fmt::format("{} earlier blocks rejected by validation", d.rejected_blocks));
  }
  s += "</table>\n</section>\n";

  // Verdict.
  fmt::format_to(out, "<h2>Verdict</h2>\n<section id=\"verdict\" class=\"verdict state-{}\">\n",
                 XmlEscape(d.state));
  std::string headline = StateLabel(d.state);
  if (!d.gear.empty()) {
    headline += fmt::format(": gear {} (shaft {}, confidence {})", d.gear, d.shaft,
                            DisplayNumber(d.confidence, 2));
  }
  fmt::format_to(out, "<p class=\"verdict-text\" data-state=\"{}\" data-gear=\"{}\">{}</p>\n",
                 XmlEscape(d.state), XmlEscape(d.gear), XmlEscape(headline));
  if (d.candidates.size() > 1) {
    std::string c;
    for (const auto& name : d.candidates) c += (c.empty() ? "" : ", ") + name;
    fmt::format_to(out, "<p class=\"note\">candidates the evidence cannot separate: {}</p>\n",
                   XmlEscape(c));
  }
  if (!d.reason.empty()) {
    fmt::format_to(out, "<p class=\"note verdict-reason\">{}</p>\n", XmlEscape(d.reason));
  }
  s += "</section>\n";

  StatisticsSection(s, d);
  WaveformSection(s, d);

  // Paths.
  s += "<h2>Transfer paths</h2>\n<section id=\"paths\" class=\"row\">\n";
  s += PathBarsSvg(d.paths, d.dominant_path);
  s += "<table class=\"paths\">\n<tr><th class=\"name\">path</th><th class=\"name\">bearing</th>"
       "<th>share</th><th>energy</th><th>criterion</th></tr>\n";
  for (std::size_t i = 0; i < d.paths.size(); ++i) {
    const ReportPath& p = d.paths[i];
    fmt::format_to(
        out, "<tr data-path=\"{}\"><td class=\"name\">{}{}</td><td class=\"name\">{}</td>",
        XmlEscape(p.name), XmlEscape(p.name),
        static_cast<int>(i) == d.dominant_path ? " (dominant)" : "", XmlEscape(p.bearing));
    Cell(s, p.share);
    Cell(s, p.energy);
    Cell(s, p.criterion);
    s += "</tr>\n";
  }
  s += "</table>\n</section>\n";

  SpectraSection(s, d);

  // Kurtograms.
  s += "<h2>Kurtograms (spectral kurtosis per band and level)</h2>\n"
       "<section id=\"kurtograms\" class=\"row\">\n";
  // One colour scale for both maps: the same colour is the same spectral kurtosis.
  double sk_max = 0.0;
  for (const ReportKurtogram* map : {&d.kurtogram_raw, &d.kurtogram_reconstructed}) {
    for (const auto& row : map->rows) {
      for (const double v : row) {
        if (std::isfinite(v)) sk_max = std::max(sk_max, v);
      }
    }
  }
  s += KurtogramSvg(d.kurtogram_raw, sk_max);
  s += KurtogramSvg(d.kurtogram_reconstructed, sk_max);
  s += "</section>\n";

  // Squared envelope spectra on a common scale up to 6x the highest shaft rate.
  double max_rate = 0.0;
  for (const auto& sh : d.shafts) max_rate = std::max(max_rate, sh.rate_hz);
  const double max_hz = max_rate > 0.0 ? 6.0 * max_rate : 100.0;
  double y_max = 0.0;
  for (const ReportSes* ses : {&d.ses_raw, &d.ses_reconstructed}) {
    for (std::size_t k = 1; k < ses->values.size(); ++k) {
      if (static_cast<double>(k) * ses->bin_hz > max_hz) break;
      if (std::isfinite(ses->values[k])) y_max = std::max(y_max, ses->values[k]);
    }
  }
  y_max = y_max > 0.0 ? 1.1 * y_max : 1.0;
  s += "<h2>Squared envelope spectra (same scale)</h2>\n<section id=\"ses\" class=\"row\">\n";
  s += SesSvg(d.ses_raw, d.shafts, max_hz, y_max, false);
  s += SesSvg(d.ses_reconstructed, d.shafts, max_hz, y_max, true);
  s += "</section>\n";

  // Indicator table.
  s += "<h2>Fault indicators (sum of the first five SES harmonics)</h2>\n"
       "<section id=\"indicators\">\n<table class=\"indicators\">\n"
       "<tr><th class=\"name\">shaft</th><th>rate (Hz)</th><th>raw</th><th>raw threshold</th>"
       "<th>reconstructed</th><th>reconstructed threshold</th><th>enhancement (%)</th></tr>\n";
  for (const ReportShaft& sh : d.shafts) {
    fmt::format_to(out, "<tr data-shaft=\"{}\"><td class=\"name\">{}</td>", XmlEscape(sh.name),
                   XmlEscape(sh.name));
    Cell(s, sh.rate_hz, 6);
    Cell(s, sh.raw, 4, sh.raw_threshold > 0.0 && sh.raw > sh.raw_threshold);
    ThresholdCell(s, sh.raw_threshold);
    Cell(s, sh.reconstructed, 4,
         sh.reconstructed_threshold > 0.0 && sh.reconstructed > sh.reconstructed_threshold);
    ThresholdCell(s, sh.reconstructed_threshold);
    Cell(s, sh.enhancement_percent, 4);
    s += "</tr>\n";
  }
  s += "</table>\n<p class=\"note\">Thresholds are learned from the healthy baseline (mean + "
       "4 sigma) or configured; none is shown while the baseline is being learned. Red: "
       "indicator over its threshold. Enhancement = 100 x reconstructed / raw.</p>\n"
       "</section>\n";

  SynchronousAverageSection(s, d);
  ConditionSection(s, d);

  // Trend over the span.
  if (d.trend.size() > 1) {
    std::vector<std::string> names;
    for (const auto& sh : d.shafts) names.push_back(sh.name);
    s += "<h2>Trends over the span (against UTC time, speed overlaid)</h2>\n"
         "<section id=\"trend\">\n";
    s += ScoreTrendSvg(d.trend);
    s += TrendSvg(d.trend, names);
    s += "<table class=\"trend\">\n<tr><th>block</th><th>sequence</th><th class=\"name\">t0 "
         "(UTC)</th><th>speed (Hz)</th><th class=\"name\">dominant "
         "path</th><th class=\"name\">state</th><th class=\"name\">gear</th>";
    for (const auto& n : names) {
      fmt::format_to(out, "<th>{} raw</th><th>{} reconstructed</th>", XmlEscape(n), XmlEscape(n));
    }
    s += "</tr>\n";
    for (const auto& p : d.trend) {
      fmt::format_to(out,
                     "<tr data-block=\"{}\"><td>{}</td><td>{}</td><td class=\"name time\">{}</td>"
                     "<td>{}</td><td class=\"name\">{}</td>"
                     "<td class=\"name\">{}</td><td class=\"name\">{}</td>",
                     p.block_index, p.block_index, p.sequence, XmlEscape(FormatUtc(p.t0_ns)),
                     XmlEscape(DisplayNumber(p.speed_hz, 5)), XmlEscape(p.dominant_path),
                     XmlEscape(p.state), XmlEscape(p.gear));
      for (std::size_t i = 0; i < names.size(); ++i) {
        Cell(s, i < p.raw.size() ? p.raw[i] : NAN);
        Cell(s, i < p.reconstructed.size() ? p.reconstructed[i] : NAN);
      }
      s += "</tr>\n";
    }
    s += "</table>\n</section>\n";
  }
  s += "<p class=\"note\">Generated by gearpath report. Self-contained: no script, no external "
       "resource.</p>\n</body>\n</html>\n";
  return s;
}

}  // namespace gearpath::tools
