// Localisation tracking (AnalysisOptions::localisation_tracking): the shaft evidence of a
// machine whose speed drifts within each block comes from order-tracked averages, and names
// the faulty shaft where constant-speed averages name another one; the scores, and therefore
// the detection, are the same either way.
#include <gtest/gtest.h>

#include <atomic>
#include <string>
#include <utility>
#include <vector>

#include "core/evaluation/evaluation_runner.h"
#include "core/evaluation/scenario_matrix.h"
#include "tests/core/counting_operator_new.h"
#include "tests/core/evaluation/drifting_machine.h"
#include "tests/core/evaluation/scenario_of.h"

namespace {
std::atomic<long> g_allocations{0};
}  // namespace

void counting_new::OnAllocation() noexcept {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
}

namespace gearpath {
namespace {

// A pulse on G1 (input shaft) of the distinct-teeth torsional plant at 900 r/min with pump
// tones, bursts and +/- 0.3 % drift within each block: one of the tuning matrix's scenarios.
Scenario DriftingPulseOnG1(bool unmodelled) {
  return testing::ScenarioOf(PlantFamily::kLumpedTorsional, TrainVariant::kDistinct,
                             PlantFaultKind::kTePulse, "G1", 900.0, 0.05, ChannelSet::kSeats,
                             unmodelled);
}

// Amplitude modulation by a tooth of G1 on the seed-teeth (Table 1) perturbed plant at
// 900 r/min, 2 % noise, housing channel, pump tones, bursts and +/- 0.3 % drift: a
// tuning-matrix scenario whose shaft the constant-speed evidence misses.
Scenario DriftingModulationOnG1() {
  return testing::ScenarioOf(PlantFamily::kLumpedPerturbed, TrainVariant::kTable1,
                             PlantFaultKind::kMeshAm, "G1", 900.0, 0.02,
                             ChannelSet::kSeatsAndHousing, true);
}

// Order tracking of every average off (the default is on): the localisation alone is tracked.
ScenarioOutcome RunWith(const Scenario& s, bool localisation_tracking) {
  RunnerOptions o;
  o.order_tracking = false;
  o.localisation_tracking = localisation_tracking;
  ScenarioOutcome out = RunScenario(s, o);
  EXPECT_TRUE(out.error.empty()) << out.error;
  return out;
}

TEST(LocalisationTracking, NamesTheDriftingMachinesFaultyShaft) {
  const Scenario s = DriftingModulationOnG1();
  const ScenarioOutcome tracked = RunWith(s, true);
  const ScenarioOutcome constant = RunWith(s, false);
  ASSERT_EQ(tracked.verdicts.size(), constant.verdicts.size());
  // Same scores, same states: only the localisation reads the tracked averages.
  for (std::size_t i = 0; i < tracked.verdicts.size(); ++i) {
    EXPECT_EQ(tracked.verdicts[i].state, constant.verdicts[i].state) << "block " << i;
  }
  EXPECT_TRUE(tracked.score.detected);
  EXPECT_TRUE(tracked.score.right_gear);
  for (const BlockVerdictRecord& v : tracked.verdicts) {
    if (v.state == FaultState::kSuspected || v.state == FaultState::kAlarm) {
      EXPECT_EQ(v.shaft, "input");
    }
  }
  // Constant-speed averages smear the drifting machine's high orders across the rate groups
  // and name another shaft. Should the constant-speed evidence one day name it too, this
  // scenario no longer shows the point: pick another drifting one from `gearpath evaluate
  // --json` and `--no-localisation-tracking --json` (the pulse on G1 of DriftingPulseOnG1 was
  // this test's scenario until the locked shaft evidence named its shaft without tracking;
  // the same modulation on the distinct-teeth plant at 10 % noise, until the shaft evidence
  // gate did).
  EXPECT_FALSE(constant.score.right_gear);
}

TEST(LocalisationTracking, ChangesNothingAtConstantSpeed) {
  // The same machine without drift (nor tones and bursts): the per-machine decision does not
  // track it, so both settings give the same verdicts.
  const Scenario s = DriftingPulseOnG1(false);
  const ScenarioOutcome tracked = RunWith(s, true);
  const ScenarioOutcome constant = RunWith(s, false);
  ASSERT_EQ(tracked.verdicts.size(), constant.verdicts.size());
  for (std::size_t i = 0; i < tracked.verdicts.size(); ++i) {
    EXPECT_EQ(tracked.verdicts[i].state, constant.verdicts[i].state) << "block " << i;
    EXPECT_EQ(tracked.verdicts[i].gear, constant.verdicts[i].gear) << "block " << i;
    EXPECT_EQ(tracked.verdicts[i].shaft, constant.verdicts[i].shaft) << "block " << i;
  }
  EXPECT_TRUE(tracked.score.right_gear);
}

// The tracked averages reuse plans and buffers made at configuration: a tracked block of a
// learned, alarming machine allocates nothing (DESIGN.md: hot paths allocate nothing), with
// every average tracked (the default) and with the localisation's only.
TEST(LocalisationTracking, ATrackedBlockAllocatesNothing) {
  for (const bool everything : {true, false}) {
    AnalysisOptions options;
    ASSERT_TRUE(options.order_tracking && options.localisation_tracking);  // the defaults
    options.order_tracking = everything;
    testing::DriftingMachine m =
        testing::MakeDriftingMachine(/*drift=*/true, options, PlantFaultKind::kTePulse, "G1");
    PlantSimulator* sim = &m.sim;
    BlockProcessor* processor = &m.processor;
    AccelBlock block;
    BlockResult result;
    for (int b = 0; b < kBaselineBlocks + 3; ++b) {
      sim->NextBlock(b >= kBaselineBlocks, block);
      ASSERT_TRUE(processor->Process(block.view(), result).accepted());
    }
    ASSERT_EQ(processor->ExportLearnedState().order_tracking_mode, 1) << everything;  // tracked
    sim->NextBlock(true, block);
    const long probe = g_allocations.load();
    std::vector<double>* seen = new std::vector<double>(4);  // the counter sees allocations
    delete seen;
    ASSERT_GT(g_allocations.load(), probe);
    const long before = g_allocations.load();
    const ProcessOutcome o = processor->Process(block.view(), result);
    const long after = g_allocations.load();
    EXPECT_TRUE(o.accepted()) << everything;
    EXPECT_GT(result.score.limit_z, 0.0) << everything;
    EXPECT_EQ(after - before, 0) << everything;
  }
}

}  // namespace
}  // namespace gearpath
