// No machine cap (issue 9): one gearpathd serving 100 machines over loopback DDS. Blocks of a
// machine beyond the 64th are processed, its MachineHealth instance (one per daemon and machine)
// arrives with the right counters, Status carries the first 64 machines (its wire bound) and
// `gearpath monitor` shows the machine from MachineHealth. Every wait has a deadline (ctest's
// TIMEOUT is the outer watchdog); waits are on a DDS WaitSet or on the condition polled.
#include <gtest/gtest.h>

#include <array>
#include <set>
#include <sstream>
#include <string>

#include "tests/integration/gearpathd_fixture.h"

namespace gearpath::testing {
namespace {

constexpr int kMachines = 100;
constexpr int kFar = 99;  // the machine the blocks go to: far beyond Status' 64

class GearpathdManyMachines : public GearpathdOverDds {
 protected:
  void Configure(json& config) override {
    json one = config["machines"][0];
    config["machines"] = json::array();
    for (int i = 0; i < kMachines; ++i) {
      json m = one;
      m["id"] = MachineId(i);
      // Only the machines that get blocks prepare their block length before READY: 100
      // machines start quickly on a loaded 2-core host (the others would configure the
      // length with their first block).
      if (i != 0 && i != kFar) {
        m["acquisition"]["prepare_samples_per_channel"] = json::array();
      }
      config["machines"].push_back(m);
    }
    // 100 MachineHealth samples per period: a period of 0.2 s is plenty for the waits.
    config["daemon"]["status_period_s"] = 0.2;
    config["daemon"]["log_level"] = "info";
  }

  // Machine 0 keeps the fixture's id, whose Status entry SetUp waits for.
  std::string MachineId(int i) const {
    return i == 0 ? machine_id_ : machine_id_ + "_" + std::to_string(i);
  }

  void SetUp() override {
    GearpathdOverDds::SetUp();
    if (HasFatalFailure()) return;
    health_topic_ = std::make_unique<dds::Topic<gearpath_MachineHealth>>(*participant_);
    health_reader_ = std::make_unique<dds::Reader<gearpath_MachineHealth>>(*health_topic_);
    health_ready_ = std::make_unique<dds::ReadCondition>(*health_reader_);
    waitset_ = std::make_unique<dds::WaitSet>(*participant_);
    waitset_->Attach(*health_ready_, 1);
  }

  void TearDown() override {
    waitset_.reset();
    health_ready_.reset();
    health_reader_.reset();
    health_topic_.reset();
    GearpathdOverDds::TearDown();
  }

  // Takes MachineHealth samples of our daemon until `pred` holds for one (kept in last_health_)
  // or `timeout` passes; `seen` collects the machine ids of every sample taken.
  bool WaitHealth(const std::function<bool(const gearpath_MachineHealth&)>& pred,
                  std::chrono::milliseconds timeout, std::set<std::string>* seen = nullptr) {
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    std::vector<dds::Owned<gearpath_MachineHealth>> samples(128);
    std::vector<dds::SampleInfo> infos(128);
    std::array<dds_attach_t, 1> triggered{};
    for (;;) {
      auto n = health_reader_->Take(samples, infos);
      if (!n) return false;
      for (std::size_t i = 0; i < *n; ++i) {
        if (!infos[i].valid_data) continue;
        const gearpath_MachineHealth& h = *samples[i];
        if (dds::GetString(h.daemon_id) != daemon_id_) continue;
        if (seen != nullptr) seen->insert(std::string(dds::GetString(h.machine_id)));
        if (pred(h)) {
          last_health_ = std::move(samples[i]);
          return true;
        }
      }
      const auto left = deadline - std::chrono::steady_clock::now();
      if (left <= std::chrono::steady_clock::duration::zero()) return false;
      if (!waitset_->Wait(triggered, std::min<std::chrono::nanoseconds>(left, 1s))) return false;
    }
  }

