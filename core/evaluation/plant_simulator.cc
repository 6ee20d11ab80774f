#include "core/evaluation/plant_simulator.h"

#include <fmt/format.h>

#include <cmath>
#include <complex>
#include <numbers>

#include "core/simulation/deterministic_rng.h"

namespace gearpath {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;
constexpr std::uint64_t kSourceStream = 201;         // unmodelled sources, fixed per run
constexpr std::uint64_t kNoiseStreamBase = 1 << 20;  // + block index
constexpr std::uint64_t kBurstStreamBase = 1 << 21;  // + block index
// Irrational multiples of the pump rate for the three tones.
const double kToneMultiples[] = {7.0 * std::numbers::sqrt2, 13.0 * std::numbers::sqrt3,
                                 9.0 * std::numbers::pi};
constexpr double kToneModulation = 0.3;

double UniformIn(DeterministicRng& rng, double lo, double hi) {
  return lo + (hi - lo) * rng.Uniform();
}

}  // namespace

Result<PlantSimulator> PlantSimulator::Create(std::shared_ptr<const PlantDynamics> dynamics,
                                              std::vector<ChannelInfo> channels,
                                              PlantExcitation excitation,
                                              const PlantSimulatorConfig& config) {
  const PlantSimulatorConfig& c = config;
  if (dynamics == nullptr) return Error{"plant simulator: dynamics is null"};
  if (!(c.sample_rate_hz > 0.0) || !std::isfinite(c.sample_rate_hz)) {
    return Error{fmt::format("plant simulator: sample_rate_hz must be finite and > 0, got {}",
                             c.sample_rate_hz)};
  }
  if (!(c.input_speed_hz > 0.0) || !std::isfinite(c.input_speed_hz)) {
    return Error{fmt::format("plant simulator: input_speed_hz must be finite and > 0, got {}",
                             c.input_speed_hz)};
  }
  if (c.block_length < 16) {
    return Error{
        fmt::format("plant simulator: block_length must be >= 16, got {}", c.block_length)};
  }
  if (c.segment_factor < 2) {
    return Error{
        fmt::format("plant simulator: segment_factor must be >= 2, got {}", c.segment_factor)};
  }
  if (c.te_oversampling < 1 || c.te_oversampling > 16) {
    return Error{fmt::format("plant simulator: te_oversampling must be in [1, 16], got {}",
                             c.te_oversampling)};
  }
  if (!(c.noise_relative >= 0.0) || !std::isfinite(c.noise_relative)) {
    return Error{fmt::format("plant simulator: noise_relative must be finite and >= 0, got {}",
                             c.noise_relative)};
  }
  if (!(c.drift_relative >= 0.0 && c.drift_relative < 0.1)) {
    return Error{fmt::format("plant simulator: drift_relative must be in [0, 0.1), got {}",
                             c.drift_relative)};
  }
  if (!(c.tone_level >= 0.0) || !(c.burst_level >= 0.0) || !(c.burst_rate_hz >= 0.0)) {
    return Error{"plant simulator: tone_level, burst_level and burst_rate_hz must be >= 0"};
  }
  if (static_cast<int>(channels.size()) != dynamics->channel_count()) {
    return Error{fmt::format("plant simulator: {} channels named but the dynamics has {}",
                             channels.size(), dynamics->channel_count())};
  }
  if (excitation.stage_count() != dynamics->stage_count()) {
    return Error{fmt::format("plant simulator: the excitation has {} stages but the dynamics {}",
                             excitation.stage_count(), dynamics->stage_count())};
  }

  PlantSimulator sim(std::move(excitation));
  sim.config_ = c;
  sim.dynamics_ = std::move(dynamics);
  sim.channels_ = std::move(channels);
  sim.segment_ = static_cast<std::size_t>(c.segment_factor) * c.block_length;
  const std::size_t s = sim.segment_;
  const Eigen::Index bins = static_cast<Eigen::Index>(s / 2 + 1);
  // Transfer on the inner bins only (DC and Nyquist are dropped).
  Eigen::VectorXd f(bins - 2);
  for (Eigen::Index k = 1; k + 1 < bins; ++k) {
    f[k - 1] = static_cast<double>(k) * c.sample_rate_hz / static_cast<double>(s);
  }
  Result<FrfMatrix> t = sim.dynamics_->TeTransfer(f);
  if (!t) return Error{"plant simulator: " + t.error()};
  sim.transfer_ = std::move(t).value();

  const double healthy_top = sim.excitation_.HealthyBandwidthOrder() * c.input_speed_hz *
                             (1.0 + (c.speed_drift ? c.drift_relative : 0.0));
  if (healthy_top >= 0.5 * c.sample_rate_hz) {
    return Error{fmt::format(
        "plant simulator: the healthy TE reaches {:.0f} Hz at input_speed_hz {}, over half the "
        "sample_rate_hz {}; lower the speed or the mesh harmonics",
        healthy_top, c.input_speed_hz, c.sample_rate_hz)};
  }
  Result<FftPlan> fwd = FftPlan::Create(FftKind::kRealToComplex, s);
  if (!fwd) return Error{"plant simulator: " + fwd.error()};
  Result<FftPlan> fwd_fault = FftPlan::Create(FftKind::kRealToComplex, s * c.te_oversampling);
  if (!fwd_fault) return Error{"plant simulator: " + fwd_fault.error()};
  sim.forward_fault_ = std::make_unique<FftPlan>(std::move(fwd_fault).value());
  Result<FftPlan> bwd = FftPlan::Create(FftKind::kComplexToReal, s);
  if (!bwd) return Error{"plant simulator: " + bwd.error()};
  sim.forward_ = std::make_unique<FftPlan>(std::move(fwd).value());
  sim.backward_ = std::make_unique<FftPlan>(std::move(bwd).value());
  sim.te_spectrum_.resize(bins, sim.excitation_.stage_count());

  const Eigen::Index nc = static_cast<Eigen::Index>(sim.channels_.size());
  DeterministicRng rng(c.seed, kSourceStream);
  sim.pump_hz_ = UniformIn(rng, 17.0, 31.0);
  sim.tone_gain_.resize(nc, 3);
  for (double m : kToneMultiples) {
    sim.tone_hz_.push_back(m * sim.pump_hz_);
    sim.tone_phase_.push_back(kTwoPi * rng.Uniform());
  }
  for (Eigen::Index ch = 0; ch < nc; ++ch) {
    for (Eigen::Index k = 0; k < 3; ++k) sim.tone_gain_(ch, k) = UniformIn(rng, 0.3, 1.0);
  }
  sim.burst_gain_.resize(nc);
  for (Eigen::Index ch = 0; ch < nc; ++ch) sim.burst_gain_[ch] = UniformIn(rng, 0.3, 1.0);
  sim.drift_phase_ = kTwoPi * rng.Uniform();

  Eigen::MatrixXd first;
  sim.NoiseFree(0, false, first);
  sim.reference_rms_.resize(nc);
  for (Eigen::Index ch = 0; ch < nc; ++ch) {
    sim.reference_rms_[ch] =
        std::sqrt(first.col(ch).squaredNorm() / static_cast<double>(first.rows()));
  }
  return sim;
}

