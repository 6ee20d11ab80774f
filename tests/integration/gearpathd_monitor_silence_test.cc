// `gearpath monitor` shows a daemon that died: after a SIGKILL no Status arrives any more, and
// the monitor says so (DaemonSilent) within two status periods (issue 12's bar) instead of
// showing the last "running" forever; while the daemon lives it never says so.
#include "tests/integration/gearpathd_fixture.h"

namespace gearpath::testing {
namespace {

constexpr double kStatusPeriodS = 1.0;  // the daemon's default

class GearpathdMonitorSilence : public GearpathdOverDds {
 protected:
  void Configure(json& config) override { config["daemon"]["status_period_s"] = kStatusPeriodS; }
};

std::size_t Count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) {
    ++n;
  }
  return n;
}

TEST_F(GearpathdMonitorSilence, AKilledDaemonIsReportedNotRespondingWithinTwoStatusPeriods) {
  ChildProcess monitor(GEARPATH_TOOL_PATH,
                       {"monitor", "--json", "--domain", std::to_string(domain_id_),
                        "--timeout", "120"},
                       (dir_ / "monitor.log").string());
  ASSERT_TRUE(monitor.started());
  const std::string status_line =
      "\"daemon\":\"" + daemon_id_ + "\",\"machines\"";  // a Status line of our daemon
  auto wait_for = [&](const std::function<bool(const std::string&)>& done,
                      std::chrono::seconds timeout) {
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    while (!done(monitor.Log())) {
      if (std::chrono::steady_clock::now() > deadline) return false;
      std::this_thread::sleep_for(5ms);
    }
    return true;
  };
  // Alive for five periods (the monitor then knows the period): never reported silent.
  ASSERT_TRUE(wait_for([&](const std::string& log) { return Count(log, status_line) >= 5; }, 60s))
      << monitor.Log();
  EXPECT_EQ(monitor.Log().find("DaemonSilent"), std::string::npos) << monitor.Log();

  const auto killed = std::chrono::steady_clock::now();
  daemon_->Signal(SIGKILL);
  ASSERT_TRUE(wait_for(
      [](const std::string& log) { return log.find("DaemonSilent") != std::string::npos; }, 30s))
      << monitor.Log();
  const double reported_after_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - killed).count();
  ASSERT_TRUE(daemon_->WaitExit(30s));
  const std::string log = monitor.Log();
  const std::size_t at = log.find("DaemonSilent");
  const std::size_t begin = log.rfind('\n', at) + 1;  // npos + 1 = 0 on the first line
  const json line = json::parse(log.substr(begin, log.find('\n', at) - begin));
  EXPECT_EQ(line["daemon"], daemon_id_);
  EXPECT_EQ(line["last_state"], "running");
  // The bar: stale within two status periods of the kill. The monitor's own figure, silence
  // since the last Status arrived, is 1.5 periods (its rule) and at most two.
  EXPECT_LE(reported_after_s, 2 * kStatusPeriodS) << log;
  EXPECT_GE(line["silent_s"].get<double>(), 1.5 * kStatusPeriodS);
  EXPECT_LE(line["silent_s"].get<double>(), 2 * kStatusPeriodS);
  std::printf("DaemonSilent %.3f s after the SIGKILL (status period %.1f s), silent_s %.3f\n",
              reported_after_s, kStatusPeriodS, line["silent_s"].get<double>());
  monitor.Signal(SIGTERM);
  (void)monitor.WaitExit(10s);
}

}  // namespace
}  // namespace gearpath::testing
