// gearpathd remembers what each machine learned across a crash, a clean restart and a reload
// (daemon/machine_state_store.h). The truth is the fault the simulator was given: a daemon
// that relearned its baseline after the restart would take the present fracture for healthy
// and answer learning, then no_fault.
#include "tests/integration/gearpathd_fixture.h"

namespace gearpath::testing {
namespace {

constexpr int kBaselineBlocks = 6;

class GearpathdState : public GearpathdOverDds {
 protected:
  void Configure(json& config) override {
    config["machines"][0]["analysis"]["baseline"]["learning_blocks"] = kBaselineBlocks;
    config["state"]["directory"] = (dir_ / "state").string();
  }

  // Publishes one block and returns the daemon's verdict on it.
  std::optional<dds::Owned<gearpath_SuspectedGear>> Judge(GearboxSimulator& sim) {
    AccelBlock block;
    sim.NextBlock(block);
    block.sequence = sequence_++;
    Publish(block);
    const std::uint64_t s = block.sequence;
    return WaitResult<gearpath_SuspectedGear>(
        *gear_reader_, [s](const auto& r) { return r.block_sequence == s; }, 60s);
  }

  void LearnHealthy() {
    GearboxSimulator healthy = Table1Simulator(FaultType::kNone, "", 7);
    for (int i = 0; i < kBaselineBlocks; ++i) {
      auto v = Judge(healthy);
      ASSERT_TRUE(v.has_value()) << "no verdict on healthy block " << i;
      ASSERT_EQ((*v)->state, gearpath_LEARNING);
    }
  }

  // Feeds the faulty gearbox until the daemon alarms (at most 8 blocks).
  void AlarmOn(GearboxSimulator& broken) {
    for (int i = 0; i < 8; ++i) {
      auto v = Judge(broken);
      ASSERT_TRUE(v.has_value()) << "no verdict on faulty block " << i;
      if ((*v)->state == gearpath_ALARM) return;
    }
    FAIL() << "the fault never raised an alarm";
  }

