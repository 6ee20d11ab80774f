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

// What a machine learned at one operating point (a band of input speed and load): the
// indicator baseline, NA4's reference, the dominant-path criterion's healthy levels, and the
// speeds and loads it learned at (AnalysisOptions::operating_bands; docs/diagnosis.md section
// 10, "Operating bands"). The MachineState's `band` is the one the current block is judged
// against; the others are parked.
struct OperatingBand {
  int id = 0;  // order of creation: 0 is the machine's first baseline
  // The healthy baseline of the whole indicator vector (MachineContext layout); the band is
  // learning until it is complete.
  std::optional<RobustBaseline> indicator_baseline;
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
  HealthyMean residual_variance_healthy;  // per condition slot: NA4's reference
  HealthyMean criterion_healthy;          // per path: dominant-path criterion

  bool learned() const noexcept { return indicator_baseline && indicator_baseline->learned(); }
  // Back to an empty band (no allocation).
  void Reset() noexcept {
    indicator_baseline->Reset();
    baseline_speed_lo_hz = baseline_speed_hi_hz = 0.0;
    baseline_load_lo = baseline_load_hi = 0.0;
    baseline_load_partial = false;
    residual_variance_healthy.Reset();
    criterion_healthy.Reset();
  }
};

struct MachineState {
  SequenceTracker tracker;
  // The operating band this block is judged against (or learns into), and the parked ones:
  // parked_bands has operating_bands - 1 slots, made at creation, the first parked_count in use.
  OperatingBand band;
  std::vector<OperatingBand> parked_bands;
  std::size_t parked_count = 0;
  double limit_z = 0.0;         // z limit of one block's z for the target false-alarm rate
  double window_limit_z = 0.0;  // the same for the two-block score (indicator_scoring_stage.h)
  // The last scored block's z per indicator, for the two-block score; not part of
  // the learned state (a restart starts a new window). previous_scored is false after a block
  // that was not scored (learning, no speed).
  std::vector<double> previous_z;
  bool previous_scored = false;
  std::optional<HealthyBaseline> envelope_baseline;  // published envelope thresholds
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
  bool learning = true;  // band.indicator_baseline is incomplete

  // A parked band has learned its baseline: the band in force, while it learns, is then an
  // added operating point, and the machine's verdict holds meanwhile (operating_band_stage.h).
  bool parked_band_learned() const noexcept {
    for (std::size_t i = 0; i < parked_count; ++i) {
      if (parked_bands[i].learned()) return true;
    }
    return false;
  }
  // Some band has learned its baseline.
  bool any_band_learned() const noexcept { return band.learned() || parked_band_learned(); }
};

}  // namespace gearpath
