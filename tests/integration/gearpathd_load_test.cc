// gearpathd reads the blocks that carry the machine's load (AccelBlockV2) beside the plain ones,
// and judges a block only within the loads its healthy baseline learned at (docs/diagnosis.md
// section 10, "Operating load"). The truth is what the test sends: the loads, and a fracture
// the simulator was given.
#include "tests/integration/gearpathd_fixture.h"

namespace gearpath::testing {
namespace {

constexpr int kBaselineBlocks = 6;
constexpr double kLearnedLoad = 100.0;  // N m

class GearpathdLoad : public GearpathdOverDds {
 protected:
  void Configure(json& config) override {
    config["machines"][0]["analysis"]["baseline"]["learning_blocks"] = kBaselineBlocks;
    config["state"]["directory"] = (dir_ / "state").string();
  }

  void SetUp() override {
    GearpathdOverDds::SetUp();
    if (HasFatalFailure()) return;
    ASSERT_TRUE(block_v2_writer_->WaitForReaders(1, 30s).ok()) << daemon_->Log();
  }

  // Publishes the simulator's next block with `load` (AccelBlockV2; NaN too, unchecked), or
  // without one (AccelBlock) when `load` is 0, and returns the daemon's verdict on it.
  std::optional<dds::Owned<gearpath_SuspectedGear>> Judge(GearboxSimulator& sim, double load) {
    AccelBlock block;
    sim.NextBlock(block);
    block.sequence = sequence_++;
    block.load = load;
    if (load == 0.0) {
      Publish(block);
    } else {
      PublishWithLoad(block);
    }
    const std::uint64_t s = block.sequence;
    return WaitResult<gearpath_SuspectedGear>(
        *gear_reader_, [s](const auto& r) { return r.block_sequence == s; }, 60s);
  }

  void LearnAt(double load) {
    GearboxSimulator healthy = Table1Simulator(FaultType::kNone, "", 7);
    for (int i = 0; i < kBaselineBlocks; ++i) {
      auto v = Judge(healthy, load);
      ASSERT_TRUE(v.has_value()) << "no verdict on healthy block " << i << "\n" << daemon_->Log();
      ASSERT_EQ((*v)->state, gearpath_LEARNING) << (*v)->reason;
    }
  }

  // The machine's state file, as the daemon saved it (null when there is none).
  json SavedState() const {
    for (const auto& entry : std::filesystem::directory_iterator(dir_ / "state")) {
      if (!entry.path().string().ends_with(".state.json")) continue;
      std::ifstream in(entry.path());
      return json::parse(in);
    }
    return nullptr;
  }