  std::unique_ptr<dds::Topic<gearpath_MachineHealth>> health_topic_;
  std::unique_ptr<dds::Reader<gearpath_MachineHealth>> health_reader_;
  std::unique_ptr<dds::ReadCondition> health_ready_;
  std::unique_ptr<dds::WaitSet> waitset_;
  dds::Owned<gearpath_MachineHealth> last_health_;
};

TEST_F(GearpathdManyMachines, AMachineBeyondTheSixtyFourthIsProcessedAndReportedOnMachineHealth) {
  const std::string far = MachineId(kFar);

  // Every configured machine has its instance, each saying where it stands in the daemon.
  std::set<std::string> seen;
  EXPECT_TRUE(WaitHealth([&](const gearpath_MachineHealth&) {
    return seen.size() == static_cast<std::size_t>(kMachines);
  }, 60s, &seen))
      << seen.size() << " of " << kMachines << " machines on MachineHealth\n" << daemon_->Log();

  // Three good blocks, then one at the wrong sample rate.
  for (std::uint64_t seq = 0; seq < 3; ++seq) {
    AccelBlock b = NoiseBlock(seq);
    b.machine_id = far;
    Publish(b);
  }
  AccelBlock bad = NoiseBlock(3);
  bad.machine_id = far;
  bad.sample_rate_hz = kSampleRate / 2;
  Publish(bad);

  // Its results are published like any machine's.
  std::vector<std::uint64_t> verdicts;
  const auto deadline = std::chrono::steady_clock::now() + 120s;
  std::vector<dds::Owned<gearpath_SuspectedGear>> gears(8);
  std::vector<dds::SampleInfo> infos(8);
  while (verdicts.size() < 3) {
    ASSERT_LT(std::chrono::steady_clock::now(), deadline)
        << "watchdog: " << verdicts.size() << " of 3 verdicts of " << far << "\n"
        << daemon_->Log();
    auto n = gear_reader_->Take(gears, infos);
    ASSERT_TRUE(n.ok()) << n.error();
    for (std::size_t k = 0; k < *n; ++k) {
      if (infos[k].valid_data && dds::GetString(gears[k]->machine_id) == far) {
        verdicts.push_back(gears[k]->block_sequence);
      }
    }
    if (*n == 0) std::this_thread::sleep_for(20ms);
  }
  EXPECT_EQ(verdicts, (std::vector<std::uint64_t>{0, 1, 2}));

  // Its MachineHealth instance counts them.
  ASSERT_TRUE(WaitHealth([&](const gearpath_MachineHealth& h) {
    return dds::GetString(h.machine_id) == far && h.blocks_received == 4;
  }, 60s)) << daemon_->Log();
  const gearpath_MachineHealth& h = *last_health_;
  EXPECT_EQ(h.machine_index, static_cast<std::uint32_t>(kFar));
  EXPECT_EQ(h.machine_count, static_cast<std::uint32_t>(kMachines));
  EXPECT_EQ(h.daemon_state, gearpath_RUNNING);
  EXPECT_GT(h.timestamp_ns, 0);
  EXPECT_TRUE(h.publishing_results);
  EXPECT_EQ(h.blocks_processed, 3u);
  EXPECT_EQ(h.blocks_rejected, 1u);
  EXPECT_EQ(h.blocks_lost, 0u);
  EXPECT_EQ(h.last_block_sequence, 2u);
  EXPECT_EQ(h.last_block_t0_ns, 2'000'000'000);
  // The fixture's baseline needs 4 healthy blocks: 3 are not enough.
  EXPECT_EQ(h.fault_state, gearpath_LEARNING);
  EXPECT_EQ(std::string(dds::GetString(h.last_rejection_reason)).rfind("wrong_sample_rate: ", 0),
            0u)
      << dds::GetString(h.last_rejection_reason);
  EXPECT_GT(h.latency_last_ms, 0.0);
  EXPECT_GE(h.latency_max_ms, h.latency_last_ms);
  EXPECT_GT(h.last_condition_number, 0.0);

  // A machine that got no block is there too, with nothing counted.
  ASSERT_TRUE(WaitHealth([&](const gearpath_MachineHealth& m) {
    return dds::GetString(m.machine_id) == MachineId(70);
  }, 30s));
  EXPECT_EQ(last_health_->blocks_received, 0u);
  EXPECT_EQ(last_health_->machine_index, 70u);

  // Status carries the first 64 machines in configuration order (its wire bound), not more.
  std::vector<dds::Owned<gearpath_Status>> statuses(8);
  std::vector<dds::SampleInfo> status_infos(8);
  bool checked = false;
  const auto status_deadline = std::chrono::steady_clock::now() + 30s;
  while (!checked && std::chrono::steady_clock::now() < status_deadline) {
    auto n = status_reader_->Take(statuses, status_infos);
    ASSERT_TRUE(n.ok()) << n.error();
    for (std::size_t k = 0; k < *n && !checked; ++k) {
      if (!status_infos[k].valid_data || dds::GetString(statuses[k]->daemon_id) != daemon_id_) {
        continue;
      }
      const auto machines = dds::View(statuses[k]->machines);
      ASSERT_EQ(machines.size(), static_cast<std::size_t>(gearpath_MAX_MACHINES));
      for (std::size_t i = 0; i < machines.size(); ++i) {
        EXPECT_EQ(dds::GetString(machines[i].machine_id), MachineId(static_cast<int>(i)));
      }
      checked = true;
    }
    if (!checked) std::this_thread::sleep_for(20ms);
  }
  EXPECT_TRUE(checked) << "no Status of the daemon within 30 s";
  EXPECT_NE(daemon_->Log().find("100 machines: Status lists the first 64"), std::string::npos)
      << daemon_->Log();
}

TEST_F(GearpathdManyMachines, TheMonitorShowsAMachineBeyondTheSixtyFourth) {
  const std::string far = MachineId(kFar);
  for (std::uint64_t seq = 0; seq < 2; ++seq) {
    AccelBlock b = NoiseBlock(seq);
    b.machine_id = far;
    Publish(b);
  }
  // The monitor's own --timeout ends it even if the line never comes.
  ChildProcess monitor(GEARPATH_TOOL_PATH,
                       {"monitor", "--json", "--domain", std::to_string(domain_id_), "--machine",
                        far, "--timeout", "120"},
                       (dir_ / "monitor.log").string());
  ASSERT_TRUE(monitor.started());
  const auto deadline = std::chrono::steady_clock::now() + 120s;
  bool shown = false;
  while (!shown) {
    std::istringstream lines(monitor.Log());
    for (std::string line; std::getline(lines, line) && !shown;) {
      if (line.find(R"("topic":"MachineHealth")") == std::string::npos) continue;
      const json j = json::parse(line, nullptr, /*allow_exceptions=*/false);
      shown = !j.is_discarded() && j.value("topic", "") == "MachineHealth" &&
              j["machine"] == far && j["daemon"] == daemon_id_ && j["processed"] == 2 &&
              j["index"] == kFar && j["machine_count"] == kMachines;
    }
    if (shown) break;
    ASSERT_LT(std::chrono::steady_clock::now(), deadline)
        << "watchdog: the monitor showed no MachineHealth of " << far << " with 2 blocks\n"
        << monitor.Log() << "\n--- gearpathd log:\n" << daemon_->Log();
    ASSERT_FALSE(monitor.WaitExit(0ms).has_value()) << "the monitor exited:\n" << monitor.Log();
    std::this_thread::sleep_for(50ms);
  }
  monitor.Signal(SIGTERM);
  (void)monitor.WaitExit(10s);
}

// A reload that drops a machine disposes its MachineHealth instance (subscribers and late
// joiners stop seeing it); one that configures more machines than the block reader was sized
// for at start-up (max(256, 2 x 100) = 256) is refused with that reason, and the daemon runs
// on.
TEST_F(GearpathdManyMachines, AReloadDisposesARemovedMachineAndRefusesMoreThanTheReaderHolds) {
  const std::string far = MachineId(kFar);
  ASSERT_TRUE(WaitHealth([&](const gearpath_MachineHealth& h) {
    return dds::GetString(h.machine_id) == far;
  }, 30s)) << daemon_->Log();

  json fewer = config_;
  fewer["machines"].erase(static_cast<std::size_t>(kFar));
  WriteConfig(fewer);
  daemon_->Signal(SIGHUP);
  ASSERT_TRUE(daemon_->WaitForLog("reload: now running 99 machine(s)", 60s)) << daemon_->Log();
  bool disposed = false;
  const auto deadline = std::chrono::steady_clock::now() + 30s;
  std::vector<dds::Owned<gearpath_MachineHealth>> samples(128);
  std::vector<dds::SampleInfo> infos(128);
  std::array<dds_attach_t, 1> triggered{};
  while (!disposed && std::chrono::steady_clock::now() < deadline) {
    auto n = health_reader_->Take(samples, infos);
    ASSERT_TRUE(n.ok()) << n.error();
    for (std::size_t i = 0; i < *n; ++i) {
      // The state arrives on the instance's last sample if that one is still unread, else on
      // an invalid sample carrying only the key.
      disposed = disposed || (infos[i].instance_state == DDS_NOT_ALIVE_DISPOSED_INSTANCE_STATE &&
                              dds::GetString(samples[i]->machine_id) == far &&
                              dds::GetString(samples[i]->daemon_id) == daemon_id_);
    }
    if (!disposed) {
      ASSERT_TRUE(waitset_->Wait(triggered, 1s).ok());
    }
  }
  EXPECT_TRUE(disposed) << "no dispose of " << far << "'s MachineHealth instance";
  // Every remaining machine is still reported, numbered in the new configuration.
  ASSERT_TRUE(WaitHealth([&](const gearpath_MachineHealth& h) {
    return dds::GetString(h.machine_id) == MachineId(98) && h.machine_count == 99;
  }, 30s)) << daemon_->Log();

  json more = fewer;
  const json one = more["machines"][1];
  for (int i = kMachines; i < 258; ++i) {  // 99 + 158 = 257 machines
    json m = one;
    m["id"] = MachineId(i);
    more["machines"].push_back(m);
  }
  WriteConfig(more);
  daemon_->Signal(SIGHUP);
  EXPECT_TRUE(daemon_->WaitForLog("machines: 257 machines exceed the 256 the block reader was "
                                  "sized for at start-up",
                                  30s))
      << daemon_->Log();
  EXPECT_TRUE(daemon_->WaitForLog("reload failed, still running the previous configuration", 5s));
  EXPECT_TRUE(daemon_->running());
}

}  // namespace
}  // namespace gearpath::testing
