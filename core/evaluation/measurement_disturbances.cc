#include "core/evaluation/measurement_disturbances.h"

#include <algorithm>
#include <cmath>
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

double SpeedProfile::Revs(double t) const noexcept {
  const double f0 = mean_hz;
  if (drift_relative == 0.0) return f0 * t;
  const double a = drift_relative;
  // Integral of f0 (1 + a sin(2 pi t / T + phase)) from 0 to t.
  return f0 * t -
         f0 * a * period_s / kTwoPi * (std::cos(kTwoPi * t / period_s + phase) - std::cos(phase));
}

double SpeedProfile::Hz(double t) const noexcept {
  if (drift_relative == 0.0) return mean_hz;
  return mean_hz * (1.0 + drift_relative * std::sin(kTwoPi * t / period_s + phase));
}

double SpeedProfile::HzPerS(double t) const noexcept {
  if (drift_relative == 0.0) return 0.0;
  return mean_hz * drift_relative * kTwoPi / period_s * std::cos(kTwoPi * t / period_s + phase);
}

MeasurementDisturbances::MeasurementDisturbances(const DisturbanceConfig& config,
                                                 Eigen::Index channels)
    : config_(config) {
  DeterministicRng rng(config.seed, kSourceStream);
  pump_hz_ = UniformIn(rng, 17.0, 31.0);
  tone_gain_.resize(channels, 3);
  for (double m : kToneMultiples) {
    tone_hz_.push_back(m * pump_hz_);
    tone_phase_.push_back(kTwoPi * rng.Uniform());
  }
  for (Eigen::Index ch = 0; ch < channels; ++ch) {
    for (Eigen::Index k = 0; k < 3; ++k) tone_gain_(ch, k) = UniformIn(rng, 0.3, 1.0);
  }
  burst_gain_.resize(channels);
  for (Eigen::Index ch = 0; ch < channels; ++ch) burst_gain_[ch] = UniformIn(rng, 0.3, 1.0);
  drift_phase_ = kTwoPi * rng.Uniform();
}

void MeasurementDisturbances::AddUnmodelled(std::int64_t first_sample, std::uint64_t block_index,
                                            const Eigen::VectorXd& reference_rms,
                                            Eigen::MatrixXd& signal) const {
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
          signal(i, ch) += config_.tone_level * reference_rms[ch] *
                           tone_gain_(ch, static_cast<Eigen::Index>(k)) * v;
        }
      }
    }
  }
  if (config_.bursts && config_.burst_level > 0.0 && config_.burst_rate_hz > 0.0) {
    DeterministicRng rng(config_.seed, kBurstStreamBase + block_index);
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
          signal(i, ch) += reference_rms[ch] * burst_gain_[ch] * v;
        }
      }
    }
  }
}

void MeasurementDisturbances::WriteWithNoise(std::uint64_t block_index,
                                             const Eigen::VectorXd& reference_rms,
                                             const Eigen::MatrixXd& signal,
                                             std::vector<float>& samples) const {
  const auto len = static_cast<std::size_t>(signal.rows());
  const auto nc = static_cast<std::size_t>(signal.cols());
  samples.resize(nc * len);
  DeterministicRng noise(config_.seed, kNoiseStreamBase + block_index);
  for (std::size_t ch = 0; ch < nc; ++ch) {
    const double sigma = config_.noise_relative * reference_rms[static_cast<Eigen::Index>(ch)];
    float* dst = samples.data() + ch * len;
    for (std::size_t i = 0; i < len; ++i) {
      double v = signal(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(ch));
      if (sigma > 0.0) v += sigma * noise.Gaussian();
      dst[i] = static_cast<float>(v);
    }
  }
}

}  // namespace gearpath
