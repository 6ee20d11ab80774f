// The metrics endpoint end to end: gearpathd with metrics.enabled on a port the kernel picks
// (port 0, read back from the daemon's log), two machines fed over loopback DDS, and /metrics
// fetched over a plain socket to 127.0.0.1. The processed counters equal what Status reports,
// a rejected block is counted under its reason, every machine has its four state series, and
// the latency histogram counts every processed block. Every wait polls its condition with a
// deadline; ctest's TIMEOUT is the outer watchdog.
#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <sys/time.h>
#include <unistd.h>

#include <limits>
#include <regex>
#include <sstream>
#include <string>

#include "tests/integration/gearpathd_fixture.h"

namespace gearpath::testing {
namespace {

struct HttpReply {
  int status = 0;  // 0: no reply (connection refused, timeout)
  std::string body;
};

// GET `path` from 127.0.0.1:`port` with HTTP/1.0 (the server closes after the reply).
HttpReply HttpGet(int port, const std::string& path) {
  HttpReply reply;
  const int fd = socket(AF_INET, SOCK_STREAM, 0);
  if (fd < 0) return reply;
  timeval timeout{5, 0};
  setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &timeout, sizeof(timeout));
  setsockopt(fd, SOL_SOCKET, SO_SNDTIMEO, &timeout, sizeof(timeout));
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_port = htons(static_cast<std::uint16_t>(port));
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  std::string raw;
  if (connect(fd, reinterpret_cast<sockaddr*>(&addr), sizeof(addr)) == 0) {
    const std::string request = "GET " + path + " HTTP/1.0\r\nHost: 127.0.0.1\r\n\r\n";
    if (send(fd, request.data(), request.size(), MSG_NOSIGNAL) ==
        static_cast<ssize_t>(request.size())) {
      char buf[65536];
      for (ssize_t n; (n = recv(fd, buf, sizeof(buf), 0)) > 0;) raw.append(buf, n);
    }
  }
  close(fd);
  const auto head_end = raw.find("\r\n\r\n");
  if (raw.rfind("HTTP/1.", 0) != 0 || head_end == std::string::npos) return reply;
  reply.status = std::stoi(raw.substr(9, 3));
  reply.body = raw.substr(head_end + 4);
  return reply;
}

// The value of the sample line `series` (name and labels exactly as exposed); NaN if absent.
double SampleValue(const std::string& text, const std::string& series) {
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    if (line.size() > series.size() && line.compare(0, series.size(), series) == 0 &&
        line[series.size()] == ' ') {
      return std::stod(line.substr(series.size() + 1));
    }
  }
  return std::numeric_limits<double>::quiet_NaN();
}

class GearpathdMetrics : public GearpathdOverDds {
 protected:
  void Configure(json& config) override {
    config["metrics"] = {{"enabled", true}, {"address", "127.0.0.1"}, {"port", 0}};
    json second = config["machines"][0];
    second["id"] = SecondMachine();
    second["analysis"]["baseline"]["epoch"] = "after the 2026-11 overhaul";
    config["machines"].push_back(second);
  }

  std::string SecondMachine() const { return machine_id_ + "_b"; }

  // The port the daemon logged ("metrics endpoint listening on http://127.0.0.1:N/metrics").
  int MetricsPort() {
    const std::string prefix = "metrics endpoint listening on http://127.0.0.1:";
    if (!daemon_->WaitForLog(prefix, 30s)) return 0;
    const std::string log = daemon_->Log();
    std::smatch m;
    const std::regex re("metrics endpoint listening on http://127\\.0\\.0\\.1:([0-9]+)/metrics");
    return std::regex_search(log, m, re) ? std::stoi(m[1]) : 0;
  }

  // Scrapes until `series` has `value` or `timeout` passes; returns the last body.
  std::string ScrapeUntil(int port, const std::string& series, double value,
                          std::chrono::milliseconds timeout) {
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    std::string body;
    do {
      body = HttpGet(port, "/metrics").body;
      if (SampleValue(body, series) == value) break;
      std::this_thread::sleep_for(50ms);
    } while (std::chrono::steady_clock::now() < deadline);
    return body;
  }
};

