// `gearpath monitor` shows a daemon that died: after a SIGKILL no Status arrives any more, and
// the monitor says so (DaemonSilent) instead of showing the last "running" forever.
#include "tests/integration/gearpathd_fixture.h"

namespace gearpath::testing {
namespace {

using GearpathdMonitorSilence = GearpathdOverDds;

TEST_F(GearpathdMonitorSilence, AKilledDaemonIsReportedNotResponding) {
  ChildProcess monitor(GEARPATH_TOOL_PATH,
                       {"monitor", "--json", "--domain", std::to_string(domain_id_),
                        "--timeout", "120"},
                       (dir_ / "monitor.log").string());
  ASSERT_TRUE(monitor.started());
  auto wait_for = [&](const std::string& text, std::chrono::seconds timeout) {
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    while (monitor.Log().find(text) == std::string::npos) {
      if (std::chrono::steady_clock::now() > deadline) return false;
      std::this_thread::sleep_for(20ms);
    }
    return true;
  };
  ASSERT_TRUE(wait_for("\"daemon\":\"" + daemon_id_ + "\"", 60s)) << monitor.Log();
  EXPECT_EQ(monitor.Log().find("DaemonSilent"), std::string::npos);  // alive: not silent

  daemon_->Signal(SIGKILL);
  ASSERT_TRUE(daemon_->WaitExit(30s));
  // Status period 0.1 s: silent after max(2 s, 3 periods); generous for a loaded host.
  ASSERT_TRUE(wait_for("DaemonSilent", 30s)) << monitor.Log();
  const std::string log = monitor.Log();
  const std::size_t at = log.find("DaemonSilent");
  const std::size_t begin = log.rfind('\n', at) + 1;  // npos + 1 = 0 on the first line
  const json line = json::parse(log.substr(begin, log.find('\n', at) - begin));
  EXPECT_EQ(line["daemon"], daemon_id_);
  EXPECT_EQ(line["last_state"], "running");
  EXPECT_GE(line["silent_s"].get<double>(), 2.0);
  monitor.Signal(SIGTERM);
  (void)monitor.WaitExit(10s);
}

}  // namespace
}  // namespace gearpath::testing
