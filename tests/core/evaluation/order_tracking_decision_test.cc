// The per-machine order-tracking decision (condition_indicator_stage.h) on a plant of the
// evaluation families: a machine whose speed drifts within each block is tracked, one at
// constant speed is not, the decision is kept in the learned state, and a machine with order
// tracking off never decides; localisation tracking alone decides the same way; the shortcut
// that skips the tracks decides as the full test at the edge of what tracking gains.
#include <gtest/gtest.h>

#include <utility>

#include "tests/core/evaluation/drifting_machine.h"

namespace gearpath {
namespace {

using Machine = testing::DriftingMachine;

// A healthy machine with or without drift, order tracking and localisation tracking as given.
Machine MakeMachine(bool drift, bool order_tracking, bool localisation_tracking = false) {
  AnalysisOptions o;
  o.order_tracking = order_tracking;
  o.localisation_tracking = localisation_tracking;
  return testing::MakeDriftingMachine(drift, o);
}

int ModeAfterBlocks(Machine& m, int blocks) {
  AccelBlock block;
  BlockResult result;
  for (int b = 0; b < blocks; ++b) {
    m.sim.NextBlock(false, block);
    EXPECT_TRUE(m.processor.Process(block.view(), result).accepted());
  }
  return m.processor.ExportLearnedState().order_tracking_mode;
}

TEST(OrderTrackingDecision, ADriftingMachineIsTrackedAndKeepsIt) {
  Machine m = MakeMachine(/*drift=*/true, /*order_tracking=*/true);
  EXPECT_EQ(ModeAfterBlocks(m, 1), 1);
  EXPECT_EQ(ModeAfterBlocks(m, 2), 1);
  // A restart resumes the decision with the baseline.
  Machine again = MakeMachine(true, true);
  ASSERT_TRUE(again.processor.ImportLearnedState(m.processor.ExportLearnedState()).ok());
  EXPECT_EQ(again.processor.ExportLearnedState().order_tracking_mode, 1);
  // A re-baseline decides again.
  m.processor.ResetBaseline();
  EXPECT_EQ(m.processor.ExportLearnedState().order_tracking_mode, -1);
}

TEST(OrderTrackingDecision, AConstantSpeedMachineIsNotTracked) {
  Machine m = MakeMachine(/*drift=*/false, /*order_tracking=*/true);
  EXPECT_EQ(ModeAfterBlocks(m, 3), 0);
}

TEST(OrderTrackingDecision, TrackingOffNeverDecides) {
  Machine m = MakeMachine(/*drift=*/true, /*order_tracking=*/false);
  EXPECT_EQ(ModeAfterBlocks(m, 2), -1);
}

// The decision's shortcut (condition_indicator_stage.cc, kCoherentEnough) leaves a machine
// untracked, without tracking, when its revolutions already agree on the mesh harmonics; it
// must not leave one untracked that the full test would track. The truth, taken with the
// shortcut switched off in a scratch build: on this plant the full test tracks from a drift of
// 2.5e-4 (the revolutions' spread there is 0.0206 of their locked power, just over the gain of
// 2 % the test asks for, where the shortcut's bound says it can first pass) and not at 2e-4
// (spread 0.0133, where the shortcut decides).
TEST(OrderTrackingDecision, TheShortcutLeavesUntrackedOnlyWhatTheTestWould) {
  const struct {
    double drift;
    int mode;
  } cases[] = {{0.0, 0}, {2e-4, 0}, {2.5e-4, 1}, {3e-4, 1}};
  for (const auto& c : cases) {
    Machine m = testing::MakeDriftingMachine(/*drift=*/c.drift > 0.0, AnalysisOptions{},
                                             PlantFaultKind::kNone, "", c.drift);
    EXPECT_EQ(ModeAfterBlocks(m, 1), c.mode) << "drift " << c.drift;
  }
}

// Localisation tracking alone (the default) takes the same per-machine decision.
TEST(OrderTrackingDecision, LocalisationTrackingDecidesLikeOrderTracking) {
  Machine drifting = MakeMachine(/*drift=*/true, /*order_tracking=*/false, true);
  EXPECT_EQ(ModeAfterBlocks(drifting, 2), 1);
  Machine steady = MakeMachine(/*drift=*/false, /*order_tracking=*/false, true);
  EXPECT_EQ(ModeAfterBlocks(steady, 2), 0);
}

}  // namespace
}  // namespace gearpath
