#include "core/pipeline/block_processor.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <exception>
#include <optional>
#include <string>
#include <utility>

#include "core/diagnosis/dominant_path.h"
#include "core/diagnosis/healthy_baseline.h"
#include "core/diagnosis/speed_estimate.h"
#include "core/dsp/band_pass.h"
#include "core/dsp/envelope_spectrum.h"
#include "core/dsp/harmonic_indicator.h"
#include "core/dsp/kurtogram.h"
#include "core/dsp/spectrum.h"
#include "core/pipeline/frf_grid_mapping.h"

namespace gearpath {
namespace {

using Cd = std::complex<double>;

std::optional<Axis> ParseAxis(const std::string& s) {
  if (s == "x" || s == "X") return Axis::kX;
  if (s == "y" || s == "Y") return Axis::kY;
  if (s == "z" || s == "Z") return Axis::kZ;
  return std::nullopt;
}

const char* AxisName(Axis a) { return a == Axis::kX ? "x" : (a == Axis::kY ? "y" : "z"); }

// Median of the first n values of `v` (reorders them). 0 for n == 0.
double MedianInPlace(std::vector<double>& v, std::size_t n) noexcept {
  if (n == 0) return 0.0;
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(n / 2);
  std::nth_element(v.begin(), mid, v.begin() + static_cast<std::ptrdiff_t>(n));
  return *mid;
}

}  // namespace

// Everything that depends on the block shape (samples per channel); built on first sight.
struct Shape {
  std::size_t n = 0;
  std::size_t bins = 0;  // n/2 + 1
  double bin_hz = 0.0;
  FrfGridMapping map;
  std::optional<IdentificationOperator> op;
  std::optional<Spectrum> spectrum;        // all channels
  std::optional<InverseSpectrum> inverse;  // one channel
  std::optional<Kurtogram> kurtogram;
  std::optional<BandPass> band_pass;
  std::optional<EnvelopeSpectrum> ses;
  std::uint64_t last_used = 0;

  // Per-block buffers.
  std::vector<double> time;         // channels x n (FRF row order)
  std::vector<Cd> spec;             // channels x bins
  Eigen::MatrixXcd forces;          // paths x in-range bins
  Eigen::VectorXcd x;               // channels
  std::vector<BinFigures> figures;  // in-range bins
  std::vector<double> work_a;       // in-range bins (medians)
  std::vector<double> work_b;
  std::vector<double> amplitude;        // bins (speed estimate)
  std::vector<std::uint8_t> band_mask;  // bins: analysis band & in range
  std::vector<std::uint8_t> sideband_mask;
  std::vector<std::uint8_t> mesh_mask;
  std::vector<Cd> one_spec;           // bins (one channel spectrum, scratch)
  std::vector<double> dominant_time;  // channels x n
  std::vector<double> raw_signal;     // n (mesh tones removed)
  std::vector<double> rec_signal;     // n
  std::vector<double> filtered;       // n
  std::vector<double> ses_buf;        // bins
};

struct BlockProcessor::Impl {
  MachineSetup setup;
  BlockExpectations expect;
  std::vector<int> block_to_row;  // block channel -> FRF row
  std::vector<double> shaft_ratio;
  std::vector<MeshLines> unit_meshes;  // at 1 Hz input speed
  std::vector<double> mesh_orders;
  VerdictTopology topology;
  std::optional<HealthyBaseline> baseline;
  SequenceTracker tracker;
  std::size_t channels = 0;
  std::size_t paths = 0;
  double max_ratio = 1.0;
  double band_lo = 0.0;
  double band_hi = 0.0;
  double max_speed_hz = 0.0;  // upper bound on the input speed (bandwidth / search range)

  std::vector<Shape> shapes;
  Shape* last_shape = nullptr;
  std::uint64_t use_counter = 0;
  int last_dominant = -1;
  bool has_last = false;

  // Per-block, per-path scratch (sized once).
  std::vector<double> path_energy;
  std::vector<double> path_share;
  std::vector<double> path_criterion;
  std::vector<double> criterion_healthy;  // mean criterion per path over the baseline blocks
  int criterion_blocks = 0;
  std::vector<double> path_force;          // per path: |F|^2 on the sideband lines
  std::vector<double> path_force_healthy;  // its mean over the baseline blocks
  int path_force_blocks = 0;
  std::vector<double> mesh_evidence;  // per mesh, from the path_force excess
  std::vector<double> indicators;     // raw (shafts) then reconstructed (shafts)
  std::vector<double> raw_thr;
  std::vector<double> rec_thr;
  std::vector<MeshLines> meshes_now;

