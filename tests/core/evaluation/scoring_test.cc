// Scoring on hand-made verdict sequences: majority rules, first alarm, flips, and which
// candidate lists count as the right gear (inseparable sets do, over-broad ones do not).
#include <gtest/gtest.h>

#include "core/evaluation/evaluation_runner.h"
#include "core/evaluation/plant_family.h"

namespace gearpath {
namespace {

TrainLayout Layout(TrainVariant v) {
  Result<TrainLayout> l = TrainLayoutFromGearTrain(MakeTrain(v));
  EXPECT_TRUE(l.ok());
  return *l;
}

BlockVerdictRecord V(FaultState state, std::string gear = "",
                     std::vector<std::string> candidates = {}) {
  BlockVerdictRecord r;
  r.state = state;
  r.gear = std::move(gear);
  r.candidates = std::move(candidates);
  return r;
}

constexpr FaultState kNo = FaultState::kNoFault;
constexpr FaultState kSus = FaultState::kSuspected;
constexpr FaultState kAl = FaultState::kAlarm;

TEST(Scoring, InseparableMeansSameRateAndSameMesh) {
  const TrainLayout t1 = Layout(TrainVariant::kTable1);
  EXPECT_TRUE(GearsInseparable(t1, 2, 3));   // G3 / G4: 7 Hz both, mesh G3-G4
  EXPECT_FALSE(GearsInseparable(t1, 1, 2));  // G2 / G3: same shaft, different meshes
  EXPECT_FALSE(GearsInseparable(t1, 0, 1));  // G1 / G2: same mesh, 10 vs 7 Hz
  const TrainLayout d = Layout(TrainVariant::kDistinct);
  EXPECT_FALSE(GearsInseparable(d, 2, 3));  // G4 with 29 teeth turns 17 % faster
}

TEST(Scoring, InseparableCandidateSetsCountOverBroadOnesDoNot) {
  const TrainLayout t1 = Layout(TrainVariant::kTable1);
  EXPECT_TRUE(VerdictNamesGear(V(kAl, "G3", {"G3", "G4"}), "G4", t1));
  EXPECT_TRUE(VerdictNamesGear(V(kSus, "G3", {"G3", "G4"}), "G3", t1));
  EXPECT_TRUE(VerdictNamesGear(V(kAl, "G1", {"G1"}), "G1", t1));
  EXPECT_TRUE(VerdictNamesGear(V(kAl, "G2"), "G2", t1));                 // no list: the gear name
  EXPECT_FALSE(VerdictNamesGear(V(kAl, "G2", {"G2", "G3"}), "G2", t1));  // over-broad
  EXPECT_FALSE(VerdictNamesGear(V(kAl, "G2", {"G2", "G3", "G4"}), "G3", t1));
  EXPECT_FALSE(VerdictNamesGear(V(kAl, "G1", {"G1"}), "G2", t1));
  EXPECT_FALSE(VerdictNamesGear(V(kNo, "G1", {"G1"}), "G1", t1));  // not an alarm
  EXPECT_FALSE(VerdictNamesGear(V(FaultState::kLearning, "G1", {"G1"}), "G1", t1));
  const TrainLayout d = Layout(TrainVariant::kDistinct);
  EXPECT_FALSE(VerdictNamesGear(V(kAl, "G3", {"G3", "G4"}), "G4", d));  // separable there
  EXPECT_TRUE(VerdictNamesGear(V(kAl, "G4", {"G4"}), "G4", d));
}

TEST(Scoring, MajorityFirstAlarmAndFlips) {
  const TrainLayout t1 = Layout(TrainVariant::kTable1);
  const std::vector<BlockVerdictRecord> seq = {V(kNo), V(kSus, "G1", {"G1"}), V(kAl, "G1", {"G1"}),
                                               V(kAl, "G2", {"G2"}), V(kNo)};
  const ScenarioScore s = ScoreVerdicts(seq, "G1", t1);
  EXPECT_TRUE(s.faulty);
  EXPECT_EQ(s.alarmed_blocks, 3);
  EXPECT_TRUE(s.detected);
  EXPECT_EQ(s.right_gear_blocks, 2);
  EXPECT_FALSE(s.right_gear);  // 2 of 5 is no majority
  EXPECT_EQ(s.first_alarm_block, 2);
  EXPECT_EQ(s.flips, 3);  // no->sus, sus->alarm, alarm->no
  EXPECT_EQ(s.reversals, 1);  // alarm->no; the onset's two steps up are not reversals
  EXPECT_EQ(s.gear_changes, 1);  // G1 -> G2 between the alarmed blocks
  EXPECT_EQ(s.false_alarm_blocks, 0);

  const std::vector<BlockVerdictRecord> g34 = {V(kAl, "G3", {"G3", "G4"}),
                                               V(kAl, "G3", {"G3", "G4"}),
                                               V(kAl, "G3", {"G3", "G4"}), V(kNo), V(kNo)};
  const ScenarioScore r = ScoreVerdicts(g34, "G4", t1);
  EXPECT_TRUE(r.detected);
  EXPECT_TRUE(r.right_gear);
  EXPECT_EQ(r.first_alarm_block, 1);
  EXPECT_EQ(r.flips, 1);
  EXPECT_EQ(r.reversals, 1);
  EXPECT_EQ(r.gear_changes, 0);

  // A change of the candidate set counts, across a quiet block too; the quiet block does not.
  const std::vector<BlockVerdictRecord> widening = {
      V(kAl, "G2", {"G2"}), V(kNo), V(kAl, "G2", {"G2", "G3", "G4"}), V(kAl, "G2", {"G2"}),
      V(kAl, "G2", {"G2"})};
  EXPECT_EQ(ScoreVerdicts(widening, "G2", t1).gear_changes, 2);

  const std::vector<BlockVerdictRecord> two = {V(kAl, "G1"), V(kNo), V(kAl, "G1"), V(kNo), V(kNo)};
  EXPECT_FALSE(ScoreVerdicts(two, "G1", t1).detected);
  EXPECT_EQ(ScoreVerdicts(two, "G1", t1).reversals, 2);
}

TEST(Scoring, HealthyScenariosCountFalseAlarmBlocks) {
  const TrainLayout t1 = Layout(TrainVariant::kTable1);
  const std::vector<BlockVerdictRecord> seq = {V(kNo), V(kSus, "G2", {"G2"}), V(kNo), V(kNo),
                                               V(FaultState::kLearning)};
  const ScenarioScore s = ScoreVerdicts(seq, "", t1);
  EXPECT_FALSE(s.faulty);
  EXPECT_EQ(s.false_alarm_blocks, 1);  // learning is not an alarm
  EXPECT_EQ(s.learning_blocks, 1);
  EXPECT_FALSE(s.detected);
  EXPECT_FALSE(s.right_gear);
  EXPECT_EQ(s.flips, 3);
}

}  // namespace
}  // namespace gearpath
