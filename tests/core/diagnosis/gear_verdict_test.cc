// GearVerdict: the published names of the fault states, and the reservation that keeps the
// verdict allocation-free. (The verdict's logic is the pipeline's localisation and alarm
// stages, tested end to end in tests/core/pipeline and tests/core/evaluation.)
#include "core/diagnosis/gear_verdict.h"

#include <gtest/gtest.h>

namespace gearpath {
namespace {

TEST(GearVerdictTest, EveryStateHasItsPublishedName) {
  EXPECT_EQ(ToString(FaultState::kLearning), "learning");
  EXPECT_EQ(ToString(FaultState::kNoFault), "no_fault");
  EXPECT_EQ(ToString(FaultState::kSuspected), "suspected");
  EXPECT_EQ(ToString(FaultState::kAlarm), "alarm");
  EXPECT_EQ(ToString(static_cast<FaultState>(9)), "unknown");
}

TEST(GearVerdictTest, ReserveMakesRoomForEveryGearAsACandidate) {
  VerdictTopology t;
  t.gear_names = {"G1", "G2", "G3", "G4"};
  GearVerdict v;
  t.Reserve(v);
  EXPECT_GE(v.candidates.capacity(), 4u);
  EXPECT_GE(v.candidate_names.capacity(), 4u);
}

}  // namespace
}  // namespace gearpath
