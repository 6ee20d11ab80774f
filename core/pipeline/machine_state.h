// MachineState: what one machine has learned and must remember from block to block, whatever
// the block shape: the sequence tracker, the healthy baselines, the dominant-path criterion's
// healthy levels. Owned by the BlockProcessor, shared by the stages of every shape.
#pragma once

#include <optional>
#include <vector>

#include "core/diagnosis/alarm_model.h"
#include "core/diagnosis/healthy_baseline.h"
#include "core/diagnosis/robust_baseline.h"
#include "core/pipeline/block_validation.h"

namespace gearpath {

// Running mean of a per-path figure over the healthy (baseline) blocks.
struct HealthyMean {
  std::vector<double> mean;
  int blocks = 0;

  void Add(std::span<const double> values) noexcept {
    ++blocks;
    for (std::size_t i = 0; i < mean.size() && i < values.size(); ++i) {
      mean[i] += (values[i] - mean[i]) / blocks;
    }
  }
  void Reset() noexcept {
    blocks = 0;
    for (double& m : mean) m = 0.0;
  }
};

struct MachineState {
  SequenceTracker tracker;
  // The healthy baseline of the whole indicator vector (MachineContext layout); the machine
  // is `learning` until it is complete.
  std::optional<RobustBaseline> indicator_baseline;
  double limit_z = 0.0;         // z limit of one block's z for the target false-alarm rate
  double window_limit_z = 0.0;  // the same for the two-block score (indicator_scoring_stage.h)
  // The last scored block's z per indicator, for the two-block score; not part of
  // the learned state (a restart starts a new window). previous_scored is false after a block
  // that was not scored (learning, no speed).
  std::vector<double> previous_z;
  bool previous_scored = false;
  // Lowest and highest input speed of the blocks the indicator baseline learned from; both 0
  // while learning or when a state saved before them was imported (then every speed is judged).
  double baseline_speed_lo_hz = 0.0;
  double baseline_speed_hi_hz = 0.0;
  // Lowest and highest load (AccelBlock::load) of those blocks; both 0 while learning, when a
  // state saved before them was imported, or when one of the blocks carried no load
  // (baseline_load_partial): then every load is judged.
  double baseline_load_lo = 0.0;
  double baseline_load_hi = 0.0;
  bool baseline_load_partial = false;
  HealthyMean residual_variance_healthy;             // per condition slot: NA4's reference
  std::optional<HealthyBaseline> envelope_baseline;  // published envelope thresholds
  HealthyMean criterion_healthy;                     // per path: dominant-path criterion
  std::optional<AlarmModel> alarm;                   // persistence, hysteresis, clear delay
  // Shaft evidence accumulated over recent exceeding blocks, per rate group
  // (localisation_stage.h).
  std::vector<double> group_excess_sum;
  // Mesh evidence (fractions) accumulated the same way, per rate group x kMaxMeshesPerShaft.
  std::vector<double> mesh_evidence_sum;
  // Order tracking for this machine (AnalysisOptions::order_tracking): -1 undecided, 0 constant
  // speed, 1 tracked. Decided once, on the first block with a speed, and kept, so the
  // baseline and every later block are averaged the same way (condition_indicator_stage.h).
  int order_tracking_mode = -1;
  bool learning = true;                              // indicator_baseline is incomplete
};

}  // namespace gearpath
