// A machine whose baseline learned with loads judges a block only within them (AnalysisOptions::
// load_tolerance, docs/diagnosis.md section 10 "Operating load"). The truth is the loads the test
// gives its blocks: which blocks lie inside the learned range widened by the tolerance.
#include <gtest/gtest.h>

#include <string>
#include <string_view>
#include <utility>

#include "core/pipeline/learned_state_json.h"
#include "tests/core/pipeline/learned_state_round_trip.h"
#include "tests/core/pipeline/simulated_machine.h"

namespace gearpath {
namespace {
using namespace gearpath::testing;

bool Contains(std::string_view text, std::string_view part) {
  return text.find(part) != std::string_view::npos;
}

// Learned over blocks at 95 and 105 (N m, say): the range 95-105, judged within 85.5-115.5.
BlockProcessor LearnedAtLoads(std::uint64_t& seq, double other_load = 105.0) {
  auto p = BlockProcessor::Create(MakeSetup(Table1Machine()));
  EXPECT_TRUE(p.ok()) << p.error();
  GearboxSimulator healthy = MakeSimulator(Table1Machine(), FaultType::kNone, "", 7);
  for (int b = 0; b < kBaselineBlocks; ++b) {
    RunBlocks(p.value(), healthy, 1, seq, b == 1 ? other_load : 95.0);
  }
  EXPECT_EQ(p->baseline_blocks_learned(), kBaselineBlocks);
  return std::move(p.value());
}

TEST(OperatingLoadTest, ABlockIsJudgedOnlyWithinTheLearnedLoadsWidenedByTheTolerance) {
  std::uint64_t seq = 0;
  BlockProcessor p = LearnedAtLoads(seq);
  GearboxSimulator healthy = MakeSimulator(Table1Machine(), FaultType::kNone, "", 13);
  RunBlocks(p, healthy, 1, seq, 100.0);  // the first block after learning
  for (const double load : {86.0, 100.0, 115.0}) {
    const BlockResult r = RunBlocks(p, healthy, 1, seq, load);
    EXPECT_TRUE(r.score.judged) << load << ": " << r.verdict.reason.view();
    EXPECT_EQ(r.score.not_judged, NotJudgedCause::kNone) << load;
    EXPECT_EQ(r.verdict.state, FaultState::kNoFault) << r.verdict.reason.view();
  }
  for (const double load : {85.0, 116.0, 200.0}) {
    const BlockResult r = RunBlocks(p, healthy, 1, seq, load);
    EXPECT_FALSE(r.score.judged) << load;
    EXPECT_EQ(r.score.not_judged, NotJudgedCause::kLoadOutside) << load;
    EXPECT_EQ(r.verdict.state, FaultState::kNoFault);  // held
    EXPECT_EQ(r.verdict.confidence, 0.0);
    EXPECT_DOUBLE_EQ(r.score.baseline_load_lo, 95.0);
    EXPECT_DOUBLE_EQ(r.score.baseline_load_hi, 105.0);
    EXPECT_TRUE(Contains(r.verdict.reason.view(), "outside the 95-105 the healthy baseline was "
                                                  "learned at (+/- 10 %): not judged"))
        << r.verdict.reason.view();
  }
  // A block without a load is judged at any load.
  EXPECT_TRUE(RunBlocks(p, healthy, 1, seq, 0.0).score.judged);
}

TEST(OperatingLoadTest, TheLearnedLoadRangeTravelsWithTheState) {
  std::uint64_t seq = 0;
  BlockProcessor learned = LearnedAtLoads(seq);
  const LearnedState saved = ThroughJson(learned.ExportLearnedState());
  EXPECT_DOUBLE_EQ(saved.baseline_load_lo, 95.0);
  EXPECT_DOUBLE_EQ(saved.baseline_load_hi, 105.0);
  EXPECT_FALSE(saved.baseline_load_partial);

  GearboxSimulator healthy = MakeSimulator(Table1Machine(), FaultType::kNone, "", 13);
  auto resumed = BlockProcessor::Create(MakeSetup(Table1Machine()));
  ASSERT_TRUE(resumed.ok());
  ASSERT_TRUE(resumed->ImportLearnedState(saved).ok());
  EXPECT_FALSE(RunBlocks(resumed.value(), healthy, 1, seq, 150.0).score.judged);

  // A state saved before the range existed judges every load.
  nlohmann::json old = ToJson(learned.ExportLearnedState());
  old.erase("baseline_load");
  old.erase("baseline_load_partial");
  auto read = LearnedStateFromJson(old);
  ASSERT_TRUE(read.ok()) << read.error();
  auto legacy = BlockProcessor::Create(MakeSetup(Table1Machine()));
  ASSERT_TRUE(legacy.ok());
  ASSERT_TRUE(legacy->ImportLearnedState(read.value()).ok());
  EXPECT_TRUE(RunBlocks(legacy.value(), healthy, 1, seq, 150.0).score.judged);
  // A bad range is refused by name: LearnedStateTest.TheLearnedSpeedRangeTravelsWithTheBaseline.
}

// One baseline block without a load: the blocks' loads are not the whole baseline's, so there is
// no range, and every load is judged.
TEST(OperatingLoadTest, ABaselineWithABlockWithoutALoadLearnsNoRange) {
  std::uint64_t seq = 0;
  BlockProcessor p = LearnedAtLoads(seq, 0.0);
  const LearnedState s = p.ExportLearnedState();
  EXPECT_TRUE(s.baseline_load_partial);
  EXPECT_EQ(s.baseline_load_hi, 0.0);
  GearboxSimulator healthy = MakeSimulator(Table1Machine(), FaultType::kNone, "", 13);
  RunBlocks(p, healthy, 1, seq, 95.0);
  EXPECT_TRUE(RunBlocks(p, healthy, 1, seq, 300.0).score.judged);
}

}  // namespace
}  // namespace gearpath
