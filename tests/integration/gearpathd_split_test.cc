// Several daemons on one domain split the machines between them by configuration: each
// processes only the blocks of its own machines and ignores (does not reject) the others', so
// no block is processed twice.
#include "tests/integration/gearpathd_fixture.h"

namespace gearpath::testing {
namespace {

TEST_F(GearpathdOverDds, TwoDaemonsOnOneDomainEachProcessOnlyTheirOwnMachine) {
  // A second daemon, same domain and topics, watching another machine.
  json other = config_;
  const std::string other_daemon = "other_" + daemon_id_;
  const std::string other_machine = "other_" + machine_id_;
  other["daemon"]["id"] = other_daemon;
  other["machines"][0]["id"] = other_machine;
  const std::string other_path = (dir_ / "other.json").string();
  std::ofstream(other_path) << other.dump(2);
  ChildProcess second(GEARPATHD_PATH, {"--config", other_path}, (dir_ / "other.log").string());
  ASSERT_TRUE(WaitStatusOf(other_daemon, other_machine, [](const auto&) { return true; }, 60s))
      << second.Log();
  ASSERT_TRUE(block_writer_->WaitForReaders(2, 30s).ok());

  for (std::uint64_t s = 1; s <= 2; ++s) {
    Publish(NoiseBlock(s));
    AccelBlock theirs = NoiseBlock(s);
    theirs.machine_id = other_machine;
    Publish(theirs);
  }
  Publish(NoiseBlock(3));
  ASSERT_TRUE(WaitStatus([](const auto& m) { return m.blocks_processed == 3; }, 30s));
  EXPECT_EQ(last_status_.blocks_received, 3u);  // the other machine's 2 blocks are not counted
  EXPECT_EQ(last_status_.blocks_rejected, 0u);
  ASSERT_TRUE(WaitStatusOf(other_daemon, other_machine,
                           [](const auto& m) { return m.blocks_processed == 2; }, 30s))
      << second.Log();
  EXPECT_EQ(last_status_.blocks_received, 2u);
  EXPECT_EQ(last_status_.blocks_rejected, 0u);
  EXPECT_TRUE(second.WaitForLog("ignoring blocks of machine \"" + machine_id_ + "\"", 5s));
  EXPECT_TRUE(daemon_->WaitForLog("ignoring blocks of machine \"" + other_machine + "\"", 5s));
  second.Signal(SIGTERM);
  const auto code = second.WaitExit(2s);
  ASSERT_TRUE(code.has_value());
  EXPECT_EQ(*code, 0);
}

}  // namespace
}  // namespace gearpath::testing