TEST_F(GearpathdMetrics, ScrapeShowsTheCountersStatusReportsAndEveryStateSeries) {
  const int port = MetricsPort();
  ASSERT_GT(port, 0) << daemon_->Log();
  const std::string a = machine_id_;
  const std::string b = SecondMachine();

  // Machine a: 5 good blocks. Machine b: 3 good blocks, then one with a NaN sample.
  for (std::uint64_t s = 1; s <= 5; ++s) Publish(NoiseBlock(s));
  for (std::uint64_t s = 1; s <= 3; ++s) {
    AccelBlock block = NoiseBlock(s);
    block.machine_id = b;
    Publish(block);
  }
  AccelBlock bad = NoiseBlock(4);
  bad.machine_id = b;
  bad.samples[10] = std::numeric_limits<float>::quiet_NaN();
  Publish(bad);

  ASSERT_TRUE(WaitStatus([](const auto& m) { return m.blocks_processed == 5; }, 60s))
      << "processed " << last_status_.blocks_processed;
  const std::uint64_t processed_a = last_status_.blocks_processed;
  ASSERT_TRUE(WaitStatusOf(daemon_id_, b,
                           [](const auto& m) {
                             return m.blocks_processed == 3 && m.blocks_rejected == 1;
                           },
                           60s));
  const std::uint64_t processed_b = last_status_.blocks_processed;

  const std::string pa = "{machine=\"" + a + "\"}";
  const std::string pb = "{machine=\"" + b + "\"}";
  const auto t0 = std::chrono::steady_clock::now();
  const HttpReply first = HttpGet(port, "/metrics");
  const double scrape_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  ASSERT_EQ(first.status, 200) << daemon_->Log();
  std::cout << "scrape of " << first.body.size() << " bytes took " << scrape_ms << " ms\n";
  // The counters are read live, so the scrape agrees with Status once both have the blocks.
  const std::string text = ScrapeUntil(port, "gearpath_blocks_processed_total" + pb,
                                       static_cast<double>(processed_b), 10s);
  std::cout << text;
  EXPECT_EQ(SampleValue(text, "gearpath_blocks_processed_total" + pa),
            static_cast<double>(processed_a));
  EXPECT_EQ(SampleValue(text, "gearpath_blocks_processed_total" + pb),
            static_cast<double>(processed_b));
  EXPECT_EQ(SampleValue(text, "gearpath_blocks_received_total" + pa), 5.0);
  EXPECT_EQ(SampleValue(text, "gearpath_blocks_received_total" + pb), 4.0);
  EXPECT_EQ(SampleValue(text, "gearpath_blocks_rejected_total{machine=\"" + b +
                                  "\",reason=\"non_finite\"}"),
            1.0);
  EXPECT_EQ(SampleValue(text, "gearpath_blocks_rejected_total{machine=\"" + a +
                                  "\",reason=\"non_finite\"}"),
            0.0);
  EXPECT_EQ(SampleValue(text, "gearpath_blocks_lost_total" + pa), 0.0);
  EXPECT_EQ(SampleValue(text, "gearpath_block_latency_seconds_count" + pa), 5.0);
  EXPECT_EQ(SampleValue(text, "gearpath_block_latency_seconds_bucket{machine=\"" + a +
                                  "\",le=\"+Inf\"}"),
            5.0);
  EXPECT_GT(SampleValue(text, "gearpath_block_latency_seconds_sum" + pa), 0.0);
  for (const std::string& machine : {a, b}) {
    double hot = 0.0;
    for (const char* state : {"learning", "no_fault", "suspected", "alarm"}) {
      const double v = SampleValue(text, "gearpath_machine_state{machine=\"" + machine +
                                             "\",state=\"" + state + "\"}");
      EXPECT_TRUE(v == 0.0 || v == 1.0) << machine << " " << state << " = " << v;
      hot += v;
    }
    EXPECT_EQ(hot, 1.0) << machine;
    EXPECT_EQ(SampleValue(text, "gearpath_machine_speed_hz{machine=\"" + machine + "\"}"),
              10.0);
  }
  EXPECT_EQ(SampleValue(text, "gearpath_machine_baseline_epoch{machine=\"" + a + "\",epoch=\"\"}"),
            1.0);
  EXPECT_EQ(SampleValue(text, "gearpath_machine_baseline_epoch{machine=\"" + b +
                                  "\",epoch=\"after the 2026-11 overhaul\"}"),
            1.0);
  EXPECT_EQ(SampleValue(text, "gearpath_daemon_state{state=\"running\"}"), 1.0);
  EXPECT_EQ(SampleValue(text, "gearpath_machines"), 2.0);
  EXPECT_NE(text.find("gearpath_build_info{version=\""), std::string::npos);
  EXPECT_GT(SampleValue(text, "gearpath_daemon_uptime_seconds"), 0.0);

  EXPECT_EQ(HttpGet(port, "/nothing").status, 404);
}