  Status Configure(std::size_t n);
  Shape* FindShape(std::size_t n) noexcept;
  void Envelope(Shape& s, std::span<const double> signal, double speed_hz, BlockEnvelopeBand& band,
                std::span<double> indicator_sum, std::span<BlockShaftIndicator> shafts,
                bool reconstructed) noexcept;
  void Contribution(const Shape& s, std::size_t path, std::size_t channel,
                    std::span<Cd> out) const noexcept;
};

Shape* BlockProcessor::Impl::FindShape(std::size_t n) noexcept {
  for (Shape& s : shapes) {
    if (s.n == n) return &s;
  }
  return nullptr;
}

Status BlockProcessor::Impl::Configure(std::size_t n) {
  if (FindShape(n) != nullptr) return Status::Ok();
  const double fs = setup.options.sample_rate_hz;
  Shape s;
  s.n = n;
  s.bins = n / 2 + 1;
  s.bin_hz = fs / static_cast<double>(n);
  auto map = MapFrfToBlockGrid(setup.frf_set.decoupled, n, fs);
  if (!map) return Error{map.error()};
  s.map = std::move(map.value());
  auto op = IdentificationOperator::Create(s.map.frf, setup.options.identification);
  if (!op) return Error{"identification operator: " + op.error()};
  s.op.emplace(std::move(op.value()));
  auto spectrum = Spectrum::Create(n, channels, fs);
  if (!spectrum) return Error{spectrum.error()};
  s.spectrum.emplace(std::move(spectrum.value()));
  auto inverse = InverseSpectrum::Create(n, 1);
  if (!inverse) return Error{inverse.error()};
  s.inverse.emplace(std::move(inverse.value()));

  const AnalysisOptions& o = setup.options;
  KurtogramOptions ko;
  ko.depth = o.kurtogram_max_level;
  ko.min_bandwidth_hz = o.min_band_width_hz > 0.0
                            ? o.min_band_width_hz
                            : 2.0 * kIndicatorHarmonics * max_ratio * max_speed_hz;
  if (ko.min_bandwidth_hz >= fs / 2.0) {
    return Error{
        fmt::format("envelope band: minimum width {} Hz (2 x {} harmonics x highest "
                    "shaft rate) does not fit below Nyquist {} Hz",
                    ko.min_bandwidth_hz, kIndicatorHarmonics, fs / 2.0)};
  }
  auto kurtogram = Kurtogram::Create(n, fs, ko);
  if (!kurtogram) return Error{"kurtogram: " + kurtogram.error()};
  s.kurtogram.emplace(std::move(kurtogram.value()));
  auto band_pass = BandPass::Create(n, fs, 0.1 * ko.min_bandwidth_hz);
  if (!band_pass) return Error{"band-pass: " + band_pass.error()};
  s.band_pass.emplace(std::move(band_pass.value()));
  auto ses = EnvelopeSpectrum::Create(n, fs);
  if (!ses) return Error{"envelope spectrum: " + ses.error()};
  s.ses.emplace(std::move(ses.value()));

  const std::size_t in_range = static_cast<std::size_t>(s.map.frf.bins());
  s.time.assign(channels * n, 0.0);
  s.spec.assign(channels * s.bins, Cd{});
  s.forces =
      Eigen::MatrixXcd::Zero(static_cast<Eigen::Index>(paths), static_cast<Eigen::Index>(in_range));
  s.x = Eigen::VectorXcd::Zero(static_cast<Eigen::Index>(channels));
  s.figures.assign(in_range, BinFigures{});
  s.work_a.assign(in_range, 0.0);
  s.work_b.assign(in_range, 0.0);
  s.amplitude.assign(s.bins, 0.0);
  s.band_mask.assign(s.bins, 0);
  for (std::size_t k = 0; k < s.bins; ++k) {
    const double f = static_cast<double>(k) * s.bin_hz;
    s.band_mask[k] = s.map.InRange(k) && f >= band_lo && f <= band_hi ? 1 : 0;
  }
  s.sideband_mask.assign(s.bins, 0);
  s.mesh_mask.assign(s.bins, 0);
  s.one_spec.assign(s.bins, Cd{});
  s.dominant_time.assign(channels * n, 0.0);
  s.raw_signal.assign(n, 0.0);
  s.rec_signal.assign(n, 0.0);
  s.filtered.assign(n, 0.0);
  s.ses_buf.assign(s.bins, 0.0);

  if (shapes.size() >= kMaxShapes) {
    // Replace the least recently used shape (the last-block pointer may dangle: reset it).
    auto oldest =
        std::min_element(shapes.begin(), shapes.end(),
                         [](const Shape& a, const Shape& b) { return a.last_used < b.last_used; });
    shapes.erase(oldest);
    last_shape = nullptr;
    has_last = false;
  }
  if (shapes.capacity() < kMaxShapes) shapes.reserve(kMaxShapes);
  shapes.push_back(std::move(s));
  return Status::Ok();
}

// Contribution spectrum of `path` at FRF row `channel`: H_cp(k) F_p(k) on in-range bins, 0
// elsewhere (forces outside the FRF range are zero by definition, docs/diagnosis.md).
void BlockProcessor::Impl::Contribution(const Shape& s, std::size_t path, std::size_t channel,
                                        std::span<Cd> out) const noexcept {
  std::fill(out.begin(), out.end(), Cd{});
  const auto p = static_cast<Eigen::Index>(path);
  const auto c = static_cast<Eigen::Index>(channel);
  for (Eigen::Index i = 0; i < s.map.frf.bins(); ++i) {
    out[s.map.first_bin + static_cast<std::size_t>(i)] =
        s.map.frf.at[static_cast<std::size_t>(i)](c, p) * s.forces(p, i);
  }
}

// Kurtogram band -> band-pass -> SES -> indicators of every shaft.
void BlockProcessor::Impl::Envelope(Shape& s, std::span<const double> signal, double speed_hz,
                                    BlockEnvelopeBand& band, std::span<double> indicator_sum,
                                    std::span<BlockShaftIndicator> shafts,
                                    bool reconstructed) noexcept {
  band = BlockEnvelopeBand{};
  const double nyquist = setup.options.sample_rate_hz / 2.0;
  double lo = band_lo;
  double hi = std::min(band_hi, nyquist);
  auto k = s.kurtogram->Process(signal);
  if (k.ok()) {
    const KurtogramBand& kb = k.value();
    band.kurtosis = kb.kurtosis;
    band.level = kb.node.level;
    band.significant = kb.significant;
    if (kb.significant) {
      lo = kb.low_hz;
      hi = kb.high_hz;
    }
  }
  band.centre_hz = 0.5 * (lo + hi);
  band.width_hz = hi - lo;
  const bool filtered = s.band_pass->Process(signal, lo, hi, s.filtered).ok();
  const bool have_ses = filtered && s.ses->Process(s.filtered, s.ses_buf).ok();
  HarmonicSearch search;
  search.relative_tolerance = setup.options.harmonic_tolerance;
  for (std::size_t sh = 0; sh < shafts.size(); ++sh) {
    BlockShaftIndicator& out = shafts[sh];
    const double fc = shaft_ratio[sh] * speed_hz;
    auto& harmonics = reconstructed ? out.reconstructed_harmonics : out.raw_harmonics;
    double& value = reconstructed ? out.reconstructed : out.raw;
    harmonics.fill(0.0);
    value = 0.0;
    if (have_ses && fc > 0.0) {
      auto ind = ComputeHarmonicIndicator(s.ses_buf, s.bin_hz, fc, search);
      if (ind.ok()) {
        for (std::size_t h = 0; h < harmonics.size(); ++h) {
          harmonics[h] = ind->harmonics[h].amplitude;
        }
        value = ind->sum;
      }
    }
    indicator_sum[sh] = value;
  }
}

BlockProcessor::BlockProcessor(std::unique_ptr<Impl> impl) noexcept : impl_(std::move(impl)) {}
BlockProcessor::BlockProcessor(BlockProcessor&&) noexcept = default;
BlockProcessor& BlockProcessor::operator=(BlockProcessor&&) noexcept = default;
BlockProcessor::~BlockProcessor() = default;

Result<BlockProcessor> BlockProcessor::Create(MachineSetup setup) {
  auto impl = std::make_unique<Impl>();
  const AnalysisOptions& o = setup.options;
  const FrfSet& set = setup.frf_set;
  const std::string& id = setup.machine_id;
  if (id.empty()) return Error{"machine setup: machine_id is empty"};
  const std::string at = "machine '" + id + "': ";
  if (!(o.sample_rate_hz > 0.0) || !std::isfinite(o.sample_rate_hz)) {
    return Error{at + fmt::format("options.sample_rate_hz must be > 0, got {}", o.sample_rate_hz)};
  }
  if (!(o.sample_rate_tolerance >= 0.0) || o.sample_rate_tolerance > 0.1) {
    return Error{at + "options.sample_rate_tolerance must be in [0, 0.1]"};
  }
  if (o.min_samples_per_channel < 64 || o.min_samples_per_channel > o.max_samples_per_channel) {
    return Error{at + fmt::format("options.min_samples_per_channel ({}) must be >= 64 and <= "
                                  "max_samples_per_channel ({})",
                                  o.min_samples_per_channel, o.max_samples_per_channel)};
  }
  if (!(o.nominal_speed_hz >= 0.0) || !std::isfinite(o.nominal_speed_hz)) {
    return Error{at + "options.nominal_speed_hz must be finite and >= 0"};
  }
  if (o.speed_search_lo_hz < 0.0 || o.speed_search_hi_hz < 0.0 ||
      (o.speed_search_hi_hz > 0.0 && o.speed_search_hi_hz <= o.speed_search_lo_hz)) {
    return Error{at + "options.speed_search_lo_hz/hi_hz must satisfy 0 <= lo < hi"};
  }
  if (o.sideband_orders < 1 || o.sideband_orders > 50) {
    return Error{at + "options.sideband_orders must be in 1..50"};
  }
  if (!(o.harmonic_tolerance >= 0.0) || o.harmonic_tolerance > 0.2) {
    return Error{at + "options.harmonic_tolerance must be in [0, 0.2]"};
  }
  if (!(o.alarm_factor >= 1.0)) return Error{at + "options.alarm_factor must be >= 1"};
  if (auto st = ValidateIdentificationOptions(o.identification); !st) {
    return Error{at + "options.identification: " + st.error()};
  }
  const FrfMatrix& h = set.decoupled;
  if (h.bins() == 0 || h.at.empty()) {
    return Error{at + "frf_set has no decoupled FRF matrix (run `gearpath decouple` first)"};
  }
  if (static_cast<std::size_t>(h.outputs()) != set.channels.size() ||
      static_cast<std::size_t>(h.inputs()) != set.paths.size()) {
    return Error{at + fmt::format("frf_set.decoupled is {}x{} but the set lists {} channels and "
                                  "{} paths",
                                  h.outputs(), h.inputs(), set.channels.size(), set.paths.size())};
  }
  impl->channels = set.channels.size();
  impl->paths = set.paths.size();

  // Channel mapping: block channel c -> FRF row with the same (sensor, axis).
  std::vector<ExpectedChannel> frf_channels;
  for (std::size_t r = 0; r < set.channels.size(); ++r) {
    const auto axis = ParseAxis(set.channels[r].axis);
    if (!axis) {
      return Error{at + fmt::format("frf_set.channels[{}].axis '{}' is not x, y or z", r,
                                    set.channels[r].axis)};
    }
    frf_channels.push_back({set.channels[r].sensor, *axis});
  }
  if (setup.block_channels.empty()) setup.block_channels = frf_channels;
  if (setup.block_channels.size() != frf_channels.size()) {
    return Error{at + fmt::format("block_channels lists {} channels but the FRF set has {} rows",
                                  setup.block_channels.size(), frf_channels.size())};
  }
  std::vector<bool> row_used(frf_channels.size(), false);
  for (std::size_t c = 0; c < setup.block_channels.size(); ++c) {
    const ExpectedChannel& bc = setup.block_channels[c];
    int row = -1;
    for (std::size_t r = 0; r < frf_channels.size(); ++r) {
      if (frf_channels[r].sensor == bc.sensor && frf_channels[r].axis == bc.axis) {
        row = static_cast<int>(r);
      }
    }
    if (row < 0) {
      return Error{at + fmt::format("block_channels[{}] ({}/{}) has no row in the FRF set", c,
                                    bc.sensor, AxisName(bc.axis))};
    }
    if (row_used[static_cast<std::size_t>(row)]) {
      return Error{at + fmt::format("block_channels[{}] ({}/{}) is listed twice", c, bc.sensor,
                                    AxisName(bc.axis))};
    }
    row_used[static_cast<std::size_t>(row)] = true;
    impl->block_to_row.push_back(row);
  }
  if (o.indicator_channel >= static_cast<int>(impl->channels) || o.indicator_channel < -1) {
    return Error{at + fmt::format("options.indicator_channel {} is not an FRF row (0..{}) or -1",
                                  o.indicator_channel, impl->channels - 1)};
  }

  // Train kinematics and the verdict's topology.
  auto ratios = ShaftRateRatios(setup.train);
  if (!ratios) return Error{at + ratios.error()};
  impl->shaft_ratio = ratios.value();
  impl->max_ratio = *std::max_element(impl->shaft_ratio.begin(), impl->shaft_ratio.end());
  const TrainLayout& train = setup.train;
  VerdictTopology& t = impl->topology;
  t.rate_tolerance = std::max(o.harmonic_tolerance, 1e-6);
  for (const TrainShaft& s : train.shafts) t.shaft_names.push_back(s.name);
  t.shaft_ratio = impl->shaft_ratio;
  t.gear_mesh.assign(train.gears.size(), -1);
  for (const TrainGear& g : train.gears) {
    t.gear_names.push_back(g.name);
    t.gear_shaft.push_back(g.shaft);
  }
  if (train.meshes.size() > 32) return Error{at + "train has more than 32 meshes"};
  for (std::size_t m = 0; m < train.meshes.size(); ++m) {
    const TrainGear& a = train.gears[static_cast<std::size_t>(train.meshes[m].gear_a)];
    const TrainGear& b = train.gears[static_cast<std::size_t>(train.meshes[m].gear_b)];
    for (int gi : {train.meshes[m].gear_a, train.meshes[m].gear_b}) {
      if (t.gear_mesh[static_cast<std::size_t>(gi)] >= 0) {
        return Error{at + fmt::format("gear '{}' is in two meshes; the verdict needs one mesh per "
                                      "gear (an idler must be modelled as two gears)",
                                      train.gears[static_cast<std::size_t>(gi)].name)};
      }
      t.gear_mesh[static_cast<std::size_t>(gi)] = static_cast<int>(m);
    }
    t.mesh_names.push_back(a.name + "-" + b.name);
    MeshLines lines;
    lines.mesh_hz = a.teeth * impl->shaft_ratio[static_cast<std::size_t>(a.shaft)];
    lines.shaft_hz = {impl->shaft_ratio[static_cast<std::size_t>(a.shaft)],
                      impl->shaft_ratio[static_cast<std::size_t>(b.shaft)]};
    impl->unit_meshes.push_back(lines);
    impl->mesh_orders.push_back(lines.mesh_hz);
  }
  for (std::size_t p = 0; p < set.paths.size(); ++p) {
    std::vector<int> seen;
    for (const std::string& gear : set.paths[p].gears) {
      const auto it = std::find(t.gear_names.begin(), t.gear_names.end(), gear);
      if (it == t.gear_names.end()) {
        return Error{at + fmt::format("frf_set.paths[{}] ({}) names gear '{}', which is not in "
                                      "the gear train",
                                      p, set.paths[p].name, gear)};
      }
      const int mesh = t.gear_mesh[static_cast<std::size_t>(it - t.gear_names.begin())];
      if (mesh >= 0 && std::find(seen.begin(), seen.end(), mesh) == seen.end()) {
        seen.push_back(mesh);
      }
    }
    t.path_meshes.push_back(std::move(seen));
    t.path_names.push_back(set.paths[p].name);
  }

  // Speed bounds: the search range and the highest speed the envelope band must serve.
  double lo = o.speed_search_lo_hz;
  double hi = o.speed_search_hi_hz;
  if (hi <= 0.0) {
    lo = o.nominal_speed_hz > 0.0 ? 0.8 * o.nominal_speed_hz : 1.0;
    hi = o.nominal_speed_hz > 0.0 ? 1.2 * o.nominal_speed_hz : 100.0;
  }
  impl->setup.options.speed_search_lo_hz = lo;
  impl->setup.options.speed_search_hi_hz = hi;
  impl->max_speed_hz = std::max(hi, o.nominal_speed_hz);

  // Analysis band: the FRF range, narrowed by the options.
  impl->band_lo = std::max(o.analysis_band_lo_hz, h.frequency_hz[0]);
  impl->band_hi = o.analysis_band_hi_hz > 0.0
                      ? std::min(o.analysis_band_hi_hz, h.frequency_hz[h.bins() - 1])
                      : h.frequency_hz[h.bins() - 1];
  impl->band_hi = std::min(impl->band_hi, o.sample_rate_hz / 2.0);
  if (!(impl->band_hi > impl->band_lo)) {
    return Error{at + fmt::format("analysis band {}..{} Hz is empty inside the FRF range "
                                  "{}..{} Hz",
                                  o.analysis_band_lo_hz, o.analysis_band_hi_hz, h.frequency_hz[0],
                                  h.frequency_hz[h.bins() - 1])};
  }

  // Thresholds: configured (both lists) or learned.
  const std::size_t shafts = train.shafts.size();
  if (!o.raw_thresholds.empty() || !o.reconstructed_thresholds.empty()) {
    if (o.raw_thresholds.size() != shafts || o.reconstructed_thresholds.size() != shafts) {
      return Error{at + fmt::format("options.raw_thresholds and reconstructed_thresholds need {} "
                                    "values each (one per shaft), got {} and {}",
                                    shafts, o.raw_thresholds.size(),
                                    o.reconstructed_thresholds.size())};
    }
    std::vector<double> all(o.raw_thresholds);
    all.insert(all.end(), o.reconstructed_thresholds.begin(), o.reconstructed_thresholds.end());
    auto b = HealthyBaseline::Configured(all);
    if (!b) return Error{at + "options thresholds: " + b.error()};
    impl->baseline.emplace(std::move(b.value()));
  } else {
    BaselineOptions bo;
    bo.blocks = o.baseline_blocks;
    bo.k_sigma = o.baseline_k_sigma;
    auto b = HealthyBaseline::Create(2 * shafts, bo);
    if (!b) return Error{at + "options.baseline: " + b.error()};
    impl->baseline.emplace(std::move(b.value()));
  }

  impl->expect.machine_id = id;
  impl->expect.channels = setup.block_channels;
  impl->expect.sample_rate_hz = o.sample_rate_hz;
  impl->expect.sample_rate_tolerance = o.sample_rate_tolerance;
  impl->expect.min_samples_per_channel = o.min_samples_per_channel;
  impl->expect.max_samples_per_channel = o.max_samples_per_channel;
  impl->expect.max_total_samples =
      static_cast<std::size_t>(o.max_samples_per_channel) * impl->channels;

  impl->path_energy.assign(impl->paths, 0.0);
  impl->path_share.assign(impl->paths, 0.0);
  impl->path_criterion.assign(impl->paths, 0.0);
  impl->criterion_healthy.assign(impl->paths, 0.0);
  impl->path_force.assign(impl->paths, 0.0);
  impl->path_force_healthy.assign(impl->paths, 0.0);
  impl->mesh_evidence.assign(impl->unit_meshes.size(), 0.0);
  impl->indicators.assign(2 * shafts, 0.0);
  impl->raw_thr.assign(shafts, 0.0);
  impl->rec_thr.assign(shafts, 0.0);
  impl->meshes_now = impl->unit_meshes;
  impl->shapes.reserve(kMaxShapes);

  const double keep_lo = impl->setup.options.speed_search_lo_hz;
  const double keep_hi = impl->setup.options.speed_search_hi_hz;
  impl->setup = std::move(setup);
  impl->setup.options.speed_search_lo_hz = keep_lo;
  impl->setup.options.speed_search_hi_hz = keep_hi;
  return BlockProcessor(std::move(impl));
}

Status BlockProcessor::Prepare(std::uint32_t samples_per_channel) {
  if (samples_per_channel < impl_->expect.min_samples_per_channel ||
      samples_per_channel > impl_->expect.max_samples_per_channel) {
    return Error{fmt::format("machine '{}': {} samples per channel is outside {}..{}",
                             impl_->setup.machine_id, samples_per_channel,
                             impl_->expect.min_samples_per_channel,
                             impl_->expect.max_samples_per_channel)};
  }
  try {
    return impl_->Configure(samples_per_channel);
  } catch (const std::exception& e) {
    return Error{fmt::format("machine '{}': configuring for {} samples failed: {}",
                             impl_->setup.machine_id, samples_per_channel, e.what())};
  }
}

ProcessOutcome BlockProcessor::Process(const AccelBlockView& block, BlockResult& out) noexcept {
  ProcessOutcome outcome;
  Impl& im = *impl_;
  outcome.reason = ValidateBlock(block, im.expect, outcome.message);
  if (!outcome.accepted()) return outcome;

  const std::size_t n = block.samples_per_channel;
  Shape* shape = im.FindShape(n);
  if (shape == nullptr) {
    Status st = Status::Ok();
    try {
      st = im.Configure(n);
    } catch (const std::exception& e) {
      outcome.reason = RejectReason::kNotConfigured;
      outcome.message.Format("configuring for %zu samples per channel failed: %s", n, e.what());
      return outcome;
    }
    if (!st) {
      outcome.reason = RejectReason::kNotConfigured;
      outcome.message.Format("cannot configure for %zu samples per channel: %s", n,
                             st.error().c_str());
      return outcome;
    }
    shape = im.FindShape(n);
  }
  const SequenceTracker::Verdict seq =
      im.tracker.Observe(block.sequence, im.expect.machine_id, outcome.message);
  if (seq.reason != RejectReason::kNone) {
    outcome.reason = seq.reason;
    return outcome;
  }
  Shape& s = *shape;
  s.last_used = ++im.use_counter;
  const AnalysisOptions& o = im.setup.options;
  const std::size_t C = im.channels;
  const std::size_t P = im.paths;
  const std::size_t S = im.shaft_ratio.size();

  // Result bookkeeping (vectors keep their capacity across blocks).
  out.sequence = block.sequence;
  out.t0_ns = block.t0_ns;
  out.sequence_gap = seq.gap;
  out.sequence_restarted = seq.restarted;
  out.paths.resize(P);
  out.shafts.resize(S);
  if (out.verdict.candidates.capacity() < im.topology.gear_names.size()) {
    im.topology.Reserve(out.verdict);  // first use of this BlockResult only
  }
  out.criterion = o.criterion;
  out.analysis_band_lo_hz = im.band_lo;
  out.analysis_band_hi_hz = im.band_hi;

  // 1. Samples to double, FRF row order; spectra.
  for (std::size_t c = 0; c < C; ++c) {
    const auto src = block.channel(c);
    double* dst = s.time.data() + static_cast<std::size_t>(im.block_to_row[c]) * n;
    for (std::size_t i = 0; i < n; ++i) dst[i] = static_cast<double>(src[i]);
  }
  if (!s.spectrum->Process(s.time, s.spec).ok()) {
    outcome.reason = RejectReason::kNonFinite;
    outcome.message.Assign("spectrum rejected the block");
    return outcome;
  }

  // 2. Speed: block, else configuration, else mesh-frequency tracking.
  double speed = 0.0;
  SpeedSource source = SpeedSource::kUnknown;
  if (block.speed_hz > 0.0 && std::isfinite(block.speed_hz)) {
    speed = block.speed_hz;
    source = block.speed_source == SpeedSource::kUnknown ? SpeedSource::kAcquisition
                                                         : block.speed_source;
  } else if (o.nominal_speed_hz > 0.0) {
    speed = o.nominal_speed_hz;
    source = SpeedSource::kConfiguration;
  } else {
    for (std::size_t k = 0; k < s.bins; ++k) {
      double p = 0.0;
      for (std::size_t c = 0; c < C; ++c) p += std::norm(s.spec[c * s.bins + k]);
      s.amplitude[k] = std::sqrt(p);
    }
    SpeedSearch search;
    search.lo_hz = o.speed_search_lo_hz;
    search.hi_hz = o.speed_search_hi_hz;
    const SpeedEstimate est =
        EstimateSpeedFromMeshes(s.amplitude, s.bin_hz, im.mesh_orders, search);
    if (est.found) {
      speed = est.speed_hz;
      source = SpeedSource::kEstimated;
    }
  }
  out.speed_hz = speed;
  out.speed_source = source;

  // 3. Bearing forces per in-range bin.
  const Eigen::Index in_range = s.map.frf.bins();
  double res_num = 0.0;
  double res_den = 0.0;
  std::size_t used = 0;
  double cond_max = 0.0;
  for (Eigen::Index i = 0; i < in_range; ++i) {
    const std::size_t k = s.map.first_bin + static_cast<std::size_t>(i);
    double x2 = 0.0;
    for (std::size_t c = 0; c < C; ++c) {
      s.x[static_cast<Eigen::Index>(c)] = s.spec[c * s.bins + k];
      x2 += std::norm(s.spec[c * s.bins + k]);
    }
    BinFigures& fig = s.figures[static_cast<std::size_t>(i)];
    const IdentifyStatus st = s.op->Identify(i, s.x, s.forces.col(i), &fig);
    if (st != IdentifyStatus::kOk) {
      s.forces.col(i).setZero();
      continue;
    }
    if (s.band_mask[k]) {
      res_num += fig.relative_residual * fig.relative_residual * x2;
      res_den += x2;
    }
    if (std::isfinite(fig.parameter) && std::isfinite(fig.condition_weighted)) {
      s.work_a[used] = fig.parameter;
      s.work_b[used] = fig.condition_weighted;
      cond_max = std::max(cond_max, fig.condition_weighted);
      ++used;
    }
  }
  BlockRegularisation& reg = out.regularisation;
  reg.alpha_median = MedianInPlace(s.work_a, used);
  reg.condition_median = MedianInPlace(s.work_b, used);
  reg.condition_max = cond_max;
  reg.relative_residual = res_den > 0.0 ? std::sqrt(res_num / res_den) : 0.0;
  reg.bins_used = static_cast<std::uint32_t>(in_range);
  reg.bins_outside_frf = static_cast<std::uint32_t>(s.map.bins_outside);

  // 4. Path contributions: energy in the analysis band and on the fault sidebands.
  for (std::size_t m = 0; m < im.unit_meshes.size(); ++m) {
    im.meshes_now[m].mesh_hz = im.unit_meshes[m].mesh_hz * speed;
    im.meshes_now[m].shaft_hz = {im.unit_meshes[m].shaft_hz[0] * speed,
                                 im.unit_meshes[m].shaft_hz[1] * speed};
  }
  if (speed > 0.0) {
    BuildSidebandMask(s.bin_hz, im.meshes_now, o.sideband_orders, im.band_lo, im.band_hi, 1.0,
                      s.sideband_mask);
    BuildMeshHarmonicMask(s.bin_hz, im.meshes_now, 1.0, s.mesh_mask);
  } else {
    std::fill(s.sideband_mask.begin(), s.sideband_mask.end(), std::uint8_t{0});
    std::fill(s.mesh_mask.begin(), s.mesh_mask.end(), std::uint8_t{0});
  }
  for (std::size_t p = 0; p < P; ++p) {
    double band = 0.0;
    double side = 0.0;
    double force = 0.0;
    const auto pi = static_cast<Eigen::Index>(p);
    for (Eigen::Index i = 0; i < in_range; ++i) {
      const std::size_t k = s.map.first_bin + static_cast<std::size_t>(i);
      if (!s.band_mask[k]) continue;
      const Eigen::MatrixXcd& hk = s.map.frf.at[static_cast<std::size_t>(i)];
      const Cd f = s.forces(pi, i);
      double e = 0.0;
      for (std::size_t c = 0; c < C; ++c) e += std::norm(hk(static_cast<Eigen::Index>(c), pi) * f);
      band += e;
      if (s.sideband_mask[k]) {
        side += e;
        force += std::norm(f);
      }
    }
    im.path_force[p] = force;
    im.path_energy[p] = band;
    im.path_criterion[p] =
        o.criterion == AnalysisOptions::DominantCriterion::kBandEnergy ? band : side;
  }
  EnergyShares(im.path_energy, im.path_share);

  // Indicator channel for a path: the FRF row where its contribution is largest.
  const auto best_channel = [&](std::size_t p) {
    if (o.indicator_channel >= 0) return static_cast<std::size_t>(o.indicator_channel);
    std::size_t best = 0;
    double best_e = -1.0;
    const auto pi = static_cast<Eigen::Index>(p);
    for (std::size_t c = 0; c < C; ++c) {
      double e = 0.0;
      for (Eigen::Index i = 0; i < in_range; ++i) {
        if (!s.band_mask[s.map.first_bin + static_cast<std::size_t>(i)]) continue;
        e += std::norm(s.map.frf.at[static_cast<std::size_t>(i)](static_cast<Eigen::Index>(c), pi) *
                       s.forces(pi, i));
      }
      if (e > best_e) {
        best_e = e;
        best = c;
      }
    }
    return best;
  };
  // Time signal of a spectrum with the mesh tones comb-removed (when enabled).
  const auto to_time = [&](std::span<double> dst) {
    if (o.remove_mesh_tones) {
      for (std::size_t k = 0; k < s.bins; ++k) {
        if (s.mesh_mask[k]) s.one_spec[k] = Cd{};
      }
    }
    (void)s.inverse->Process(s.one_spec, dst);
  };

  if (o.criterion == AnalysisOptions::DominantCriterion::kIndicator && speed > 0.0) {
    // Each path's own fault indicator (max over shafts) at its best channel.
    BlockEnvelopeBand scratch_band;
    for (std::size_t p = 0; p < P; ++p) {
      im.Contribution(s, p, best_channel(p), s.one_spec);
      to_time(s.rec_signal);
      im.Envelope(s, s.rec_signal, speed, scratch_band,
                  std::span<double>(im.indicators).subspan(S, S), out.shafts, true);
      double best = 0.0;
      for (std::size_t sh = 0; sh < S; ++sh) best = std::max(best, im.indicators[S + sh]);
      im.path_criterion[p] = best;
    }
  }
  // Excess over the healthy level (see AnalysisOptions::criterion_over_baseline).
  const bool baseline_learned = im.baseline->learned();
  if (o.criterion_over_baseline && !baseline_learned && speed > 0.0) {
    ++im.criterion_blocks;
    for (std::size_t p = 0; p < P; ++p) {
      im.criterion_healthy[p] +=
          (im.path_criterion[p] - im.criterion_healthy[p]) / im.criterion_blocks;
    }
  } else if (o.criterion_over_baseline && im.criterion_blocks > 0) {
    bool any = false;
    for (std::size_t p = 0; p < P; ++p) any = any || im.path_criterion[p] > im.criterion_healthy[p];
    if (any) {
      for (std::size_t p = 0; p < P; ++p) {
        im.path_criterion[p] = std::max(0.0, im.path_criterion[p] - im.criterion_healthy[p]);
      }
    }
  }
  // Mesh evidence: the bearing FORCES' energy on the sideband lines, in excess of the healthy
  // level, split over the meshes each path sees. Forces locate the source; contributions
  // also weigh the housing's transfer, which favours whichever seat is most mobile.
  if (!baseline_learned && speed > 0.0) {
    ++im.path_force_blocks;
    for (std::size_t p = 0; p < P; ++p) {
      im.path_force_healthy[p] +=
          (im.path_force[p] - im.path_force_healthy[p]) / im.path_force_blocks;
    }
  }
  std::fill(im.mesh_evidence.begin(), im.mesh_evidence.end(), 0.0);
  if (baseline_learned && im.path_force_blocks > 0) {
    for (std::size_t p = 0; p < P; ++p) {
      const auto& seen = im.topology.path_meshes[p];
      if (seen.empty()) continue;
      const double excess = std::max(0.0, im.path_force[p] - im.path_force_healthy[p]);
      for (int m : seen) {
        im.mesh_evidence[static_cast<std::size_t>(m)] += excess / static_cast<double>(seen.size());
      }
    }
  }
  const int dominant = SelectDominantPath(im.path_criterion);
  out.dominant_path = dominant;
  out.dominant_path_name =
      dominant >= 0
          ? std::string_view(im.setup.frf_set.paths[static_cast<std::size_t>(dominant)].name)
          : std::string_view{};
  for (std::size_t p = 0; p < P; ++p) {
    out.paths[p].name = im.setup.frf_set.paths[p].name;
    out.paths[p].bearing = im.setup.frf_set.paths[p].bearing;
    out.paths[p].energy = im.path_energy[p];
    out.paths[p].share = im.path_share[p];
    out.paths[p].criterion = im.path_criterion[p];
  }

  // 5. Dominant path's contribution in time, at every channel (kept for the accessor).
  if (dominant >= 0) {
    for (std::size_t c = 0; c < C; ++c) {
      im.Contribution(s, static_cast<std::size_t>(dominant), c, s.one_spec);
      (void)s.inverse->Process(s.one_spec, std::span<double>(s.dominant_time).subspan(c * n, n));
    }
  } else {
    std::fill(s.dominant_time.begin(), s.dominant_time.end(), 0.0);
  }
  im.last_shape = &s;
  im.last_dominant = dominant;
  im.has_last = true;
  const std::size_t channel =
      dominant >= 0
          ? best_channel(static_cast<std::size_t>(dominant))
          : (o.indicator_channel >= 0 ? static_cast<std::size_t>(o.indicator_channel) : 0);
  out.indicator_channel = static_cast<int>(channel);

  // 6-8. Kurtogram band, band-pass, SES, indicators: raw measured signal and reconstructed
  // dominant-path signal at the indicator channel, mesh tones removed from both alike.
  std::copy_n(s.spec.begin() + static_cast<std::ptrdiff_t>(channel * s.bins), s.bins,
              s.one_spec.begin());
  to_time(s.raw_signal);
  if (dominant >= 0) {
    im.Contribution(s, static_cast<std::size_t>(dominant), channel, s.one_spec);
  } else {
    std::fill(s.one_spec.begin(), s.one_spec.end(), Cd{});
  }
  to_time(s.rec_signal);
  std::span<double> raw_ind(im.indicators.data(), S);
  std::span<double> rec_ind(im.indicators.data() + S, S);
  im.Envelope(s, s.raw_signal, speed, out.raw_band, raw_ind, out.shafts, false);
  im.Envelope(s, s.rec_signal, speed, out.reconstructed_band, rec_ind, out.shafts, true);

  // 9. Baseline, thresholds, verdict.
  HealthyBaseline& baseline = *im.baseline;
  const bool learning = !baseline.learned();
  if (learning && speed > 0.0) baseline.Add(im.indicators);
  for (std::size_t sh = 0; sh < S; ++sh) {
    BlockShaftIndicator& si = out.shafts[sh];
    si.shaft = im.topology.shaft_names[sh];
    si.characteristic_hz = im.shaft_ratio[sh] * speed;
    const auto e = EnhancementPercent(si.reconstructed, si.raw);
    si.enhancement_percent = e.ok() ? e.value() : 0.0;
    im.raw_thr[sh] = learning ? 0.0 : baseline.thresholds()[sh];
    im.rec_thr[sh] = learning ? 0.0 : baseline.thresholds()[S + sh];
    si.raw_threshold = im.raw_thr[sh];
    si.reconstructed_threshold = im.rec_thr[sh];
  }
  VerdictInputs vin;
  vin.input_speed_hz = speed;
  vin.raw = raw_ind;
  vin.reconstructed = rec_ind;
  vin.raw_threshold = im.raw_thr;
  vin.reconstructed_threshold = im.rec_thr;
  vin.path_criterion = im.path_criterion;
  if (speed > 0.0) vin.mesh_evidence = im.mesh_evidence;
  vin.dominant_path = dominant;
  vin.alarm_factor = o.alarm_factor;
  vin.learning = learning;
  if (speed > 0.0) {
    DecideGearVerdict(im.topology, vin, out.verdict);
  } else {
    DecideGearVerdict(im.topology, vin, out.verdict);
    out.verdict.state = learning ? FaultState::kLearning : FaultState::kNoFault;
    out.verdict.confidence = 0.0;
    out.verdict.reason.Assign(
        "input speed unknown (not in the block, not configured, no mesh lines to track): "
        "indicators not computed");
  }
  return outcome;
}

std::span<const double> BlockProcessor::DominantPathSignal(std::size_t channel) const noexcept {
  const Impl& im = *impl_;
  if (!im.has_last || im.last_shape == nullptr || im.last_dominant < 0 || channel >= im.channels) {
    return {};
  }
  const Shape& s = *im.last_shape;
  return std::span<const double>(s.dominant_time).subspan(channel * s.n, s.n);
}

bool BlockProcessor::PathSignal(std::size_t path, std::size_t channel,
                                std::span<double> out) noexcept {
  Impl& im = *impl_;
  if (!im.has_last || im.last_shape == nullptr || path >= im.paths || channel >= im.channels) {
    return false;
  }
  Shape& s = *im.last_shape;
  if (out.size() != s.n) return false;
  im.Contribution(s, path, channel, s.one_spec);
  return s.inverse->Process(s.one_spec, out).ok();
}

int BlockProcessor::baseline_blocks_learned() const noexcept {
  return impl_->baseline->blocks_seen();
}
int BlockProcessor::baseline_blocks_needed() const noexcept {
  return impl_->baseline->blocks_needed();
}
void BlockProcessor::ResetBaseline() noexcept {
  impl_->baseline->Reset();
  if (!impl_->baseline->learned()) {
    impl_->criterion_blocks = 0;
    std::fill(impl_->criterion_healthy.begin(), impl_->criterion_healthy.end(), 0.0);
    impl_->path_force_blocks = 0;
    std::fill(impl_->path_force_healthy.begin(), impl_->path_force_healthy.end(), 0.0);
  }
}
const MachineSetup& BlockProcessor::setup() const noexcept { return impl_->setup; }
const BlockExpectations& BlockProcessor::expectations() const noexcept { return impl_->expect; }

}  // namespace gearpath
