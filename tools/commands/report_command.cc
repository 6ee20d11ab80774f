// `gearpath report`: the pictures an analyst wants for one block or a span of a recording, as
// one self-contained HTML file (tools/report/report_page.h; docs/report.md).
//
// It runs the recording through the same BlockProcessor the daemon uses, from its first block
// up to the block asked for, so the healthy baseline is learned exactly as the daemon would
// learn it (the first --baseline-blocks accepted blocks) unless thresholds are given. The
// table, bars and verdict are the BlockResult's numbers. The kurtogram maps and the squared
// envelope spectra are drawn from the same dsp stages (core/dsp) run again on the block's raw
// signal and on the processor's dominant-path signal with the processor's own settings (the
// envelope band width is set explicitly in the setup so both use one value); the harmonic
// amplitudes read from these spectra are checked against the BlockResult's and a mismatch is
// an error, so a picture can never show another computation than the verdict's.
//
// Exit codes: 0 report written, 1 the report could not be written, 2 bad input (missing or
// unreadable recording or FRF set, unknown machine, block or span out of range, rejected
// block, bad thresholds).
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/common/result.h"
#include "core/diagnosis/train_layout.h"
#include "core/dsp/band_pass.h"
#include "core/dsp/envelope_spectrum.h"
#include "core/dsp/harmonic_indicator.h"
#include "core/dsp/kurtogram.h"
#include "core/dsp/synchronous_average.h"
#include "core/io/frf_set_io.h"
#include "core/io/recording.h"
#include "core/model/gear_train.h"
#include "core/model/lumped_gearbox_model.h"
#include "core/pipeline/block_processor.h"
#include "core/simulation/model_frf_set.h"
#include "tools/commands/commands.h"
#include "tools/report/amplitude_spectrum.h"
#include "tools/report/report_data.h"
#include "tools/report/report_page.h"
#include "tools/report/signal_statistics.h"

namespace gearpath::tools {
namespace {

struct ReportOptions {
  std::string builtin;
  std::string frf_set_dir;
  std::string train = "table1";
  std::string recording;
  long long block = -1;
  std::string span;
  int baseline_blocks = 20;
  std::vector<double> raw_thresholds;
  std::vector<double> reconstructed_thresholds;
  double speed_hz = 0.0;
  std::string output;
};

// Relative agreement the redrawn harmonic amplitudes must have with the BlockResult's (same
// code on the same samples; only the band edges may differ by rounding).
constexpr double kRedrawTolerance = 1e-6;

Result<TrainLayout> NamedTrain(const std::string& name) {
  if (name != "table1") {
    return Error{fmt::format("unknown gear train '{}' (known: table1)", name)};
  }
  return TrainLayoutFromGearTrain(GearTrain::Table1());
}

struct BlockRange {
  std::size_t first = 0;  // first block of the trend
  std::size_t last = 0;   // the block whose pictures are drawn
};

Result<BlockRange> ParseRange(const ReportOptions& o, std::size_t count) {
  const std::string have =
      count == 0 ? std::string("the recording holds no block")
                 : fmt::format("the recording holds {} blocks (0..{})", count, count - 1);
  BlockRange r;
  if (!o.span.empty()) {
    const auto colon = o.span.find(':');
    std::size_t used_a = 0;
    std::size_t used_b = 0;
    long long a = -1;
    long long b = -1;
    try {
      if (colon == std::string::npos) throw std::invalid_argument("no colon");
      const std::string sa = o.span.substr(0, colon);
      const std::string sb = o.span.substr(colon + 1);
      a = std::stoll(sa, &used_a);
      b = std::stoll(sb, &used_b);
      if (used_a != sa.size() || used_b != sb.size()) throw std::invalid_argument("trailing");
    } catch (const std::exception&) {
      return Error{fmt::format("--span '{}' is not START:END (block indices)", o.span)};
    }
    if (a < 0 || b < a) {
      return Error{fmt::format("--span {}: START must be >= 0 and <= END", o.span)};
    }
    if (static_cast<std::size_t>(b) >= count) {
      return Error{fmt::format("--span {}: block {} is out of range: {}", o.span, b, have)};
    }
    r.first = static_cast<std::size_t>(a);
    r.last = static_cast<std::size_t>(b);
    return r;
  }
  if (o.block < 0) return Error{"give --block N or --span START:END"};
  if (static_cast<std::size_t>(o.block) >= count) {
    return Error{fmt::format("--block {} is out of range: {}", o.block, have)};
  }
  r.first = r.last = static_cast<std::size_t>(o.block);
  return r;
}

// FRF row -> index of the recording channel with the same sensor and axis; -1 if none.
int RecordingChannelOf(const Recording& rec, const ResponseChannel& row) {
  for (std::size_t c = 0; c < rec.layout.channels.size(); ++c) {
    const ChannelInfo& ch = rec.layout.channels[c];
    if (ch.sensor == row.sensor && AxisName(ch.axis) == row.axis) return static_cast<int>(c);
  }
  return -1;
}

// The dsp stages of BlockProcessor's envelope analysis, configured like the processor's.
struct EnvelopeRedraw {
  std::optional<Kurtogram> kurtogram;
  std::optional<BandPass> band_pass;
  std::optional<EnvelopeSpectrum> ses;
  std::vector<double> filtered;

