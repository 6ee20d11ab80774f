#include "core/evaluation/plant_simulator.h"

#include <fmt/format.h>

#include <cmath>
#include <complex>

namespace gearpath {

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
  sim.header_ = {c.machine_id, c.sample_rate_hz, c.input_speed_hz, c.start_time_ns,
                 c.first_sequence};
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
  sim.disturbances_ = MeasurementDisturbances(DisturbanceConfigOf(c), nc);
  sim.speed_.mean_hz = c.input_speed_hz;
  sim.speed_.drift_relative = c.speed_drift ? c.drift_relative : 0.0;
  sim.speed_.period_s = static_cast<double>(c.block_length) / c.sample_rate_hz;
  sim.speed_.phase = sim.disturbances_.drift_phase();

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
  return speed_.Revs(sample / config_.sample_rate_hz);
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

void PlantSimulator::NextBlock(bool fault_on, AccelBlock& block) {
  const std::uint32_t len = config_.block_length;
  const std::int64_t first = static_cast<std::int64_t>(blocks_) * len;
  NoiseFree(first, fault_on, scratch_);
  disturbances_.AddUnmodelled(first, blocks_, reference_rms_, scratch_);
  header_.Stamp(blocks_, len, channels_, block);
  disturbances_.WriteWithNoise(blocks_, reference_rms_, scratch_, block.samples);
  ++blocks_;
}

}  // namespace gearpath
