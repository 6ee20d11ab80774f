// gearpathd's systemd notifications, received on a NOTIFY_SOCKET of the test's own (as systemd
// would provide it): READY=1 after start, WATCHDOG=1 while idle, RELOADING=1 then READY=1 around
// a reload, STOPPING=1 on SIGTERM.
#include <sys/socket.h>
#include <sys/un.h>

#include <cstdlib>

#include "tests/integration/gearpathd_fixture.h"

namespace gearpath::testing {
namespace {

class GearpathdSystemdNotify : public GearpathdOverDds {
 protected:
  void Configure(json& config) override {
    (void)config;
    socket_path_ = (dir_ / "notify.sock").string();
    fd_ = socket(AF_UNIX, SOCK_DGRAM | SOCK_CLOEXEC | SOCK_NONBLOCK, 0);
    ASSERT_GE(fd_, 0);
    sockaddr_un addr{};
    addr.sun_family = AF_UNIX;
    ASSERT_LT(socket_path_.size(), sizeof(addr.sun_path));
    std::memcpy(addr.sun_path, socket_path_.c_str(), socket_path_.size() + 1);
    ASSERT_EQ(bind(fd_, reinterpret_cast<sockaddr*>(&addr), sizeof(addr)), 0);
    // Inherited by the daemon started right after Configure().
    setenv("NOTIFY_SOCKET", socket_path_.c_str(), 1);
    setenv("WATCHDOG_USEC", "400000", 1);  // 0.4 s: the daemon must pet at least every 0.4 s
  }

  void TearDown() override {
    GearpathdOverDds::TearDown();
    unsetenv("NOTIFY_SOCKET");
    unsetenv("WATCHDOG_USEC");
    if (fd_ >= 0) close(fd_);
  }

  // Everything received so far, message after message.
  std::string Drain() {
    char buf[4096];
    for (;;) {
      const ssize_t n = recv(fd_, buf, sizeof buf, 0);
      if (n <= 0) break;
      received_.append(buf, static_cast<std::size_t>(n));
      received_ += '\n';
    }
    return received_;
  }

  bool WaitFor(const std::string& text, std::chrono::milliseconds timeout) {
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    while (std::chrono::steady_clock::now() < deadline) {
      if (Drain().find(text) != std::string::npos) return true;
      std::this_thread::sleep_for(10ms);
    }
    return false;
  }

  std::size_t Count(const std::string& text) {
    std::size_t n = 0;
    for (std::size_t at = Drain().find(text); at != std::string::npos;
         at = received_.find(text, at + 1)) {
      ++n;
    }
    return n;
  }

  std::string socket_path_;
  int fd_ = -1;
  std::string received_;
};

TEST_F(GearpathdSystemdNotify, TellsSystemdReadyReloadingWatchdogAndStopping) {
  ASSERT_TRUE(WaitFor("READY=1", 10s)) << received_;
  EXPECT_NE(received_.find("STATUS=running: 1 machine(s)"), std::string::npos) << received_;
  // Idle (no blocks at all) but healthy: the watchdog is still petted, several times a second.
  const std::size_t pets = Count("WATCHDOG=1");
  std::this_thread::sleep_for(1s);
  EXPECT_GE(Count("WATCHDOG=1"), pets + 3) << received_;

  daemon_->Signal(SIGHUP);
  ASSERT_TRUE(WaitFor("RELOADING=1", 10s)) << received_;
  const std::size_t reloading_at = received_.find("RELOADING=1");
  ASSERT_TRUE(WaitFor("(reloaded)", 30s)) << received_;
  const std::size_t ready_again = received_.find("READY=1", reloading_at);
  EXPECT_NE(ready_again, std::string::npos) << received_;

  daemon_->Signal(SIGTERM);
  ASSERT_TRUE(WaitFor("STOPPING=1", 5s)) << received_;
  const auto code = daemon_->WaitExit(2s);
  ASSERT_TRUE(code.has_value());
  EXPECT_EQ(*code, 0);
}

}  // namespace
}  // namespace gearpath::testing