TEST_F(GearpathdMetrics, AReloadThatDisablesMetricsClosesTheEndpoint) {
  const int port = MetricsPort();
  ASSERT_GT(port, 0) << daemon_->Log();
  ASSERT_EQ(HttpGet(port, "/metrics").status, 200);
  json off = config_;
  off["metrics"]["enabled"] = false;
  WriteConfig(off);
  daemon_->Signal(SIGHUP);
  ASSERT_TRUE(daemon_->WaitForLog("metrics endpoint stopped", 60s)) << daemon_->Log();
  ASSERT_TRUE(daemon_->WaitForLog("reload: now running 2 machine(s)", 60s)) << daemon_->Log();
  EXPECT_EQ(HttpGet(port, "/metrics").status, 0) << "the endpoint still answers";
}

// Listens on a free loopback port until destroyed; port() says which.
class PortHolder {
 public:
  PortHolder() : fd_(socket(AF_INET, SOCK_STREAM, 0)) {
    sockaddr_in addr{};
    addr.sin_family = AF_INET;
    addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    socklen_t len = sizeof(addr);
    if (fd_ >= 0 && bind(fd_, reinterpret_cast<sockaddr*>(&addr), sizeof(addr)) == 0 &&
        listen(fd_, 1) == 0 &&
        getsockname(fd_, reinterpret_cast<sockaddr*>(&addr), &len) == 0) {
      port_ = ntohs(addr.sin_port);
    }
  }
  ~PortHolder() {
    if (fd_ >= 0) close(fd_);
  }
  PortHolder(const PortHolder&) = delete;
  PortHolder& operator=(const PortHolder&) = delete;
  int port() const { return port_; }

 private:
  int fd_;
  int port_ = 0;
};

TEST_F(GearpathdMetrics, AReloadOntoABusyPortIsRefusedAndTheEndpointStaysWhereItWas) {
  const int port = MetricsPort();
  ASSERT_GT(port, 0) << daemon_->Log();
  PortHolder busy;
  ASSERT_GT(busy.port(), 0);
  json moved = config_;
  moved["metrics"]["port"] = busy.port();
  WriteConfig(moved);
  daemon_->Signal(SIGHUP);
  ASSERT_TRUE(daemon_->WaitForLog("reload failed, still running the previous configuration",
                                  60s))
      << daemon_->Log();
  EXPECT_NE(daemon_->Log().find("metrics endpoint: cannot listen on 127.0.0.1:" +
                                std::to_string(busy.port())),
            std::string::npos);
  // The previous endpoint is back on its own port (chosen by the kernel at start).
  EXPECT_EQ(HttpGet(port, "/metrics").status, 200);
}

// A port that cannot be bound stops the start-up (exit 1) with the address in the message:
// an operator who asked for metrics learns at once that there are none.
TEST(GearpathdMetricsStartup, APortInUseStopsTheStartWithExitCode1) {
  PortHolder busy;
  const int port = busy.port();
  ASSERT_GT(port, 0);

  const auto dir = std::filesystem::temp_directory_path() /
                   ("gearpathd_metrics_port_" + std::to_string(getpid()));
  std::filesystem::create_directories(dir);
  json config = json::parse(daemon::DefaultConfigText());
  config["dds"]["domain_id"] = 100 + static_cast<int>(getpid()) % 120;
  config["metrics"] = {{"enabled", true}, {"port", port}};
  const std::string config_path = (dir / "gearpathd.json").string();
  std::ofstream(config_path) << config.dump(2);
  std::string log;
  const auto code = RunToCompletion(GEARPATHD_PATH, {"--config", config_path},
                                    (dir / "gearpathd.log").string(), &log, 60s);
  std::filesystem::remove_all(dir);
  ASSERT_TRUE(code.has_value()) << "gearpathd did not stop:\n" << log;
  EXPECT_EQ(*code, 1) << log;
  EXPECT_NE(log.find("metrics endpoint: cannot listen on 127.0.0.1:" + std::to_string(port)),
            std::string::npos)
      << log;
}

}  // namespace
}  // namespace gearpath::testing