double PlantSimulator::InputRevs(double sample) const noexcept {
  const double t = sample / config_.sample_rate_hz;
  const double f0 = config_.input_speed_hz;
  if (!config_.speed_drift || config_.drift_relative == 0.0) return f0 * t;
  const double period = static_cast<double>(config_.block_length) / config_.sample_rate_hz;
  const double a = config_.drift_relative;
  // Integral of f0 (1 + a sin(2 pi t / T + phase)) from 0 to t.
  return f0 * t - f0 * a * period / kTwoPi *
                      (std::cos(kTwoPi * t / period + drift_phase_) - std::cos(drift_phase_));
}

void PlantSimulator::NoiseFree(std::int64_t first_sample, bool fault_on, Eigen::MatrixXd& out) {
  const std::size_t s = segment_;
  const auto b = static_cast<Eigen::Index>(config_.block_length);
  const std::int64_t start =
      first_sample + static_cast<std::int64_t>(config_.block_length) - static_cast<std::int64_t>(s);
  const int stages = excitation_.stage_count();
  const Eigen::Index bins = te_spectrum_.rows();
  const std::uint32_t q = config_.te_oversampling;
  const double inv_q = 1.0 / static_cast<double>(q);
  for (int st = 0; st < stages; ++st) {
    std::span<double> in = forward_->real_in();
    for (std::size_t i = 0; i < s; ++i) {
      in[i] = excitation_.Te(
          st, InputRevs(static_cast<double>(start + static_cast<std::int64_t>(i))), false);
    }
    forward_->Execute();
    const std::span<std::complex<double>> spec = forward_->complex_out();
    for (Eigen::Index k = 0; k < bins; ++k) te_spectrum_(k, st) = spec[static_cast<std::size_t>(k)];
    if (!fault_on || st != excitation_.fault_stage()) continue;
    std::span<double> fin = forward_fault_->real_in();
    for (std::size_t i = 0; i < s * q; ++i) {
      const double position = static_cast<double>(start) + static_cast<double>(i) * inv_q;
      fin[i] = excitation_.FaultDeviation(st, InputRevs(position));
    }
    forward_fault_->Execute();
    // The same record length: bin k of the oversampled FFT is frequency k fs / S; only the
    // bins up to fs / 2 are kept (scaled back to an S-point transform).
    const std::span<std::complex<double>> fspec = forward_fault_->complex_out();
    for (Eigen::Index k = 0; k < bins; ++k) {
      te_spectrum_(k, st) += fspec[static_cast<std::size_t>(k)] * inv_q;
    }
  }
  const Eigen::Index nc = static_cast<Eigen::Index>(channels_.size());
  out.resize(b, nc);
  const double scale = 1.0 / static_cast<double>(s);
  for (Eigen::Index ch = 0; ch < nc; ++ch) {
    std::span<std::complex<double>> in = backward_->complex_in();
    in[0] = 0.0;
    in[static_cast<std::size_t>(bins - 1)] = 0.0;
    for (Eigen::Index k = 1; k + 1 < bins; ++k) {
      const Eigen::MatrixXcd& t = transfer_.at[static_cast<std::size_t>(k - 1)];
      std::complex<double> y = 0.0;
      for (int st = 0; st < stages; ++st) y += t(ch, st) * te_spectrum_(k, st);
      in[static_cast<std::size_t>(k)] = y;
    }
    backward_->Execute();
    const std::span<double> x = backward_->real_out();
    const std::size_t keep_from = s - static_cast<std::size_t>(b);
    for (Eigen::Index i = 0; i < b; ++i) {
      out(i, ch) = x[keep_from + static_cast<std::size_t>(i)] * scale;
    }
  }
}

