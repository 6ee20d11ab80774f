// A machine's healthy baseline holds the housing's response at the speeds it was learned at.
// The truth here is the processor's own judgement with the speed range switched off
// (speed_tolerance = 1): a healthy machine run 10 % faster than it learned at
// exceeds its limits there, and the range is what keeps that from being published as a fault.
#include <gtest/gtest.h>

#include <string>
#include <string_view>

#include "tests/core/pipeline/simulated_machine.h"

namespace gearpath {
namespace {
using namespace gearpath::testing;

constexpr double kLearnedHz = 10.0;  // LearnedProcessor's blocks
constexpr double kOtherHz = 11.0;    // 10 % faster

BlockProcessor LearnedWithTolerance(double tolerance, std::uint64_t& seq) {
  MachineSetup setup = MakeSetup(Table1Machine());
  setup.options.speed_tolerance = tolerance;
  auto p = BlockProcessor::Create(setup);
  EXPECT_TRUE(p.ok()) << p.error();
  GearboxSimulator healthy = MakeSimulator(Table1Machine(), FaultType::kNone, "", 7);
  RunBlocks(p.value(), healthy, kBaselineBlocks, seq);
  return std::move(p.value());
}

bool Raised(FaultState s) { return s == FaultState::kSuspected || s == FaultState::kAlarm; }

bool Contains(std::string_view text, std::string_view part) {
  return text.find(part) != std::string_view::npos;
}

TEST(OperatingSpeedTest, AHealthyMachineAtASpeedItDidNotLearnIsNotJudged) {
  // The truth: judged at every speed, the healthy machine at 11 Hz is raised.
  {
    std::uint64_t seq = 0;
    BlockProcessor every_speed = LearnedWithTolerance(1.0, seq);
    GearboxSimulator faster =
        MakeSimulator(Table1Machine(), FaultType::kNone, "", 11, true, kBlock, kOtherHz);
    const BlockResult r = RunBlocks(every_speed, faster, 4, seq);
    ASSERT_TRUE(r.score.judged);
    EXPECT_GT(r.score.score, 1.0);
    EXPECT_TRUE(Raised(r.verdict.state)) << r.verdict.reason.view();
  }
  std::uint64_t seq = 0;
  BlockProcessor p = LearnedWithTolerance(AnalysisOptions{}.speed_tolerance, seq);
  GearboxSimulator learned_speed = MakeSimulator(Table1Machine(), FaultType::kNone, "", 13);
  ASSERT_EQ(RunBlocks(p, learned_speed, 2, seq).verdict.state, FaultState::kNoFault);
  GearboxSimulator faster =
      MakeSimulator(Table1Machine(), FaultType::kNone, "", 11, true, kBlock, kOtherHz);
  for (int i = 0; i < 4; ++i) {
    const BlockResult r = RunBlocks(p, faster, 1, seq);
    EXPECT_FALSE(r.score.judged);
    EXPECT_EQ(r.score.not_judged, NotJudgedCause::kSpeedOutside);
    EXPECT_EQ(r.verdict.state, FaultState::kNoFault) << r.verdict.reason.view();
    EXPECT_EQ(r.verdict.confidence, 0.0);
    EXPECT_TRUE(Contains(r.verdict.reason.view(), "outside")) << r.verdict.reason.view();
    EXPECT_TRUE(Contains(r.verdict.reason.view(), "not judged")) << r.verdict.reason.view();
    EXPECT_DOUBLE_EQ(r.score.baseline_speed_lo_hz, kLearnedHz);
    EXPECT_DOUBLE_EQ(r.score.baseline_speed_hi_hz, kLearnedHz);
    EXPECT_EQ(r.localisation.group, -1);  // no evidence gathered either
  }
  // Back at the learned speed it is judged again, and healthy.
  const BlockResult r = RunBlocks(p, learned_speed, 2, seq);
  EXPECT_TRUE(r.score.judged);
  EXPECT_EQ(r.verdict.state, FaultState::kNoFault) << r.verdict.reason.view();
  EXPECT_GT(r.verdict.confidence, 0.0);
}

// Learned, but the first blocks after it at another speed: still no verdict, and the reason
// says why.
TEST(OperatingSpeedTest, NoVerdictYetWhenTheFirstBlocksAfterLearningAreAtAnotherSpeed) {
  std::uint64_t seq = 0;
  BlockProcessor p = LearnedWithTolerance(AnalysisOptions{}.speed_tolerance, seq);
  GearboxSimulator faster =
      MakeSimulator(Table1Machine(), FaultType::kNone, "", 11, true, kBlock, kOtherHz);
  const BlockResult r = RunBlocks(p, faster, 2, seq);
  EXPECT_FALSE(r.score.judged);
  EXPECT_EQ(r.verdict.state, FaultState::kLearning);
  EXPECT_TRUE(Contains(r.verdict.reason.view(), "not judged")) << r.verdict.reason.view();
}

TEST(OperatingSpeedTest, SpeedsWithinTheToleranceAreJudged) {
  std::uint64_t seq = 0;
  BlockProcessor p = LearnedWithTolerance(0.12, seq);
  GearboxSimulator faster =
      MakeSimulator(Table1Machine(), FaultType::kNone, "", 11, true, kBlock, kOtherHz);
  EXPECT_TRUE(RunBlocks(p, faster, 1, seq).score.judged);
}

// An alarm raised at the learned speed stays raised, with its gear, while the machine runs at a
// speed the baseline cannot judge: leaving the range is no evidence that the fault went away.
TEST(OperatingSpeedTest, AnAlarmIsHeldWithItsGearOutsideTheLearnedSpeeds) {
  std::uint64_t seq = 0;
  BlockProcessor p = LearnedWithTolerance(AnalysisOptions{}.speed_tolerance, seq);
  GearboxSimulator fault = MakeSimulator(Table1Machine(), FaultType::kChippedTooth, "G1", 21);
  const BlockResult raised = RunBlocks(p, fault, 3, seq);
  ASSERT_EQ(raised.verdict.state, FaultState::kAlarm) << raised.verdict.reason.view();
  ASSERT_EQ(raised.verdict.gear_name, "G1");
  GearboxSimulator faster =
      MakeSimulator(Table1Machine(), FaultType::kNone, "", 11, true, kBlock, kOtherHz);
  for (int i = 0; i < 6; ++i) {  // longer than the clear delay
    const BlockResult r = RunBlocks(p, faster, 1, seq);
    EXPECT_FALSE(r.score.judged);
    EXPECT_EQ(r.verdict.state, FaultState::kAlarm) << r.verdict.reason.view();
    EXPECT_EQ(r.verdict.gear_name, "G1");
    EXPECT_EQ(r.verdict.confidence, 0.0);
    EXPECT_TRUE(Contains(r.verdict.reason.view(), "not judged")) << r.verdict.reason.view();
    EXPECT_TRUE(Contains(r.verdict.reason.view(), "G1")) << r.verdict.reason.view();
  }
}

}  // namespace
}  // namespace gearpath
