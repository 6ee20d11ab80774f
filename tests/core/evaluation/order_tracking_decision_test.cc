// The per-machine order-tracking decision (condition_indicator_stage.h) on a plant of the
// evaluation families: a machine whose speed drifts within each block is tracked, one at
// constant speed is not, the decision is kept in the learned state, and a machine with order
// tracking off never decides; localisation tracking alone decides the same way.
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

// Localisation tracking alone (the default) takes the same per-machine decision.
TEST(OrderTrackingDecision, LocalisationTrackingDecidesLikeOrderTracking) {
  Machine drifting = MakeMachine(/*drift=*/true, /*order_tracking=*/false, true);
  EXPECT_EQ(ModeAfterBlocks(drifting, 2), 1);
  Machine steady = MakeMachine(/*drift=*/false, /*order_tracking=*/false, true);
  EXPECT_EQ(ModeAfterBlocks(steady, 2), 0);
}

}  // namespace
}  // namespace gearpath