  static Result<EnvelopeRedraw> Create(std::size_t n, const AnalysisOptions& o) {
    EnvelopeRedraw r;
    KurtogramOptions ko;
    ko.depth = o.kurtogram_max_level;
    ko.min_bandwidth_hz = o.min_band_width_hz;
    auto k = Kurtogram::Create(n, o.sample_rate_hz, ko);
    if (!k) return Error{"kurtogram: " + k.error()};
    r.kurtogram.emplace(std::move(k.value()));
    auto bp = BandPass::Create(n, o.sample_rate_hz, 0.1 * o.min_band_width_hz);
    if (!bp) return Error{"band-pass: " + bp.error()};
    r.band_pass.emplace(std::move(bp.value()));
    auto ses = EnvelopeSpectrum::Create(n, o.sample_rate_hz);
    if (!ses) return Error{"envelope spectrum: " + ses.error()};
    r.ses.emplace(std::move(ses.value()));
    r.filtered.assign(n, 0.0);
    return r;
  }

  // Kurtogram map and SES of `signal`; the band is the processor's rule (the kurtogram band
  // when significant, else the analysis band [band_lo, band_hi]).
  Status Draw(std::span<const double> signal, double band_lo, double band_hi,
              const std::string& what, ReportKurtogram& map, ReportSes& ses_out) {
    auto k = kurtogram->Process(signal);
    if (!k) return Error{"kurtogram of the " + what + " signal: " + k.error()};
    const KurtogramBand& kb = k.value();
    map.title = "Kurtogram, " + what + " signal";
    map.nyquist_hz = kurtogram->sample_rate_hz() / 2.0;
    map.row_level.clear();
    map.rows.clear();
    for (std::size_t r = 0; r < kurtogram->row_count(); ++r) {
      const KurtogramNode node = kurtogram->row_node(r);
      map.row_level.push_back(node.DisplayLevel());
      const auto row = kurtogram->map_row(r);
      map.rows.emplace_back(row.begin(), row.end());
      if (kb.significant && node.level == kb.node.level && node.ternary == kb.node.ternary) {
        map.chosen_row = static_cast<int>(r);
        map.chosen_index = kb.node.index;
      }
    }
    map.significant = kb.significant;
    map.kurtosis = kb.kurtosis;
    map.low_hz = kb.significant ? kb.low_hz : band_lo;
    map.high_hz = kb.significant ? kb.high_hz : band_hi;
    if (!band_pass->Process(signal, map.low_hz, map.high_hz, filtered).ok()) {
      return Error{"band-pass of the " + what + " signal failed"};
    }
    ses_out.title = "Squared envelope spectrum, " + what + " signal";
    ses_out.bin_hz = ses->bin_hz();
    ses_out.values.assign(ses->bin_count(), 0.0);
    ses_out.band_low_hz = map.low_hz;
    ses_out.band_high_hz = map.high_hz;
    if (!ses->Process(filtered, ses_out.values).ok()) {
      return Error{"squared envelope spectrum of the " + what + " signal failed"};
    }
    return Status::Ok();
  }
};

// The harmonics read from a redrawn SES must be the BlockResult's.
Status CheckRedraw(const ReportSes& ses, const BlockShaftIndicator& shaft, bool reconstructed,
                   double tolerance) {
  HarmonicSearch search;
  search.relative_tolerance = tolerance;
  if (!(shaft.characteristic_hz > 0.0)) return Status::Ok();
  auto ind = ComputeHarmonicIndicator(ses.values, ses.bin_hz, shaft.characteristic_hz, search);
  if (!ind) return Error{"harmonic indicator of the redrawn SES: " + ind.error()};
  const double want = reconstructed ? shaft.reconstructed : shaft.raw;
  if (std::abs(ind->sum - want) > kRedrawTolerance * std::max(1.0, std::abs(want))) {
    return Error{
        fmt::format("redrawn {} SES gives indicator {} for shaft {} but the block "
                    "processor reported {}: the pictures would not match the table",
                    reconstructed ? "reconstructed" : "raw", ind->sum, shaft.shaft, want)};
  }
  return Status::Ok();
}

ReportSignalStatistics StatisticsOf(std::string name, std::string unit,
                                    std::span<const double> x) {
  const SignalStatistics st = ComputeSignalStatistics(x);
  return {std::move(name), std::move(unit), st.rms, st.peak, st.crest_factor, st.kurtosis};
}

Result<ReportSpectrum> SpectrumOf(std::string title, std::string unit, std::span<const double> x,
                                  double sample_rate_hz) {
  auto sp = HannAmplitudeSpectrum(x, sample_rate_hz);
  if (!sp) return Error{title + ": " + sp.error()};
  return ReportSpectrum{std::move(title), std::move(unit), sp->bin_hz, std::move(sp->amplitude)};
}

// The time-domain and spectral pictures of the reported block: statistics of every measured
// channel, waveforms, the indicator channel's spectrum (mesh zooms), each path's contribution
// spectrum and their sum, and one synchronous average per distinct shaft rate. `raw` and
// `reconstructed` are the indicator row's measured and dominant-path signals.
Status AddSignalPictures(const Recording& rec, std::size_t block, std::size_t row,
                         int block_channel, const TrainLayout& train, BlockProcessor& proc,
                         std::span<const double> raw, std::span<const double> reconstructed,
                         ReportData& d) {
  const std::size_t n = raw.size();
  const double fs = rec.layout.sample_rate_hz;
  const std::string unit = rec.layout.channels[static_cast<std::size_t>(block_channel)].unit;
  const std::string row_name = d.indicator_channel;
  std::vector<double> buffer(n);
  for (std::size_t c = 0; c < rec.layout.channels.size(); ++c) {
    const ChannelInfo& ch = rec.layout.channels[c];
    const auto samples = rec.block(block).channel(c);
    std::transform(samples.begin(), samples.end(), buffer.begin(),
                   [](float v) { return static_cast<double>(v); });
    d.statistics.push_back(
        StatisticsOf(ch.sensor + " " + AxisName(ch.axis), ch.unit, buffer));
  }
  const std::string dominant =
      d.dominant_path >= 0 && static_cast<std::size_t>(d.dominant_path) < d.paths.size()
          ? d.paths[static_cast<std::size_t>(d.dominant_path)].name
          : std::string("-");
  const std::string recon_name =
      fmt::format("reconstructed ({} contribution at {})", dominant, row_name);
  d.statistics.push_back(StatisticsOf(recon_name, unit, reconstructed));
  d.waveforms.push_back({"Measured, " + row_name, unit, fs, {raw.begin(), raw.end()}});
  d.waveforms.push_back(
      {"Reconstructed: path " + dominant + "'s contribution at " + row_name, unit, fs,
       {reconstructed.begin(), reconstructed.end()}});

  // Spectra at the indicator row.
  auto measured = SpectrumOf("measured " + row_name, unit, raw, fs);
  if (!measured) return Error{measured.error()};
  d.measured_spectrum = std::move(measured.value());
  std::vector<double> sum(n, 0.0);
  for (std::size_t p = 0; p < d.paths.size(); ++p) {
    if (!proc.PathSignal(p, row, buffer)) {
      return Error{fmt::format("no contribution signal for path {} at FRF row {}", p, row)};
    }
    for (std::size_t i = 0; i < n; ++i) sum[i] += buffer[i];
    auto sp = SpectrumOf("path " + d.paths[p].name, unit, buffer, fs);
    if (!sp) return Error{sp.error()};
    d.path_spectra.push_back(std::move(sp.value()));
  }
  // Identified forces: the processor's own spectra (no window: the inverse works on them).
  std::vector<double> force(n / 2 + 1);
  for (std::size_t p = 0; p < d.paths.size(); ++p) {
    if (!proc.ForceAmplitude(p, force)) {
      return Error{fmt::format("no identified force for path {}", p)};
    }
    d.force_spectra.push_back({"force " + d.paths[p].name, "N", fs / static_cast<double>(n),
                               force});
  }
  auto summed = SpectrumOf("sum of contributions", unit, sum, fs);
  if (!summed) return Error{summed.error()};
  d.contribution_sum = std::move(summed.value());

  // Meshes at this block's shaft rates (d.shafts is in TrainLayout order).
  for (const TrainMesh& m : train.meshes) {
    const TrainGear& a = train.gears[static_cast<std::size_t>(m.gear_a)];
    const TrainGear& b = train.gears[static_cast<std::size_t>(m.gear_b)];
    const auto sa = static_cast<std::size_t>(a.shaft);
    const auto sb = static_cast<std::size_t>(b.shaft);
    if (sa >= d.shafts.size() || sb >= d.shafts.size()) continue;
    d.meshes.push_back({a.name + "-" + b.name, a.teeth * d.shafts[sa].rate_hz, sa, sb});
  }
  d.sideband_orders = proc.setup().options.sideband_orders;

  // Synchronous averages, one per distinct shaft rate (shafts turning at one rate share it).
  double slowest = 0.0;
  for (const auto& sh : d.shafts) {
    if (sh.rate_hz > 0.0 && (slowest == 0.0 || sh.rate_hz < slowest)) slowest = sh.rate_hz;
  }
  if (!(slowest > 0.0)) return Status::Ok();
  std::size_t cap = 4;
  while (static_cast<double>(cap) < fs / slowest && cap < (1u << 16)) cap *= 2;
  auto tsa = SynchronousAverage::Create(n, fs, cap);
  if (!tsa) return Error{"synchronous average: " + tsa.error()};
  SynchronousAverageRecord rec_raw = tsa->MakeRecord();
  SynchronousAverageRecord rec_recon = tsa->MakeRecord();
  for (const auto& sh : d.shafts) {
    if (!(sh.rate_hz > 0.0)) continue;
    bool merged = false;
    for (auto& done : d.synchronous_averages) {
      if (std::abs(done.shaft_hz - sh.rate_hz) <= 1e-9 * sh.rate_hz) {
        done.shaft += ", " + sh.name;
        merged = true;
      }
    }
    if (merged) continue;
    if (!tsa->Process(raw, sh.rate_hz, rec_raw).ok() ||
        !tsa->Process(reconstructed, sh.rate_hz, rec_recon).ok()) {
      continue;  // a block shorter than one revolution: no average to show
    }
    d.synchronous_averages.push_back({sh.name, sh.rate_hz,
                                      static_cast<int>(rec_raw.revolutions),
                                      {rec_raw.tsa().begin(), rec_raw.tsa().end()},
                                      {rec_recon.tsa().begin(), rec_recon.tsa().end()}});
  }
  return Status::Ok();
}

int Fail(int code, const std::string& message) {
  std::fprintf(stderr, "gearpath report: %s\n", message.c_str());
  return code;
}

int RunReport(const ReportOptions& o) {
  // Machine: FRF set and gear train.
  FrfSet frf;
  std::string frf_source;
  if (!o.builtin.empty() && !o.frf_set_dir.empty()) {
    return Fail(kExitBadInput, "give either --builtin or --frf-set, not both");
  }
  if (!o.builtin.empty()) {
    if (o.builtin != "table1") {
      return Fail(kExitBadInput,
                  fmt::format("unknown built-in machine '{}' (known: table1)", o.builtin));
    }
    auto set = MakeTable1FrfSet();
    if (!set) return Fail(kExitFailure, set.error());
    frf = std::move(set.value());
    frf_source = "builtin:table1";
  } else if (!o.frf_set_dir.empty()) {
    auto set = ReadFrfSet(o.frf_set_dir);
    if (!set) return Fail(kExitBadInput, set.error());
    frf = std::move(set.value());
    frf_source = o.frf_set_dir;
  } else {
    return Fail(kExitBadInput, "give the machine: --builtin table1 or --frf-set DIR");
  }
  auto train = NamedTrain(o.train);
  if (!train) return Fail(kExitBadInput, "--train: " + train.error());
  auto ratios = ShaftRateRatios(train.value());
  if (!ratios) return Fail(kExitBadInput, "--train: " + ratios.error());

  // Recording and range.
  if (!std::filesystem::is_directory(o.recording)) {
    return Fail(kExitBadInput,
                fmt::format("recording '{}' does not exist or is not a directory", o.recording));
  }
  auto rec_or = ReadRecording(o.recording);
  if (!rec_or) return Fail(kExitBadInput, rec_or.error());
  const Recording& rec = rec_or.value();
  auto range = ParseRange(o, rec.block_count());
  if (!range) return Fail(kExitBadInput, range.error());

  // Setup, as the daemon builds it for one machine.
  MachineSetup setup;
  setup.machine_id = rec.layout.machine_id;
  setup.frf_set = frf;
  setup.train = train.value();
  for (const ChannelInfo& ch : rec.layout.channels) {
    setup.block_channels.push_back(ExpectedChannel{ch.sensor, ch.axis});
  }
  AnalysisOptions& opt = setup.options;
  opt.sample_rate_hz = rec.layout.sample_rate_hz;
  double nominal = o.speed_hz;
  for (std::size_t i = 0; nominal <= 0.0 && i < rec.block_count(); ++i) {
    if (rec.blocks[i].speed_hz > 0.0) nominal = rec.blocks[i].speed_hz;
  }
  opt.nominal_speed_hz = nominal;
  opt.baseline_blocks = o.baseline_blocks;
  opt.raw_thresholds = o.raw_thresholds;
  opt.reconstructed_thresholds = o.reconstructed_thresholds;
  // The processor's automatic envelope band width, made explicit so the redraw uses the same.
  const double max_ratio = *std::max_element(ratios->begin(), ratios->end());
  const double max_speed = nominal > 0.0 ? 1.2 * nominal : 100.0;
  opt.min_band_width_hz = 2.0 * kIndicatorHarmonics * max_ratio * max_speed;
  auto proc_or = BlockProcessor::Create(setup);
  if (!proc_or) return Fail(kExitBadInput, proc_or.error());
  BlockProcessor& proc = proc_or.value();

  // Run the blocks up to the last one asked for.
  ReportData d;
  BlockResult result;
  std::size_t rejected = 0;
  for (std::size_t i = 0; i <= range->last; ++i) {
    const ProcessOutcome outcome = proc.Process(rec.block(i), result);
    if (!outcome.accepted()) {
      if (i >= range->first) {
        return Fail(kExitBadInput, fmt::format("block {} was rejected: {}", i,
                                               std::string(outcome.message.view())));
      }
      ++rejected;
      continue;
    }
    if (i >= range->first && range->last > range->first) {
      ReportTrendPoint p;
      p.block_index = i;
      p.sequence = result.sequence;
      p.dominant_path = std::string(result.dominant_path_name);
      p.state = ToString(result.verdict.state);
      p.gear = std::string(result.verdict.gear_name);
      p.t0_ns = result.t0_ns;
      p.speed_hz = result.speed_hz;
      p.score = result.score.score;
      p.limit_z = result.score.limit_z;
      p.clear_level = result.score.clear_level;
      for (const BlockShaftIndicator& sh : result.shafts) {
        p.raw.push_back(sh.raw);
        p.reconstructed.push_back(sh.reconstructed);
        p.reconstructed_threshold.push_back(sh.reconstructed_threshold);
      }
      d.trend.push_back(std::move(p));
    }
  }

  // The last block's numbers.
  const RecordedBlockInfo& info = rec.blocks[range->last];
  d.machine_id = rec.layout.machine_id;
  d.recording = o.recording;
  d.frf_source = frf_source;
  d.block_index = range->last;
  d.block_count = rec.block_count();
  d.sequence = result.sequence;
  d.t0_ns = result.t0_ns;
  d.sample_rate_hz = rec.layout.sample_rate_hz;
  d.samples_per_channel = rec.layout.samples_per_channel;
  d.speed_hz = result.speed_hz;
  d.speed_source = SpeedSourceName(result.speed_source);
  d.baseline_learned = proc.baseline_blocks_learned();
  d.baseline_needed = proc.baseline_blocks_needed();
  d.rejected_blocks = rejected;
  (void)info;
  for (const BlockPathShare& p : result.paths) {
    d.paths.push_back(
        {std::string(p.name), std::string(p.bearing), p.share, p.energy, p.criterion});
  }
  d.dominant_path = result.dominant_path;
  const auto row = static_cast<std::size_t>(std::max(result.indicator_channel, 0));
  if (row >= frf.channels.size()) {
    return Fail(kExitFailure, fmt::format("indicator channel {} is not an FRF row", row));
  }
  d.indicator_channel = frf.channels[row].sensor + " " + frf.channels[row].axis;
  for (const BlockShaftIndicator& sh : result.shafts) {
    ReportShaft r;
    r.name = std::string(sh.shaft);
    r.rate_hz = sh.characteristic_hz;
    r.raw = sh.raw;
    r.reconstructed = sh.reconstructed;
    r.enhancement_percent = sh.enhancement_percent;
    r.raw_threshold = sh.raw_threshold;
    r.reconstructed_threshold = sh.reconstructed_threshold;
    r.raw_harmonics = sh.raw_harmonics;
    r.reconstructed_harmonics = sh.reconstructed_harmonics;
    d.shafts.push_back(std::move(r));
  }
  // Condition indicators: BlockResult::condition is signal-major over the rate groups and does
  // not store a set's group, so set i has group i % groups (groups = the processor's groups of
  // indicator names = condition.size() / number of signals).
  std::size_t groups = 0;
  while (!proc.ConditionIndicatorNames(groups).empty()) ++groups;
  const BlockScore& score = result.score;
  d.score = {score.limit_z,
             score.clear_level,
             score.score,
             std::string(score.indicator),
             std::string(score.signal),
             std::string(score.shaft),
             score.exceed_count,
             score.window};
  for (std::size_t i = 0; groups > 0 && i < result.condition.size(); ++i) {
    const BlockConditionIndicators& c = result.condition[i];
    ReportIndicatorSet set;
    set.source = std::string(ToString(c.source));
    set.signal = std::string(c.signal);
    set.shaft = std::string(c.shaft);
    set.group = i % groups;
    set.shaft_hz = c.shaft_hz;
    set.revolutions = c.revolutions;
    set.score = c.score;
    const auto names = proc.ConditionIndicatorNames(set.group);
    for (std::size_t k = 0; k < c.value.size() && k < c.z.size(); ++k) {
      set.values.push_back({k < names.size() ? names[k] : fmt::format("#{}", k), c.value[k],
                            c.z[k]});
    }
    d.condition.push_back(std::move(set));
  }
  d.state = ToString(result.verdict.state);
  d.gear = std::string(result.verdict.gear_name);
  d.shaft = std::string(result.verdict.shaft_name);
  d.confidence = result.verdict.confidence;
  for (const auto name : result.verdict.candidate_names) d.candidates.emplace_back(name);
  d.reason = std::string(result.verdict.reason.view());

  // Redraw the envelope stages for the pictures: raw = the block's channel of the indicator
  // row, reconstructed = the processor's dominant-path signal at that row.
  const int block_channel = RecordingChannelOf(rec, frf.channels[row]);
  if (block_channel < 0) {
    return Fail(kExitBadInput, fmt::format("FRF row {} ({} {}) is not a channel of the recording",
                                           row, frf.channels[row].sensor, frf.channels[row].axis));
  }
  const std::size_t n = rec.layout.samples_per_channel;
  std::vector<double> raw(n);
  const auto samples = rec.block(range->last).channel(static_cast<std::size_t>(block_channel));
  std::transform(samples.begin(), samples.end(), raw.begin(),
                 [](float v) { return static_cast<double>(v); });
  std::vector<double> reconstructed(n, 0.0);
  const auto dom = proc.DominantPathSignal(row);
  if (dom.size() == n) std::copy(dom.begin(), dom.end(), reconstructed.begin());
  auto redraw = EnvelopeRedraw::Create(n, proc.setup().options);
  if (!redraw) return Fail(kExitFailure, redraw.error());
  const double nyquist = rec.layout.sample_rate_hz / 2.0;
  const double band_lo = result.analysis_band_lo_hz;
  const double band_hi = std::min(result.analysis_band_hi_hz, nyquist);
  if (auto st = redraw->Draw(raw, band_lo, band_hi, "raw", d.kurtogram_raw, d.ses_raw); !st.ok()) {
    return Fail(kExitFailure, st.error());
  }
  if (auto st = redraw->Draw(reconstructed, band_lo, band_hi, "reconstructed",
                             d.kurtogram_reconstructed, d.ses_reconstructed);
      !st.ok()) {
    return Fail(kExitFailure, st.error());
  }
  const double tol = proc.setup().options.harmonic_tolerance;
  for (const BlockShaftIndicator& sh : result.shafts) {
    for (const bool r : {false, true}) {
      if (auto st = CheckRedraw(r ? d.ses_reconstructed : d.ses_raw, sh, r, tol); !st.ok()) {
        return Fail(kExitFailure, st.error());
      }
    }
  }

  d.analysis_band_lo_hz = band_lo;
  d.analysis_band_hi_hz = band_hi;
  if (auto st = AddSignalPictures(rec, range->last, row, block_channel, train.value(), proc, raw,
                                  reconstructed, d);
      !st.ok()) {
    return Fail(kExitFailure, st.error());
  }

  // Write.
  const std::string html = RenderReportHtml(d);
  std::ofstream out(o.output, std::ios::binary | std::ios::trunc);
  if (!out) return Fail(kExitFailure, fmt::format("cannot open '{}' for writing", o.output));
  out << html;
  out.close();
  if (!out) return Fail(kExitFailure, fmt::format("writing '{}' failed", o.output));
  std::printf("report of block %zu (%s) written to %s\n", range->last, d.state.c_str(),
              o.output.c_str());
  return kExitOk;
}

}  // namespace

void AddReportCommand(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<ReportOptions>();
  CLI::App* cmd = app.add_subcommand(
      "report",
      "HTML report of one block or a span of a recording: verdict, statistics, waveform, "
      "path bars, mesh-frequency zooms, contribution spectra, kurtograms, squared envelope "
      "spectra, synchronous averages, indicators, trends against UTC time");
  cmd->add_option("--builtin", o->builtin, "built-in machine (FRF set and gear train): table1");
  cmd->add_option("--frf-set", o->frf_set_dir, "FRF set directory (docs/frf_format.md)");
  cmd->add_option("--train", o->train, "gear train of an --frf-set machine (built-in: table1)")
      ->capture_default_str();
  cmd->add_option("--recording", o->recording, "recording directory (manifest.json + samples.npy)")
      ->required();
  cmd->add_option("--block", o->block, "block index (0-based) to report");
  cmd->add_option("--span", o->span,
                  "START:END block indices (inclusive): trend over the span, pictures of END");
  cmd->add_option("--baseline-blocks", o->baseline_blocks,
                  "learn thresholds from this many first accepted blocks of the recording")
      ->capture_default_str()
      ->check(CLI::Range(1, 100000));
  cmd->add_option("--raw-thresholds", o->raw_thresholds,
                  "per-shaft raw indicator thresholds (instead of learning)")
      ->delimiter(',');
  cmd->add_option("--reconstructed-thresholds", o->reconstructed_thresholds,
                  "per-shaft reconstructed indicator thresholds (instead of learning)")
      ->delimiter(',');
  cmd->add_option("--speed", o->speed_hz,
                  "nominal input-shaft speed, Hz (default: the recording's block speed)");
  cmd->add_option("-o,--output", o->output, "output HTML file")->required();
  cmd->callback([o, &exit_code] { exit_code = RunReport(*o); });
}

}  // namespace gearpath::tools
