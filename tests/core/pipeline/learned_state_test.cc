// A machine's learned state survives export, JSON and import: a processor that resumes it
// judges the next blocks exactly as the processor that learned it (the truth is the original
// processor's own continuation on the same blocks), and a state is refused by a processor
// whose configuration measures something else.
#include "core/pipeline/learned_state.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string_view>
#include <utility>

#include "core/pipeline/learned_state_json.h"
#include "tests/core/pipeline/learned_state_round_trip.h"
#include "tests/core/pipeline/simulated_machine.h"

namespace gearpath {
namespace {
using namespace gearpath::testing;

// Feeds the same `count` simulated blocks to both processors; expects identical judgements.
// The two-block score's memory of the previous block is not learned state: a resumed machine
// scores its first block alone (docs/diagnosis.md section 10), so with `first_scored_alone`
// that block's score may differ while its verdict may not; from the second block on both
// windows hold the same blocks and the scores agree bit for bit.
void ExpectSameJudgement(BlockProcessor& a, BlockProcessor& b, GearboxSimulator& sim, int count,
                         std::uint64_t& sequence, bool first_scored_alone = false) {
  AccelBlock block;
  BlockResult ra, rb;
  for (int i = 0; i < count; ++i) {
    sim.NextBlock(block);
    block.sequence = sequence++;
    ASSERT_TRUE(a.Process(block.view(), ra).accepted());
    ASSERT_TRUE(b.Process(block.view(), rb).accepted());
    EXPECT_EQ(ra.verdict.state, rb.verdict.state) << "block " << i;
    EXPECT_EQ(ra.verdict.gear_name, rb.verdict.gear_name) << "block " << i;
    // The evidence the gear stands on, accumulated over the fault's blocks, carries over too.
    EXPECT_EQ(ra.localisation.mesh_evidence, rb.localisation.mesh_evidence) << "block " << i;
    if (!(first_scored_alone && i == 0)) {
      EXPECT_EQ(ra.score.score, rb.score.score) << "block " << i;  // bit for bit
    }
    EXPECT_EQ(ra.score.exceed_count, rb.score.exceed_count) << "block " << i;
    EXPECT_EQ(ra.score.limit_z, rb.score.limit_z);
    for (std::size_t s = 0; s < ra.shafts.size(); ++s) {
      EXPECT_EQ(ra.shafts[s].raw_threshold, rb.shafts[s].raw_threshold);
    }
  }
}

// A fracture on G1 (a shaft of one mesh) and on G2 (the shaft of two meshes, where the mesh
// evidence accumulated over the fault's blocks decides, docs/diagnosis.md section 11): a
// machine resumed mid-alarm carries its sums and goes on naming the gear the learner names.
TEST(LearnedStateTest, AResumedMachineKeepsItsAlarmAndJudgesLikeTheOneThatLearned) {
  const Machine& m = Table1Machine();
  const struct {
    const char* gear;
    std::uint64_t seed;
  } faults[] = {{"G1", 21}, {"G2", 23}};
  for (const auto& fault : faults) {
    SCOPED_TRACE(fault.gear);
    std::uint64_t seq = 1;
    BlockProcessor learned = LearnedProcessor(m, seq);
    GearboxSimulator broken = MakeSimulator(m, FaultType::kToothFracture, fault.gear, fault.seed);
    const BlockResult before = RunBlocks(learned, broken, 4, seq);
    ASSERT_EQ(before.verdict.state, FaultState::kAlarm) << before.verdict.reason.view();
    const LearnedState state = learned.ExportLearnedState();
    if (std::string_view(fault.gear) == "G2") {
      double accumulated = 0.0;
      for (double x : state.mesh_evidence_sum) accumulated += x;
      EXPECT_GT(accumulated, 0.0) << "no mesh evidence accumulated over the alarmed blocks";
    }

    auto resumed = BlockProcessor::Create(MakeSetup(m));
    ASSERT_TRUE(resumed.ok()) << resumed.error();
    ASSERT_TRUE(resumed->ImportLearnedState(ThroughJson(state)).ok());
    EXPECT_EQ(resumed->baseline_blocks_learned(), kBaselineBlocks);
    // A fresh processor would learn the fracture as healthy; the resumed one goes on alarming.
    ExpectSameJudgement(learned, resumed.value(), broken, 3, seq, /*first_scored_alone=*/true);
  }
}

TEST(LearnedStateTest, ABaselineHalfLearnedIsFinishedWithTheRemainingBlocks) {
  const Machine& m = Table1Machine();
  auto a = BlockProcessor::Create(MakeSetup(m));
  ASSERT_TRUE(a.ok());
  std::uint64_t seq = 1;
  GearboxSimulator healthy = MakeSimulator(m, FaultType::kNone, "", 7);
  RunBlocks(a.value(), healthy, kBaselineBlocks / 2, seq);
  auto b = BlockProcessor::Create(MakeSetup(m));
  ASSERT_TRUE(b.ok());
  ASSERT_TRUE(b->ImportLearnedState(ThroughJson(a->ExportLearnedState())).ok());
  EXPECT_EQ(b->baseline_blocks_learned(), kBaselineBlocks / 2);
  ExpectSameJudgement(a.value(), b.value(), healthy, kBaselineBlocks, seq);
  EXPECT_EQ(b->baseline_blocks_learned(), kBaselineBlocks);
}

TEST(LearnedStateTest, AChangedAlarmWindowKeepsTheBaselineAndRestartsTheAlarmModel) {
  const Machine& m = Table1Machine();
  std::uint64_t seq = 1;
  BlockProcessor learned = LearnedProcessor(m, seq);
  MachineSetup s = MakeSetup(m);
  s.options.alarm_window = 7;
  s.options.false_alarm_rate = 0.001;  // judged differently, measured the same
  auto p = BlockProcessor::Create(s);
  ASSERT_TRUE(p.ok());
  EXPECT_EQ(p->learned_state_fingerprint(), learned.learned_state_fingerprint());
  ASSERT_TRUE(p->ImportLearnedState(learned.ExportLearnedState()).ok());
  GearboxSimulator healthy = MakeSimulator(m, FaultType::kNone, "", 11);
  const BlockResult r = RunBlocks(p.value(), healthy, 1, seq);
  EXPECT_NE(r.verdict.state, FaultState::kLearning);
  EXPECT_EQ(r.score.window, 7);
}

TEST(LearnedStateTest, AStateIsRefusedByAMachineThatMeasuresSomethingElse) {
  const Machine& m = Table1Machine();
  std::uint64_t seq = 1;
  BlockProcessor learned = LearnedProcessor(m, seq);
  const LearnedState state = learned.ExportLearnedState();

  MachineSetup other_frf = MakeSetup(m);
  other_frf.frf_set.decoupled.at[10](0, 0) *= 1.01;  // a re-measured FRF set
  MachineSetup other_floor = MakeSetup(m);
  other_floor.options.scale_floor = 0.1;
  const MachineSetup distinct = MakeSetup(MakeMachine(true));  // another gear train
  for (const MachineSetup& s : {other_frf, other_floor, distinct}) {
    auto p = BlockProcessor::Create(s);
    ASSERT_TRUE(p.ok()) << p.error();
    const Status st = p->ImportLearnedState(state);
    ASSERT_FALSE(st.ok());
    EXPECT_NE(st.error().find("measured something else"), std::string::npos) << st.error();
    EXPECT_EQ(p->baseline_blocks_learned(), 0);  // nothing changed
  }
}

// A state saved before the mesh evidence accumulated has no sums: it reads, and the machine
// starts them from zero. Sums of another machine's size are refused by name.
TEST(LearnedStateTest, AStateWithoutMeshEvidenceSumsStartsThemFromZero) {
  const Machine& m = Table1Machine();
  std::uint64_t seq = 1;
  BlockProcessor learned = LearnedProcessor(m, seq);
  nlohmann::json old = ToJson(learned.ExportLearnedState());
  old.erase("mesh_evidence_sum");
  auto read = LearnedStateFromJson(old);
  ASSERT_TRUE(read.ok()) << read.error();
  EXPECT_TRUE(read->mesh_evidence_sum.empty());
  auto p = BlockProcessor::Create(MakeSetup(m));
  ASSERT_TRUE(p.ok());
  ASSERT_TRUE(p->ImportLearnedState(read.value()).ok());
  for (double x : p->ExportLearnedState().mesh_evidence_sum) EXPECT_EQ(x, 0.0);

  LearnedState short_sums = learned.ExportLearnedState();
  short_sums.mesh_evidence_sum.pop_back();
  const Status st = p->ImportLearnedState(short_sums);
  ASSERT_FALSE(st.ok());
  EXPECT_NE(st.error().find("mesh_evidence_sum"), std::string::npos) << st.error();
}

void ExpectBadRangesRefused(const LearnedState& good, BlockProcessor& p);

// The speeds the baseline learned at travel with it. A state saved before they existed reads
// as [0, 0] and judges every speed, as its machine did; a range that is not 0 < low <= high
// is refused, as is a load range (operating_load_test.cc has the rest of the load's).
TEST(LearnedStateTest, TheLearnedSpeedRangeTravelsWithTheBaseline) {
  const Machine& m = Table1Machine();
  std::uint64_t seq = 1;
  BlockProcessor learned = LearnedProcessor(m, seq);
  const LearnedState saved = ThroughJson(learned.ExportLearnedState());
  EXPECT_DOUBLE_EQ(saved.baseline_speed_lo_hz, 10.0);
  EXPECT_DOUBLE_EQ(saved.baseline_speed_hi_hz, 10.0);

  auto resumed = BlockProcessor::Create(MakeSetup(m));
  ASSERT_TRUE(resumed.ok());
  ASSERT_TRUE(resumed->ImportLearnedState(saved).ok());
  GearboxSimulator faster = MakeSimulator(m, FaultType::kNone, "", 11, true, kBlock, 11.0);
  BlockResult r = RunBlocks(resumed.value(), faster, 1, seq);
  EXPECT_FALSE(r.score.judged) << r.verdict.reason.view();

  nlohmann::json old = ToJson(learned.ExportLearnedState());
  old.erase("baseline_speed_hz");
  auto read = LearnedStateFromJson(old);
  ASSERT_TRUE(read.ok()) << read.error();
  EXPECT_EQ(read->baseline_speed_hi_hz, 0.0);
  auto legacy = BlockProcessor::Create(MakeSetup(m));
  ASSERT_TRUE(legacy.ok());
  ASSERT_TRUE(legacy->ImportLearnedState(read.value()).ok());
  r = RunBlocks(legacy.value(), faster, 1, seq);
  EXPECT_TRUE(r.score.judged) << r.verdict.reason.view();

  ExpectBadRangesRefused(learned.ExportLearnedState(), legacy.value());
}

// Both learned ranges (speed, load): one that is not 0 < low <= high, finite, is refused on
// import, and one of three values on reading the JSON, each by name.
void ExpectBadRangesRefused(const LearnedState& good, BlockProcessor& p) {
  struct Range {
    double LearnedState::*lo;
    double LearnedState::*hi;
    const char* refusal;
    const char* key;
  };
  for (const Range& range :
       {Range{&LearnedState::baseline_speed_lo_hz, &LearnedState::baseline_speed_hi_hz,
              "speed range", "baseline_speed_hz"},
        Range{&LearnedState::baseline_load_lo, &LearnedState::baseline_load_hi, "load range",
              "baseline_load"}}) {
    for (const auto& [lo, hi] : {std::pair{11.0, 10.0}, std::pair{0.0, 10.0},
                                 std::pair{10.0, std::numeric_limits<double>::infinity()},
                                 std::pair{std::nan(""), 10.0}}) {
      LearnedState bad = good;
      bad.*range.lo = lo;
      bad.*range.hi = hi;
      const Status st = p.ImportLearnedState(bad);
      ASSERT_FALSE(st.ok()) << range.key << " " << lo << "-" << hi;
      EXPECT_NE(st.error().find(range.refusal), std::string::npos) << st.error();
    }
    nlohmann::json three = ToJson(good);
    three[range.key] = {1.0, 2.0, 3.0};
    auto refused = LearnedStateFromJson(three);
    ASSERT_FALSE(refused.ok()) << range.key;
    EXPECT_NE(refused.error().find(range.key), std::string::npos) << refused.error();
  }
}

TEST(LearnedStateTest, InconsistentPartsAreRefusedAndNamed) {
  const Machine& m = Table1Machine();
  std::uint64_t seq = 1;
  BlockProcessor learned = LearnedProcessor(m, seq);
  auto p = BlockProcessor::Create(MakeSetup(m));
  ASSERT_TRUE(p.ok());

  LearnedState short_scale = learned.ExportLearnedState();
  short_scale.indicator_baseline.scale.pop_back();
  Status st = p->ImportLearnedState(short_scale);
  ASSERT_FALSE(st.ok());
  EXPECT_NE(st.error().find("scale"), std::string::npos) << st.error();

  LearnedState bad_vote = learned.ExportLearnedState();
  bad_vote.alarm.votes = {-3};
  st = p->ImportLearnedState(bad_vote);
  ASSERT_FALSE(st.ok());
  EXPECT_NE(st.error().find("votes"), std::string::npos) << st.error();

  LearnedState nan_level = learned.ExportLearnedState();
  nan_level.criterion_healthy[0] = std::nan("");
  EXPECT_FALSE(p->ImportLearnedState(nan_level).ok());
  EXPECT_EQ(p->baseline_blocks_learned(), 0);
}

TEST(LearnedStateJsonTest, MissingKeysAndWrongTypesAreNamedNotThrown) {
  const Machine& m = Table1Machine();
  std::uint64_t seq = 1;
  BlockProcessor learned = LearnedProcessor(m, seq);
  nlohmann::json j = ToJson(learned.ExportLearnedState());

  nlohmann::json missing = j;
  missing["alarm"].erase("quiet_run");
  auto r = LearnedStateFromJson(missing);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().find("quiet_run"), std::string::npos) << r.error();

  nlohmann::json wrong = j;
  wrong["indicator_baseline"]["median"] = "many";
  EXPECT_FALSE(LearnedStateFromJson(wrong).ok());

  nlohmann::json huge = j;
  huge["alarm"]["n"] = 1e300;  // does not fit an int
  EXPECT_FALSE(LearnedStateFromJson(huge).ok());

  nlohmann::json bad_state = j;
  bad_state["alarm"]["state"] = "panic";
  r = LearnedStateFromJson(bad_state);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().find("panic"), std::string::npos) << r.error();

  EXPECT_FALSE(LearnedStateFromJson(nlohmann::json::array()).ok());
}

}  // namespace
}  // namespace gearpath
