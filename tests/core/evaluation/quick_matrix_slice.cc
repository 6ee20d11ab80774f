// Slice test of the evaluation instrument: the quick matrix of the TUNING families (the
// held-out family, parametric_plate, is never asserted on here, so no threshold is ever tuned against it) through
// the current BlockProcessor, against the figures documented for it (docs/evaluation.md).
// The constants are what the pipeline achieved when they were set; whoever improves the
// pipeline raises them (and the doc) in the same commit. The margins absorb small numerical
// differences between toolchains, not regressions.
#include <gtest/gtest.h>

#include <cstdio>
#include <thread>

#include "core/evaluation/evaluation_report.h"
#include "core/evaluation/evaluation_runner.h"
#include "core/evaluation/scenario_matrix.h"

namespace gearpath {
namespace {

// Measured on the quick matrix, tuning families (80 scenarios: 64 faulty, 16 healthy = 80
// healthy evaluation blocks), with the pipeline of commit d966309 (condition indicators with
// forces left out of the score, shaft evidence accumulated over the fault's blocks, mesh by
// transfer signature, alarm model): detection 52/64, right gear 30/64, 2 false alarms in 80
// healthy evaluation blocks. (The envelope-indicator verdict of f497ab0 got 10/64, 7/64 and
// 0/80.) The baseline's tail guard then took the false alarms to 0/80, detection and right
// gear unchanged; the Qn scale (a lower limit for the same false-alarm target) then gave
// detection 53/64, right gear 31/64, 0/80; localisation tracking (shaft and mesh evidence from
// order-tracked averages) right gear 37/64; the synchronous low-order ratio detection 54/64;
// the locked exclusive residual as shaft evidence right gear 40/64.
// Since 2026-11-27 modal_housing is a tuning family (120 scenarios: 96 faulty, 24 healthy =
// 120 healthy evaluation blocks): with the two-block score, the reconstructed envelope
// indicators out of the score and the mesh from the orthogonal signature rise, detection
// 84/96, right gear 67/96, 0/120 false alarms; the tail guard at z = 3 and the raw envelope
// indicators out of the score left all three unchanged; the shaft evidence gate (a group's
// exclusive-residual rise counts only at z >= 3) right gear 68/96; the tracking carrier chosen
// by its phase residual among the mesh harmonics (2026-11-28) right gear 70/96; the tracker
// keeping the block's mean speed, the median of the carriers' warps, and every average tracked
// by default (2026-11-28, later) detection 87/96, right gear 75/96, 0/120; the mesh evidence
// in robust z and accumulated over the fault's blocks (2026-11-28, twelfth session), chosen for
// a steadier named gear and more right gears on the 400-scenario tuning draw, right gear
// 72/96 on this slice; mesh_separation 1.3 -> 1.1 (2026-11-28, thirteenth session) right gear
// 74/96; the transient gate (2026-11-28, fifteenth session: fewer false alarms and more
// detections on the 400-scenario tuning draw) detection 86/96, right gear 72/96, 0/120 on this
// slice; the mesh evidence harmonic by harmonic in z (2026-11-28, sixteenth session) right gear
// 75/96; mesh_separation 1.1 -> 1.0 (2026-11-29, eighteenth session) right gear 77/96; the
// baseline's floor the amplitude's for every indicator (2026-11-29, twentieth session: a 10 %
// load step no longer flagged) detection 85/96 (docs/diagnosis.md section 13).
constexpr double kDocumentedDetection = 0.885;
constexpr double kDocumentedRightGear = 0.802;
constexpr double kDocumentedFalseAlarmsPerBlock = 0.0;
constexpr double kMargin = 0.05;

TEST(QuickMatrixSlice, TuningFamiliesMeetTheDocumentedFigures) {
  MatrixFilter filter;
  filter.held_out = HeldOutSelection::kExclude;
  const std::vector<Scenario> scenarios = EnumerateScenarios(MatrixSize::kQuick, filter);
  ASSERT_FALSE(scenarios.empty());
  const int threads = std::max(2, static_cast<int>(std::thread::hardware_concurrency()));
  const std::vector<ScenarioOutcome> outcomes = RunScenarios(scenarios, RunnerOptions{}, threads);
  for (const ScenarioOutcome& o : outcomes) {
    EXPECT_TRUE(o.error.empty()) << o.scenario.Key() << ": " << o.error;
  }
  const std::vector<PartitionSummary> summary = Summarise(outcomes);
  std::fputs(FormatSummary(summary).c_str(), stdout);
  ASSERT_EQ(summary.size(), 1u);
  ASSERT_EQ(summary[0].name, "tuning");
  const AggregateRow& all = summary[0].overall;
  EXPECT_GE(all.detection_rate(), kDocumentedDetection - kMargin);
  EXPECT_GE(all.right_gear_rate(), kDocumentedRightGear - kMargin);
  EXPECT_LE(all.false_alarm_rate(), kDocumentedFalseAlarmsPerBlock + kMargin);
  // The diagnosis issue's stability bar: no verdict flips back more than once in the 5
  // evaluation blocks of a steady scenario (measured: no scenario reverses at all).
  EXPECT_LE(all.max_reversals, 1);
}

}  // namespace
}  // namespace gearpath