void PlantSimulator::AddUnmodelled(std::int64_t first_sample, Eigen::MatrixXd& signal) const {
  const double fs = config_.sample_rate_hz;
  const Eigen::Index b = signal.rows();
  const Eigen::Index nc = signal.cols();
  if (config_.tones && config_.tone_level > 0.0) {
    for (Eigen::Index i = 0; i < b; ++i) {
      const double t = static_cast<double>(first_sample + i) / fs;
      const double pump_cycles = pump_hz_ * t;
      const double am =
          1.0 + kToneModulation * std::cos(kTwoPi * (pump_cycles - std::floor(pump_cycles)));
      for (std::size_t k = 0; k < tone_hz_.size(); ++k) {
        const double cycles = tone_hz_[k] * t;
        const double v = am * std::cos(kTwoPi * (cycles - std::floor(cycles)) + tone_phase_[k]);
        for (Eigen::Index ch = 0; ch < nc; ++ch) {
          signal(i, ch) += config_.tone_level * reference_rms_[ch] *
                           tone_gain_(ch, static_cast<Eigen::Index>(k)) * v;
        }
      }
    }
  }
  if (config_.bursts && config_.burst_level > 0.0 && config_.burst_rate_hz > 0.0) {
    DeterministicRng rng(config_.seed, kBurstStreamBase + blocks_);
    const double duration = static_cast<double>(b) / fs;
    double t = 0.0;
    for (;;) {
      t += -std::log(1.0 - rng.Uniform()) / config_.burst_rate_hz;
      if (t >= duration) break;
      const double f = UniformIn(rng, 400.0, 3500.0);
      const double tau = UniformIn(rng, 2e-3, 8e-3);
      const double peak = config_.burst_level * UniformIn(rng, 0.5, 1.5);
      const double phase = kTwoPi * rng.Uniform();
      const auto i0 = static_cast<Eigen::Index>(std::ceil(t * fs));
      const auto i1 = std::min(b, i0 + static_cast<Eigen::Index>(std::ceil(10.0 * tau * fs)));
      for (Eigen::Index i = i0; i < i1; ++i) {
        const double dt = static_cast<double>(i) / fs - t;
        const double v = peak * std::exp(-dt / tau) * std::sin(kTwoPi * f * dt + phase);
        for (Eigen::Index ch = 0; ch < nc; ++ch) {
          signal(i, ch) += reference_rms_[ch] * burst_gain_[ch] * v;
        }
      }
    }
  }
}

void PlantSimulator::NextBlock(bool fault_on, AccelBlock& block) {
  const std::uint32_t len = config_.block_length;
  const std::int64_t first = static_cast<std::int64_t>(blocks_) * len;
  NoiseFree(first, fault_on, scratch_);
  AddUnmodelled(first, scratch_);
  const std::size_t nc = channels_.size();
  block.machine_id = config_.machine_id;
  block.sequence = config_.first_sequence + blocks_;
  block.t0_ns = config_.start_time_ns +
                std::llround(static_cast<double>(first) * 1e9 / config_.sample_rate_hz);
  block.sample_rate_hz = config_.sample_rate_hz;
  block.speed_hz = config_.input_speed_hz;
  block.speed_source = SpeedSource::kAcquisition;
  block.channels = channels_;
  block.samples_per_channel = len;
  block.samples.resize(nc * len);
  DeterministicRng noise(config_.seed, kNoiseStreamBase + blocks_);
  for (std::size_t ch = 0; ch < nc; ++ch) {
    const double sigma = config_.noise_relative * reference_rms_[static_cast<Eigen::Index>(ch)];
    float* dst = block.samples.data() + ch * len;
    for (std::uint32_t i = 0; i < len; ++i) {
      double v = scratch_(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(ch));
      if (sigma > 0.0) v += sigma * noise.Gaussian();
      dst[i] = static_cast<float>(v);
    }
  }
  ++blocks_;
}

}  // namespace gearpath