  std::uint64_t sequence_ = 1;
};

TEST_F(GearpathdState, AfterAKillWithAFractureThePresentAlarmIsResumedNotRelearned) {
  LearnHealthy();
  GearboxSimulator broken = Table1Simulator(FaultType::kToothFracture, "G1", 21);
  ASSERT_NO_FATAL_FAILURE(AlarmOn(broken));

  RestartDaemon(SIGKILL);
  // The very first verdict of the new daemon, on the still-fractured gearbox.
  auto first = Judge(broken);
  ASSERT_TRUE(first.has_value()) << daemon_->Log();
  EXPECT_EQ((*first)->state, gearpath_ALARM) << (*first)->reason << "\n" << daemon_->Log();
  EXPECT_EQ(dds::GetString((*first)->gear_name), "G1");
  EXPECT_NE(daemon_->Log().find("resumed from"), std::string::npos) << daemon_->Log();
}

TEST_F(GearpathdState, ACleanRestartKeepsTheBaselineAndTheCounters) {
  LearnHealthy();
  const std::uint64_t processed = sequence_ - 1;
  RestartDaemon(SIGTERM);
  ASSERT_TRUE(WaitStatus([&](const auto& m) { return m.blocks_processed == processed; }, 30s))
      << "counters after restart: processed " << last_status_.blocks_processed;
  GearboxSimulator healthy = Table1Simulator(FaultType::kNone, "", 99);
  auto v = Judge(healthy);
  ASSERT_TRUE(v.has_value());
  EXPECT_NE((*v)->state, gearpath_LEARNING) << (*v)->reason;
  EXPECT_NE((*v)->state, gearpath_ALARM) << (*v)->reason;
}

TEST_F(GearpathdState, AReloadKeepsTheBaselineUnlessItChangesWhatItMeasures) {
  LearnHealthy();
  GearboxSimulator healthy = Table1Simulator(FaultType::kNone, "", 99);
  // Unchanged configuration: SIGHUP keeps the learned baseline.
  daemon_->Signal(SIGHUP);
  ASSERT_TRUE(WaitStatus([](const auto&) { return true; }, 30s));
  auto kept = Judge(healthy);
  ASSERT_TRUE(kept.has_value());
  EXPECT_NE((*kept)->state, gearpath_LEARNING) << (*kept)->reason;

  // A scale floor that changes every indicator's healthy scale: a new baseline is learned.
  config_["machines"][0]["analysis"]["baseline"]["scale_floor"] = 0.2;
  WriteConfig(config_);
  daemon_->Signal(SIGHUP);
  const auto deadline = std::chrono::steady_clock::now() + 60s;
  for (;;) {
    ASSERT_LT(std::chrono::steady_clock::now(), deadline) << daemon_->Log();
    auto v = Judge(healthy);
    ASSERT_TRUE(v.has_value());
    if ((*v)->state == gearpath_LEARNING) break;  // the reload has taken effect
  }
  EXPECT_NE(daemon_->Log().find("changes what the baseline measures"), std::string::npos)
      << daemon_->Log();
}

// After maintenance the plant changes the machine's baseline.epoch and reloads: the alarm and
// the baseline of the broken gearbox go, the repaired one is learned, and what it learned
// survives a restart under the new epoch; a later epoch given at a restart is refused by name.
TEST_F(GearpathdState, ANewEpochOnReloadForgetsTheBaselineAndTheNewOneSurvivesARestart) {
  LearnHealthy();
  GearboxSimulator broken = Table1Simulator(FaultType::kToothFracture, "G1", 21);
  ASSERT_NO_FATAL_FAILURE(AlarmOn(broken));

  const std::string epoch = "2026-11-29 G1 replaced";
  config_["machines"][0]["analysis"]["baseline"]["epoch"] = epoch;
  WriteConfig(config_);
  daemon_->Signal(SIGHUP);
  GearboxSimulator repaired = Table1Simulator(FaultType::kNone, "", 77);
  const auto deadline = std::chrono::steady_clock::now() + 60s;
  int learning = 0;
  for (;;) {
    ASSERT_LT(std::chrono::steady_clock::now(), deadline) << daemon_->Log();
    auto v = Judge(repaired);
    ASSERT_TRUE(v.has_value()) << daemon_->Log();
    if ((*v)->state == gearpath_LEARNING) {
      ++learning;
    } else if (learning > 0) {  // learned again: the repaired gearbox is healthy
      EXPECT_EQ((*v)->state, gearpath_NO_FAULT) << (*v)->reason;
      break;
    }  // else the reload has not taken effect yet: the old baseline judges (under load, long
       // enough for the repaired gearbox to clear the alarm)
  }
  EXPECT_EQ(learning, kBaselineBlocks);
  EXPECT_NE(daemon_->Log().find("baseline epoch \"\" -> \"" + epoch + "\""), std::string::npos)
      << daemon_->Log();

  RestartDaemon(SIGTERM);
  auto resumed = Judge(repaired);
  ASSERT_TRUE(resumed.has_value()) << daemon_->Log();
  EXPECT_EQ((*resumed)->state, gearpath_NO_FAULT) << (*resumed)->reason << "\n" << daemon_->Log();
  EXPECT_NE(daemon_->Log().find("resumed from"), std::string::npos) << daemon_->Log();

  // A new epoch given while it was stopped: the saved state names the one it replaces.
  const std::string next = "2026-12-03 G4 replaced";
  config_["machines"][0]["analysis"]["baseline"]["epoch"] = next;
  WriteConfig(config_);
  RestartDaemon(SIGTERM);
  auto relearning = Judge(repaired);
  ASSERT_TRUE(relearning.has_value()) << daemon_->Log();
  EXPECT_EQ((*relearning)->state, gearpath_LEARNING) << (*relearning)->reason;
  EXPECT_NE(daemon_->Log().find("baseline epoch \"" + epoch + "\" -> \"" + next + "\""),
            std::string::npos)
      << daemon_->Log();
}

}  // namespace
}  // namespace gearpath::testing
