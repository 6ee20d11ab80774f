// The baseline epoch (AnalysisOptions::baseline_epoch, config `baseline.epoch`): after
// maintenance a plant changes it, and the machine forgets what it learned. The truth is the
// gearbox the test gives: a machine whose old baseline is kept judges the repaired gearbox
// against it; one whose epoch changed is learning again, and judges against what it learns next.
#include <gtest/gtest.h>

#include <string>
#include <string_view>
#include <utility>

#include "core/pipeline/learned_state_json.h"
#include "tests/core/pipeline/simulated_machine.h"

namespace gearpath {
namespace {
using namespace gearpath::testing;

MachineSetup SetupWithEpoch(std::string epoch) {
  MachineSetup setup = MakeSetup(Table1Machine());
  setup.options.baseline_epoch = std::move(epoch);
  return setup;
}

BlockProcessor LearnedAt(std::string epoch, std::uint64_t& seq) {
  auto p = BlockProcessor::Create(SetupWithEpoch(std::move(epoch)));
  EXPECT_TRUE(p.ok()) << p.error();
  GearboxSimulator healthy = MakeSimulator(Table1Machine(), FaultType::kNone, "", 7);
  RunBlocks(p.value(), healthy, kBaselineBlocks, seq);
  EXPECT_EQ(p->baseline_blocks_learned(), kBaselineBlocks);
  return std::move(p.value());
}

TEST(BaselineEpochTest, NoEpochLeavesTheFingerprintAndEachEpochHasItsOwn) {
  std::uint64_t seq = 0;
  const std::uint64_t none = LearnedAt("", seq).ExportLearnedState().fingerprint;
  auto default_options = BlockProcessor::Create(MakeSetup(Table1Machine()));
  ASSERT_TRUE(default_options.ok());
  EXPECT_EQ(default_options->ExportLearnedState().fingerprint, none);
  const std::uint64_t a = LearnedAt("2026-11-29 G1 replaced", seq).ExportLearnedState().fingerprint;
  const std::uint64_t b = LearnedAt("2026-12-03 G1 replaced", seq).ExportLearnedState().fingerprint;
  EXPECT_NE(a, none);
  EXPECT_NE(b, none);
  EXPECT_NE(a, b);
}

TEST(BaselineEpochTest, ANewEpochForgetsTheBaselineAndTheAlarm) {
  std::uint64_t seq = 0;
  BlockProcessor before = LearnedAt("", seq);
  // The fault the maintenance is about: the machine alarms on G1.
  GearboxSimulator broken = MakeSimulator(Table1Machine(), FaultType::kToothFracture, "G1", 21);
  const BlockResult alarmed = RunBlocks(before, broken, 4, seq);
  ASSERT_EQ(alarmed.verdict.state, FaultState::kAlarm) << alarmed.verdict.reason.view();
  const LearnedState saved = before.ExportLearnedState();

  // The same epoch resumes the alarm, as a restart must.
  auto same = BlockProcessor::Create(SetupWithEpoch(""));
  ASSERT_TRUE(same.ok());
  ASSERT_TRUE(same->ImportLearnedState(saved).ok());
  EXPECT_EQ(RunBlocks(same.value(), broken, 1, seq).verdict.state, FaultState::kAlarm);

  // After the repair, a new epoch: the old baseline is refused by name, and the repaired
  // gearbox is learned instead of being judged against it.
  auto repaired = BlockProcessor::Create(SetupWithEpoch("2026-11-29 G1 replaced"));
  ASSERT_TRUE(repaired.ok());
  const Status refused = repaired->ImportLearnedState(saved);
  ASSERT_FALSE(refused.ok());
  EXPECT_NE(refused.error().find("learned under baseline epoch \"\", this configuration's is "
                                 "\"2026-11-29 G1 replaced\""),
            std::string::npos)
      << refused.error();
  GearboxSimulator healthy = MakeSimulator(Table1Machine(), FaultType::kNone, "", 31);
  const BlockResult first = RunBlocks(repaired.value(), healthy, 1, seq);
  EXPECT_EQ(first.verdict.state, FaultState::kLearning) << first.verdict.reason.view();
  RunBlocks(repaired.value(), healthy, kBaselineBlocks - 1, seq);
  const BlockResult judged = RunBlocks(repaired.value(), healthy, 1, seq);
  EXPECT_EQ(judged.verdict.state, FaultState::kNoFault) << judged.verdict.reason.view();

  // What it learned under the new epoch is resumed under it.
  auto restarted = BlockProcessor::Create(SetupWithEpoch("2026-11-29 G1 replaced"));
  ASSERT_TRUE(restarted.ok());
  EXPECT_TRUE(restarted->ImportLearnedState(repaired->ExportLearnedState()).ok());
}

// The saved state names the epoch it was learned under, so that the refusal can name it after a
// restart too; a state saved before the epoch was recorded is judged by its fingerprint alone.
TEST(BaselineEpochTest, TheSavedStateCarriesItsEpochAndOneWithoutItStillResumes) {
  std::uint64_t seq = 0;
  const LearnedState saved = LearnedAt("2026-11-29 G1 replaced", seq).ExportLearnedState();
  const nlohmann::json j = ToJson(saved);
  ASSERT_EQ(j.at("baseline_epoch"), "2026-11-29 G1 replaced");
  auto read = LearnedStateFromJson(nlohmann::json::parse(j.dump()));
  ASSERT_TRUE(read.ok()) << read.error();
  ASSERT_TRUE(read->baseline_epoch.has_value());
  EXPECT_EQ(*read->baseline_epoch, "2026-11-29 G1 replaced");

  auto later = BlockProcessor::Create(SetupWithEpoch("2026-12-03 G2 replaced"));
  ASSERT_TRUE(later.ok());
  const Status refused = later->ImportLearnedState(read.value());
  ASSERT_FALSE(refused.ok());
  EXPECT_NE(refused.error().find("\"2026-11-29 G1 replaced\", this configuration's is "
                                 "\"2026-12-03 G2 replaced\""),
            std::string::npos)
      << refused.error();

  // Written before the key existed: no epoch, and an empty one hashed nothing.
  nlohmann::json old = ToJson(LearnedAt("", seq).ExportLearnedState());
  old.erase("baseline_epoch");
  auto old_read = LearnedStateFromJson(old);
  ASSERT_TRUE(old_read.ok()) << old_read.error();
  EXPECT_FALSE(old_read->baseline_epoch.has_value());
  auto resumed = BlockProcessor::Create(SetupWithEpoch(""));
  ASSERT_TRUE(resumed.ok());
  EXPECT_TRUE(resumed->ImportLearnedState(old_read.value()).ok());
  EXPECT_EQ(resumed->baseline_blocks_learned(), kBaselineBlocks);
  // ... and under a new epoch it is refused by its fingerprint, the old epoch unknown.
  auto renamed = BlockProcessor::Create(SetupWithEpoch("2026-11-29 G1 replaced"));
  ASSERT_TRUE(renamed.ok());
  const Status by_fingerprint = renamed->ImportLearnedState(old_read.value());
  ASSERT_FALSE(by_fingerprint.ok());
  EXPECT_NE(by_fingerprint.error().find("fingerprint"), std::string::npos)
      << by_fingerprint.error();

  // A saved epoch is read with the checks of a configured one.
  for (const nlohmann::json& bad :
       {nlohmann::json("two\nlines"), nlohmann::json(std::string(kMaxBaselineEpochBytes + 1, 'x')),
        nlohmann::json(7)}) {
    nlohmann::json edited = j;
    edited["baseline_epoch"] = bad;
    auto r = LearnedStateFromJson(edited);
    ASSERT_FALSE(r.ok()) << bad;
    EXPECT_NE(r.error().find("baseline_epoch"), std::string::npos) << r.error();
  }
}

TEST(BaselineEpochTest, AnEpochWithAControlCharacterOrTooLongIsRefusedByName) {
  for (const std::string& epoch :
       {std::string("line\none"), std::string("tab\there"), std::string(1, '\x7f')}) {
    auto p = BlockProcessor::Create(SetupWithEpoch(epoch));
    ASSERT_FALSE(p.ok()) << epoch;
    EXPECT_NE(p.error().find("options.baseline_epoch holds control character"), std::string::npos)
        << p.error();
  }
  auto long_epoch =
      BlockProcessor::Create(SetupWithEpoch(std::string(kMaxBaselineEpochBytes + 1, 'x')));
  ASSERT_FALSE(long_epoch.ok());
  EXPECT_NE(long_epoch.error().find("options.baseline_epoch is 65 bytes long, at most 64"),
            std::string::npos)
      << long_epoch.error();
  // UTF-8 text is printable text.
  EXPECT_TRUE(BlockProcessor::Create(SetupWithEpoch("Getriebe getauscht, 29.11. \xc3\xbc")).ok());
}

}  // namespace
}  // namespace gearpath
