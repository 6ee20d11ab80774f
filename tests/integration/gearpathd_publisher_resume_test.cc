// `gearpath sim --publish` survives the daemon: killed mid-stream, the publisher holds its
// block and waits; a restarted daemon takes the stream up and the publisher finishes with
// exit 0 and the last block judged. Truth: the publisher's block count.
#include "tests/integration/gearpathd_fixture.h"

namespace gearpath::testing {
namespace {

using GearpathdPublisherResume = GearpathdOverDds;

TEST_F(GearpathdPublisherResume, SimWaitsForARestartedDaemonAndFinishes) {
  constexpr int kBlocks = 16;
  ChildProcess sim(GEARPATH_TOOL_PATH,
                   {"sim", "--publish", "--domain", std::to_string(domain_id_), "--machine-id",
                    machine_id_, "--blocks", std::to_string(kBlocks), "--speed", "4", "--noise",
                    "0.05"},
                   (dir_ / "sim.log").string());
  ASSERT_TRUE(sim.started());
  ASSERT_TRUE(WaitStatus([](const auto& m) { return m.blocks_processed >= 3; }, 90s))
      << sim.Log();
  daemon_->Signal(SIGKILL);
  ASSERT_TRUE(daemon_->WaitExit(30s));
  // The publisher notices (no acknowledgement, then nobody matched) and waits.
  const auto noticed_by = std::chrono::steady_clock::now() + 60s;
  while (sim.Log().find("waiting up to") == std::string::npos) {
    ASSERT_TRUE(sim.running()) << "the publisher gave up:\n" << sim.Log();
    ASSERT_LT(std::chrono::steady_clock::now(), noticed_by) << sim.Log();
    std::this_thread::sleep_for(20ms);
  }
  daemon_ = std::make_unique<ChildProcess>(
      GEARPATHD_PATH, std::vector<std::string>{"--config", config_path_},
      (dir_ / "gearpathd.2.log").string());
  ASSERT_TRUE(daemon_->started());
  const std::optional<int> exit_code = sim.WaitExit(120s);
  ASSERT_TRUE(exit_code.has_value()) << sim.Log();
  EXPECT_EQ(*exit_code, 0) << sim.Log();
  EXPECT_NE(sim.Log().find("publishing resumed"), std::string::npos) << sim.Log();
  // The restarted daemon judged the stream up to its last block (numbered from 0).
  auto last = WaitResult<gearpath_SuspectedGear>(
      *gear_reader_, [](const auto& r) { return r.block_sequence == kBlocks - 1; }, 60s);
  ASSERT_TRUE(last.has_value()) << daemon_->Log() << "\n" << sim.Log();
}

}  // namespace
}  // namespace gearpath::testing
