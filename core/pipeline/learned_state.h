// LearnedState: what one machine has learned, detached from its BlockProcessor, so that a
// restart or a reload resumes the judgement instead of relearning. Relearning is not harmless:
// a baseline learned while a fault is present takes the fault for healthy, and the fault is
// then reported as no_fault.
//
// The fingerprint says what the baseline measures: a state is only ever resumed by a processor
// whose FRF set, channels, gear train, sample rate, indicator layout and the analysis options
// that shape indicator values are the same (LearnedStateFingerprint). The false-alarm rate
// (the z limit is recomputed from it) and the mesh decision may change without a relearn; alarm
// options that changed restart the alarm model, keeping the baseline.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/common/result.h"
#include "core/diagnosis/alarm_model.h"
#include "core/diagnosis/healthy_baseline.h"
#include "core/diagnosis/robust_baseline.h"

namespace gearpath {

struct MachineContext;

// Operating bands a machine may learn (AnalysisOptions::operating_bands): each is a baseline,
// and every one is kept in memory and in the saved state.
inline constexpr int kMaxOperatingBands = 16;

// What one operating band learned (MachineState's OperatingBand).
struct LearnedBand {
  int band_id = 0;  // OperatingBand::id
  RobustBaselineState indicator_baseline;
  std::vector<double> residual_variance_healthy;  // per condition slot (NA4's reference)
  int residual_variance_blocks = 0;
  std::vector<double> criterion_healthy;  // per path (dominant-path criterion)
  int criterion_blocks = 0;
  // Input speeds the baseline learned at (OperatingBand::baseline_speed_lo_hz, _hi_hz); both 0
  // in states saved before they existed, which then judge every speed.
  double baseline_speed_lo_hz = 0.0;
  double baseline_speed_hi_hz = 0.0;
  // Loads the baseline learned at (OperatingBand::baseline_load_lo, _hi, _partial); both 0 and
  // not partial in states saved before them, which then judge every load.
  double baseline_load_lo = 0.0;
  double baseline_load_hi = 0.0;
  bool baseline_load_partial = false;
};

// The band in use (its fields at the top, as states saved before operating bands had them)
// and the parked bands.
struct LearnedState : LearnedBand {
  std::uint64_t fingerprint = 0;
  bool learning = true;
  std::optional<HealthyBaselineState> envelope_baseline;  // none: thresholds are configured
  AlarmModelState alarm;
  std::vector<double> group_excess_sum;  // per rate group (localisation evidence)
  // Per rate group x kMaxMeshesPerShaft (MachineState::mesh_evidence_sum); empty in states
  // saved before it existed.
  std::vector<double> mesh_evidence_sum;
  int order_tracking_mode = -1;  // MachineState::order_tracking_mode
  // The other operating bands (MachineState::parked_bands); empty in states saved before them.
  std::vector<LearnedBand> parked_bands;
  // The analysis.baseline.epoch it was learned under, so that a refusal can name the one it
  // replaces; absent in states saved before it was recorded (the fingerprint still decides).
  std::optional<std::string> baseline_epoch;
};

// An analysis.baseline.epoch (from a configuration or a saved state) is logged and hashed as it
// is: one line of printable text of at most kMaxBaselineEpochBytes. The error names the byte.
inline constexpr std::size_t kMaxBaselineEpochBytes = 64;
Status ValidateBaselineEpoch(std::string_view epoch);

// Version 2: FNV-1a over everything that shapes the indicator vector and its values (header
// comment), each FRF bin entering as its XXH3 digest.
std::uint64_t LearnedStateFingerprint(const MachineContext& machine);
// The fingerprint as builds before 2026-12-01 computed it (every FRF byte through FNV-1a, 25 ms
// at the reference workload against ~1 ms): a state saved by such a build still resumes when
// this matches, and is saved again with LearnedStateFingerprint.
std::uint64_t LegacyLearnedStateFingerprint(const MachineContext& machine);

}  // namespace gearpath
