#include "core/diagnosis/healthy_baseline.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace gearpath {

Result<HealthyBaseline> HealthyBaseline::Create(std::size_t indicators,
                                                const BaselineOptions& options) {
  if (indicators == 0) return Error{"healthy baseline: no indicators to learn"};
  if (options.blocks < 2) {
    return Error{"healthy baseline: blocks must be >= 2 to estimate a spread, got " +
                 std::to_string(options.blocks)};
  }
  if (!(options.k_sigma >= 0.0) || !std::isfinite(options.k_sigma)) {
    return Error{"healthy baseline: k_sigma must be finite and >= 0"};
  }
  if (!(options.min_margin >= 0.0) || !std::isfinite(options.min_margin)) {
    return Error{"healthy baseline: min_margin must be finite and >= 0"};
  }
  if (!(options.floor > 0.0) || !std::isfinite(options.floor)) {
    return Error{"healthy baseline: floor must be finite and > 0"};
  }
  HealthyBaseline b;
  b.options_ = options;
  b.mean_.assign(indicators, 0.0);
  b.m2_.assign(indicators, 0.0);
  b.thresholds_.assign(indicators, 0.0);
  return b;
}

Result<HealthyBaseline> HealthyBaseline::Configured(std::span<const double> thresholds) {
  if (thresholds.empty()) return Error{"healthy baseline: no thresholds configured"};
  for (std::size_t i = 0; i < thresholds.size(); ++i) {
    if (!(thresholds[i] > 0.0) || !std::isfinite(thresholds[i])) {
      return Error{"healthy baseline: threshold " + std::to_string(i) +
                   " must be finite and > 0, got " + std::to_string(thresholds[i])};
    }
  }
  HealthyBaseline b;
  b.configured_ = true;
  b.learned_ = true;
  b.mean_.assign(thresholds.size(), 0.0);
  b.m2_.assign(thresholds.size(), 0.0);
  b.thresholds_.assign(thresholds.begin(), thresholds.end());
  return b;
}

Result<HealthyBaseline> HealthyBaseline::FromState(const HealthyBaselineState& state) {
  if (state.configured) return Error{"healthy baseline state: configured thresholds are not state"};
  auto made = Create(state.mean.size(), state.options);
  if (!made) return Error{"healthy baseline state: " + made.error()};
  if (state.m2.size() != state.mean.size()) {
    return Error{"healthy baseline state: m2 has " + std::to_string(state.m2.size()) +
                 " values, mean " + std::to_string(state.mean.size())};
  }
  if (state.count < 0 || state.count > state.options.blocks) {
    return Error{"healthy baseline state: count must be in 0.." +
                 std::to_string(state.options.blocks) + ", got " + std::to_string(state.count)};
  }
  for (std::size_t i = 0; i < state.mean.size(); ++i) {
    if (!std::isfinite(state.mean[i]) || !std::isfinite(state.m2[i]) || state.m2[i] < 0.0) {
      return Error{"healthy baseline state: mean/m2[" + std::to_string(i) +
                   "] must be finite (m2 >= 0)"};
    }
  }
  HealthyBaseline& b = made.value();
  b.count_ = state.count;
  b.mean_ = state.mean;
  b.m2_ = state.m2;
  if (b.count_ >= b.options_.blocks) b.Finalise();
  return made;
}

HealthyBaselineState HealthyBaseline::State() const {
  HealthyBaselineState s;
  s.options = options_;
  s.configured = configured_;
  s.count = count_;
  s.mean = mean_;
  s.m2 = m2_;
  return s;
}

void HealthyBaseline::Add(std::span<const double> indicators) noexcept {
  if (learned_ || indicators.size() != mean_.size()) return;
  for (double v : indicators) {
    if (!std::isfinite(v)) return;
  }
  ++count_;
  for (std::size_t i = 0; i < mean_.size(); ++i) {
    const double delta = indicators[i] - mean_[i];
    mean_[i] += delta / count_;
    m2_[i] += delta * (indicators[i] - mean_[i]);
  }
  if (count_ >= options_.blocks) Finalise();
}

double HealthyBaseline::sigma(std::size_t i) const noexcept {
  if (i >= m2_.size() || count_ < 2) return 0.0;
  return std::sqrt(m2_[i] / (count_ - 1));
}

void HealthyBaseline::Finalise() noexcept {
  for (std::size_t i = 0; i < mean_.size(); ++i) {
    thresholds_[i] = std::max({mean_[i] + options_.k_sigma * sigma(i),
                               (1.0 + options_.min_margin) * mean_[i], options_.floor});
  }
  learned_ = true;
}

void HealthyBaseline::Reset() noexcept {
  if (configured_) return;
  learned_ = false;
  count_ = 0;
  std::fill(mean_.begin(), mean_.end(), 0.0);
  std::fill(m2_.begin(), m2_.end(), 0.0);
  std::fill(thresholds_.begin(), thresholds_.end(), 0.0);
}

}  // namespace gearpath