  std::uint64_t sequence_ = 1;
};

constexpr std::string_view kJudged = "every indicator within the healthy baseline";
constexpr std::string_view kOutside =
    "load 150 outside the 100-100 the healthy baseline was learned at (+/- 10 %): not judged, "
    "state held";

TEST_F(GearpathdLoad, ABlockIsJudgedOnlyWithinTheLearnedLoadsAndTheRangeSurvivesARestart) {
  LearnAt(kLearnedLoad);
  GearboxSimulator healthy = Table1Simulator(FaultType::kNone, "", 99);
  auto within = Judge(healthy, 105.0);  // within the default tolerance of 10 %
  ASSERT_TRUE(within.has_value());
  EXPECT_EQ((*within)->state, gearpath_NO_FAULT) << (*within)->reason;
  EXPECT_TRUE(std::string_view((*within)->reason).starts_with(kJudged)) << (*within)->reason;

  auto outside = Judge(healthy, 150.0);
  ASSERT_TRUE(outside.has_value());
  EXPECT_EQ((*outside)->state, gearpath_NO_FAULT) << (*outside)->reason;  // held
  EXPECT_EQ(std::string_view((*outside)->reason), kOutside);
  EXPECT_EQ((*outside)->confidence, 0.0);

  // A block without a load (the plain topic, same machine) is judged as before.
  auto plain = Judge(healthy, 0.0);
  ASSERT_TRUE(plain.has_value());
  EXPECT_TRUE(std::string_view((*plain)->reason).starts_with(kJudged)) << (*plain)->reason;

  // The learned range is part of the saved state, and so is the count of blocks not judged
  // for their load, which a plant watches (gearpath_blocks_not_judged_total).
  RestartDaemon(SIGTERM);
  const json saved = SavedState();
  ASSERT_FALSE(saved.is_null()) << "no state file in " << (dir_ / "state");
  EXPECT_EQ(saved["counters"]["not_judged"], json::parse(R"({"load_outside": 1})")) << saved;
  auto after = Judge(healthy, 150.0);
  ASSERT_TRUE(after.has_value()) << daemon_->Log();
  EXPECT_EQ(std::string_view((*after)->reason), kOutside) << daemon_->Log();
}

TEST_F(GearpathdLoad, AFractureAtALearnedLoadIsStillFoundAndANaNLoadIsRejectedByName) {
  LearnAt(kLearnedLoad);
  GearboxSimulator broken = Table1Simulator(FaultType::kToothFracture, "G1", 21);
  bool alarmed = false;
  std::string gear;
  for (int i = 0; i < 8 && !alarmed; ++i) {
    auto v = Judge(broken, 98.0);
    ASSERT_TRUE(v.has_value()) << "no verdict on faulty block " << i;
    alarmed = (*v)->state == gearpath_ALARM;
    gear = dds::GetString((*v)->gear_name);
  }
  EXPECT_TRUE(alarmed) << "the fracture at a learned load raised no alarm\n" << daemon_->Log();
  EXPECT_EQ(gear, "G1");

  AccelBlock block;
  broken.NextBlock(block);
  block.sequence = sequence_++;
  block.load = std::numeric_limits<double>::quiet_NaN();
  PublishWithLoad(block);
  ASSERT_TRUE(WaitStatus([](const auto& m) { return m.blocks_rejected == 1; }, 30s))
      << daemon_->Log();
  EXPECT_TRUE(std::string_view(last_status_.last_rejection_reason)
                  .starts_with("implausible_load: load nan of block "))
      << last_status_.last_rejection_reason;
}

// With baseline.operating_bands 2 the daemon learns a second band at a load its first did not
// learn at, holding the verdict meanwhile, then judges there; both bands survive a restart.
class GearpathdOperatingBands : public GearpathdLoad {
 protected:
  void Configure(json& config) override {
    GearpathdLoad::Configure(config);
    config["machines"][0]["analysis"]["baseline"]["operating_bands"] = 2;
  }
};

TEST_F(GearpathdOperatingBands, ASecondBandLearnsAtANewLoadJudgesThereAndSurvivesARestart) {
  LearnAt(kLearnedLoad);
  GearboxSimulator healthy = Table1Simulator(FaultType::kNone, "", 99);
  auto first = Judge(healthy, kLearnedLoad);
  ASSERT_TRUE(first.has_value()) << daemon_->Log();
  EXPECT_EQ((*first)->state, gearpath_NO_FAULT) << (*first)->reason;
  for (int i = 0; i < kBaselineBlocks; ++i) {
    auto v = Judge(healthy, 150.0);
    ASSERT_TRUE(v.has_value()) << "no verdict on block " << i << " at 150\n" << daemon_->Log();
    EXPECT_EQ((*v)->state, gearpath_NO_FAULT) << (*v)->reason;  // held, not LEARNING
    EXPECT_EQ((*v)->confidence, 0.0);
    EXPECT_TRUE(std::string_view((*v)->reason)
                    .starts_with("learning the healthy baseline of operating band 1 (of up to 2)"))
        << (*v)->reason;
  }
  for (const double load : {150.0, kLearnedLoad}) {
    auto v = Judge(healthy, load);
    ASSERT_TRUE(v.has_value()) << daemon_->Log();
    EXPECT_TRUE(std::string_view((*v)->reason).starts_with(kJudged))
        << load << ": " << (*v)->reason;
  }

  RestartDaemon(SIGTERM);
  const json state = SavedState();
  ASSERT_FALSE(state.is_null()) << "no state file in " << (dir_ / "state");
  EXPECT_EQ(state["learned"]["operating_bands"].size(), 1u) << state["learned"].dump();
  EXPECT_EQ(state["counters"]["not_judged"], json::parse(R"({"learning_band": 6})")) << state;
  for (const double load : {150.0, kLearnedLoad}) {
    auto v = Judge(healthy, load);
    ASSERT_TRUE(v.has_value()) << daemon_->Log();
    EXPECT_TRUE(std::string_view((*v)->reason).starts_with(kJudged))
        << load << ": " << (*v)->reason;
  }
}

}  // namespace
}  // namespace gearpath::testing
