// HealthyBaseline: per-shaft indicator thresholds learned from the machine's own healthy blocks.
//
// A healthy gearbox already shows squared-envelope lines at shaft harmonics (two meshes beat
// against each other; for seed Table 1, 28 f1 - 34 f2 = 6 f2), so a fault indicator must be
// judged against the machine's own healthy level, not against zero (DESIGN.md). Over the first
// N accepted blocks (assumed healthy; the daemon documents this and offers a reset), the mean
// and standard deviation of each indicator are accumulated (Welford, numerically stable), and
//   threshold = max(mean + k sigma, (1 + min_margin) mean, floor)
// The relative margin guards against a near-deterministic simulation, where sigma -> 0 would put
// the threshold on the healthy level itself; the floor guards against an all-zero baseline.
// Thresholds can instead be configured, in which case nothing is learned.
#pragma once

#include <cstddef>
#include <span>
#include <vector>

#include "core/common/result.h"

namespace gearpath {

struct BaselineOptions {
  int blocks = 20;          // N healthy blocks to learn from (>= 2)
  double k_sigma = 4.0;     // k (>= 0)
  double min_margin = 0.5;  // relative margin over the mean (>= 0)
  double floor = 1e-12;     // absolute lowest threshold (> 0)
};

// Everything needed to resume a learned (or half-learned) baseline after a restart.
struct HealthyBaselineState {
  BaselineOptions options;
  bool configured = false;  // configured thresholds: nothing learned, nothing to resume
  int count = 0;            // blocks accepted so far
  std::vector<double> mean;
  std::vector<double> m2;   // Welford sums of squared deviations
};

class HealthyBaseline {
 public:
  // `indicators` = number of indicators learned in parallel (e.g. shafts x {raw, rec}).
  static Result<HealthyBaseline> Create(std::size_t indicators, const BaselineOptions& options);
  // Fixed thresholds (all > 0 and finite); learned() is true from the start.
  static Result<HealthyBaseline> Configured(std::span<const double> thresholds);

  // Validates sizes, ranges and finiteness (messages name the field); a count that reached
  // options.blocks gives a learned baseline with its thresholds recomputed.
  static Result<HealthyBaseline> FromState(const HealthyBaselineState& state);
  HealthyBaselineState State() const;

  // Adds one healthy block's indicators (size must match; non-finite values skip the block).
  // Once `blocks` were added the thresholds are fixed. noexcept, no allocation.
  void Add(std::span<const double> indicators) noexcept;

  bool learned() const noexcept { return learned_; }
  int blocks_seen() const noexcept { return count_; }
  int blocks_needed() const noexcept { return configured_ ? 0 : options_.blocks; }
  std::span<const double> thresholds() const noexcept { return thresholds_; }
  std::span<const double> mean() const noexcept { return mean_; }
  // Sample standard deviation (n - 1).
  double sigma(std::size_t i) const noexcept;
  void Reset() noexcept;  // no-op for configured thresholds

 private:
  HealthyBaseline() = default;
  void Finalise() noexcept;

  BaselineOptions options_;
  bool configured_ = false;
  bool learned_ = false;
  int count_ = 0;
  std::vector<double> mean_;
  std::vector<double> m2_;
  std::vector<double> thresholds_;
};

}  // namespace gearpath
