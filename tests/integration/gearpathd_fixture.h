// Integration fixture: gearpathd as a child process on a private loopback DDS domain, and the
// test as acquisition bridge (AccelBlock writer) and plant (result and Status readers).
//
// Each test gets its own domain id (from its pid) and its own machine and daemon ids, so tests
// running in parallel never see each other's traffic. Every wait has a deadline; ctest's
// TIMEOUT is the outer watchdog. The daemon runs the test configuration: the embedded default
// (builtin:table1) with a fast status period and a short baseline.
#pragma once

#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "core/common/accel_block.h"
#include "core/model/gear_train.h"
#include "core/model/lumped_gearbox_model.h"
#include "core/simulation/gearbox_simulator.h"
#include "daemon/daemon_config.h"
#include "daemon/machine_setup_builder.h"
#include "idl/dds/gearpath_topics.h"
#include "tests/daemon/child_process.h"
#include "tests/integration/wire_block.h"

namespace gearpath::testing {

using namespace std::chrono_literals;
using nlohmann::json;

inline Axis AxisOf(const std::string& name) {
  return name == "y" ? Axis::kY : name == "z" ? Axis::kZ : Axis::kX;
}

class GearpathdOverDds : public ::testing::Test {
 protected:
  static constexpr double kSampleRate = 8000.0;
  static constexpr std::uint32_t kBlockLength = 8192;

  // Adjusts the test configuration before the daemon starts.
  virtual void Configure(json& config) { (void)config; }

  void SetUp() override {
    const int pid = static_cast<int>(getpid());
    domain_id_ = 100 + pid % 120;
    suffix_ = std::to_string(pid);
    machine_id_ = "gb_" + suffix_;
    daemon_id_ = "gearpathd_" + suffix_;
    dir_ = std::filesystem::temp_directory_path() /
           ("gearpathd_it_" + suffix_ + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::create_directories(dir_);
    config_path_ = (dir_ / "gearpathd.json").string();

    config_ = json::parse(daemon::DefaultConfigText());
    config_["daemon"]["id"] = daemon_id_;
    config_["daemon"]["status_period_s"] = 0.1;
    config_["daemon"]["throughput_log_period_s"] = 1.0;
    config_["daemon"]["log_level"] = "debug";
    config_["dds"]["domain_id"] = domain_id_;
    config_["machines"][0]["id"] = machine_id_;
    config_["machines"][0]["acquisition"]["max_samples_per_channel"] = kBlockLength;
    config_["machines"][0]["analysis"]["baseline"]["learning_blocks"] = 4;
    Configure(config_);
    WriteConfig(config_);

    // The channel layout the daemon expects: the built-in set's response channels.
    auto set = daemon::BuiltinFrfSet("table1");
    ASSERT_TRUE(set.ok()) << set.error();
    for (const auto& ch : set->channels) {
      channels_.push_back({ch.sensor, AxisOf(ch.axis), "m/s^2", 0.0});
    }

    domain_ = std::make_unique<dds::Domain>(domain_id_, dds::kLoopbackConfigXml,
                                            dds::EnvironmentConfig::kIgnore);
    participant_ = std::make_unique<dds::Participant>(*domain_);
    block_topic_ = std::make_unique<dds::Topic<gearpath_AccelBlock>>(*participant_);
    block_writer_ = std::make_unique<dds::Writer<gearpath_AccelBlock>>(*block_topic_);
    block_v2_topic_ = std::make_unique<dds::Topic<gearpath_AccelBlockV2>>(*participant_);
    block_v2_writer_ = std::make_unique<dds::Writer<gearpath_AccelBlockV2>>(*block_v2_topic_);
    status_topic_ = std::make_unique<dds::Topic<gearpath_Status>>(*participant_);
    status_reader_ = std::make_unique<dds::Reader<gearpath_Status>>(*status_topic_);
    dominant_topic_ = std::make_unique<dds::Topic<gearpath_DominantPath>>(*participant_);
    dominant_reader_ = std::make_unique<dds::Reader<gearpath_DominantPath>>(*dominant_topic_);
    gear_topic_ = std::make_unique<dds::Topic<gearpath_SuspectedGear>>(*participant_);
    gear_reader_ = std::make_unique<dds::Reader<gearpath_SuspectedGear>>(*gear_topic_);
    indicators_topic_ = std::make_unique<dds::Topic<gearpath_EnvelopeIndicators>>(*participant_);
    indicators_reader_ =
        std::make_unique<dds::Reader<gearpath_EnvelopeIndicators>>(*indicators_topic_);
    condition_topic_ = std::make_unique<dds::Topic<gearpath_ConditionIndicators>>(*participant_);
    condition_reader_ =
        std::make_unique<dds::Reader<gearpath_ConditionIndicators>>(*condition_topic_);

    // With daemon_environment_ set (by Configure), /usr/bin/env puts those variables into the
    // daemon's environment (ChildProcess clears CYCLONEDDS_URI) and execs it in place.
    std::vector<std::string> argv = daemon_environment_;
    argv.insert(argv.end(), {GEARPATHD_PATH, "--config", config_path_});
    daemon_ = daemon_environment_.empty()
                  ? std::make_unique<ChildProcess>(
                        GEARPATHD_PATH, std::vector<std::string>{"--config", config_path_},
                        (dir_ / "gearpathd.log").string())
                  : std::make_unique<ChildProcess>("/usr/bin/env", argv,
                                                   (dir_ / "gearpathd.log").string());
    ASSERT_TRUE(daemon_->started());
    if (!wait_until_ready_) return;
    // Ready = its Status arrives and it has discovered our block writer.
    ASSERT_TRUE(WaitStatus([](const gearpath_MachineStatus&) { return true; }, 90s))
        << "gearpathd did not publish Status; its log:\n"
        << daemon_->Log();
    ASSERT_TRUE(block_writer_->WaitForReaders(1, 30s).ok()) << daemon_->Log();
  }

  void TearDown() override {
    if (daemon_ && daemon_->running()) {
      daemon_->Signal(SIGTERM);
      (void)daemon_->WaitExit(5s);
    }
    if (HasFailure() && daemon_) std::cerr << "gearpathd log:\n" << daemon_->Log() << "\n";
    daemon_.reset();
    condition_reader_.reset();
    condition_topic_.reset();
    indicators_reader_.reset();
    indicators_topic_.reset();
    gear_reader_.reset();
    gear_topic_.reset();
    dominant_reader_.reset();
    dominant_topic_.reset();
    status_reader_.reset();
    status_topic_.reset();
    block_v2_writer_.reset();
    block_v2_topic_.reset();
    block_writer_.reset();
    block_topic_.reset();
    participant_.reset();
    domain_.reset();
    std::filesystem::remove_all(dir_);
  }

  void WriteConfig(const json& config) { std::ofstream(config_path_) << config.dump(2); }

  // A healthy-looking block: independent Gaussian noise on every expected channel.
  AccelBlock NoiseBlock(std::uint64_t sequence) {
    AccelBlock b;
    b.machine_id = machine_id_;
    b.sequence = sequence;
    b.t0_ns = static_cast<std::int64_t>(sequence) * 1'000'000'000;
    b.sample_rate_hz = kSampleRate;
    b.speed_hz = 10.0;
    b.speed_source = SpeedSource::kAcquisition;
    b.channels = channels_;
    b.samples_per_channel = kBlockLength;
    std::normal_distribution<float> noise(0.0f, 1.0f);
    b.samples.resize(channels_.size() * kBlockLength);
    for (float& x : b.samples) x = noise(rng_);
    return b;
  }

  // The simulated Table-1 gearbox streaming as our machine: channels p1..p3, the rows of
  // builtin:table1 (Eq. 22), 5 % noise.
  GearboxSimulator Table1Simulator(FaultType type, const std::string& gear, std::uint64_t seed) {
    auto model = LumpedGearboxModel::Create(Table1Parameters());
    EXPECT_TRUE(model.ok()) << model.error();
    SimulatorConfig c;
    c.machine_id = machine_id_;
    c.fault.type = type;
    c.fault.gear = gear;
    c.sample_rate_hz = kSampleRate;
    c.block_length = kBlockLength;
    c.noise_relative = 0.05;
    c.seed = seed;
    c.include_housing_channel = false;
    auto sim = GearboxSimulator::Create(model.value(), GearTrain::Table1(), c);
    EXPECT_TRUE(sim.ok()) << sim.error();
    return std::move(sim.value());
  }

  void Publish(const AccelBlock& block) {
    dds::Owned<gearpath_AccelBlock> sample;
    ASSERT_TRUE(ToWire(block, sample));
    Status st = block_writer_->Write(*sample);
    ASSERT_TRUE(st.ok()) << st.error();
  }

  // The same block with its load, on the AccelBlockV2 topic.
  void PublishWithLoad(const AccelBlock& block) {
    dds::Owned<gearpath_AccelBlockV2> sample;
    Status filled = dds::FillWireBlock(block.view(), "N m", *sample);
    ASSERT_TRUE(filled.ok()) << filled.error();
    Status st = block_v2_writer_->Write(*sample);
    ASSERT_TRUE(st.ok()) << st.error();
  }

  // Stops the daemon with `signal`, waits until our block writers have lost it (a killed peer
  // goes when its lease expires), drops the results still unread, then starts a new daemon on
  // the same configuration and waits until it is ready.
  void RestartDaemon(int signal) {
    daemon_->Signal(signal);
    ASSERT_TRUE(daemon_->WaitExit(30s)) << "gearpathd did not exit on signal " << signal;
    const auto deadline = std::chrono::steady_clock::now() + 60s;
    for (;;) {
      const Result<std::uint32_t> matched = block_writer_->MatchedReaders();
      const Result<std::uint32_t> matched_v2 = block_v2_writer_->MatchedReaders();
      ASSERT_TRUE(matched.ok() && matched_v2.ok());
      if (*matched == 0 && *matched_v2 == 0) break;
      ASSERT_LT(std::chrono::steady_clock::now(), deadline) << "the dead reader stayed matched";
      std::this_thread::sleep_for(50ms);
    }
    DrainResults();
    ++generation_;
    daemon_ = std::make_unique<ChildProcess>(
        GEARPATHD_PATH, std::vector<std::string>{"--config", config_path_},
        (dir_ / ("gearpathd." + std::to_string(generation_) + ".log")).string());
    ASSERT_TRUE(daemon_->started());
    ASSERT_TRUE(WaitStatus([](const gearpath_MachineStatus&) { return true; }, 90s))
        << daemon_->Log();
    ASSERT_TRUE(block_writer_->WaitForReaders(1, 30s).ok()) << daemon_->Log();
    ASSERT_TRUE(block_v2_writer_->WaitForReaders(1, 30s).ok()) << daemon_->Log();
  }

  // Takes every SuspectedGear and Status sample waiting in our readers.
  void DrainResults() {
    std::vector<dds::Owned<gearpath_SuspectedGear>> g(32);
    std::vector<dds::Owned<gearpath_Status>> s(32);
    std::vector<dds::SampleInfo> infos(32);
    for (auto n = gear_reader_->Take(g, infos); n.ok() && *n > 0;
         n = gear_reader_->Take(g, infos)) {
    }
    for (auto n = status_reader_->Take(s, infos); n.ok() && *n > 0;
         n = status_reader_->Take(s, infos)) {
    }
  }

  // Waits for a Status of our daemon whose entry for our machine satisfies `pred`; also keeps
  // the last one seen (last_status_, last_state_).
  bool WaitStatus(const std::function<bool(const gearpath_MachineStatus&)>& pred,
                  std::chrono::milliseconds timeout) {
    return WaitStatusOf(daemon_id_, machine_id_, pred, timeout);
  }

  // The same for any daemon and machine. Status samples of other daemons are consumed.
  bool WaitStatusOf(const std::string& daemon_id, const std::string& machine_id,
                    const std::function<bool(const gearpath_MachineStatus&)>& pred,
                    std::chrono::milliseconds timeout) {
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    std::vector<dds::Owned<gearpath_Status>> samples(8);
    std::vector<dds::SampleInfo> infos(8);
    while (std::chrono::steady_clock::now() < deadline) {
      auto n = status_reader_->Take(samples, infos);
      if (!n) return false;
      for (std::size_t i = 0; i < *n; ++i) {
        if (!infos[i].valid_data) continue;
        const gearpath_Status& s = *samples[i];
        if (dds::GetString(s.daemon_id) != daemon_id) continue;
        last_state_ = s.state;
        for (const auto& m : dds::View(s.machines)) {
          if (dds::GetString(m.machine_id) != machine_id) continue;
          last_status_ = m;
          if (pred(m)) return true;
        }
      }
      std::this_thread::sleep_for(20ms);
    }
    return false;
  }

  // Waits for a sample of `reader` for our machine that satisfies `pred`.
  template <typename T>
  std::optional<dds::Owned<T>> WaitResult(dds::Reader<T>& reader,
                                          const std::function<bool(const T&)>& pred,
                                          std::chrono::milliseconds timeout) {
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    std::vector<dds::Owned<T>> samples(8);
    std::vector<dds::SampleInfo> infos(8);
    while (std::chrono::steady_clock::now() < deadline) {
      auto n = reader.Take(samples, infos);
      if (!n) return std::nullopt;
      for (std::size_t i = 0; i < *n; ++i) {
        if (infos[i].valid_data && dds::GetString(samples[i]->machine_id) == machine_id_ &&
            pred(*samples[i])) {
          return std::move(samples[i]);
        }
      }
      std::this_thread::sleep_for(20ms);
    }
    return std::nullopt;
  }

  int domain_id_ = 0;
  std::string suffix_;
  std::string machine_id_;
  std::string daemon_id_;
  std::filesystem::path dir_;
  std::string config_path_;
  json config_;
  std::vector<std::string> daemon_environment_;  // "NAME=value" for the daemon, if any
  // false (set in a test's constructor): SetUp returns once the daemon is started, and the
  // test decides what to wait for.
  bool wait_until_ready_ = true;
  std::vector<ChannelInfo> channels_;
  std::mt19937 rng_{12345};
  gearpath_MachineStatus last_status_{};
  int last_state_ = -1;
  int generation_ = 0;  // daemons restarted (RestartDaemon), for their log files' names

  std::unique_ptr<dds::Domain> domain_;
  std::unique_ptr<dds::Participant> participant_;
  std::unique_ptr<dds::Topic<gearpath_AccelBlock>> block_topic_;
  std::unique_ptr<dds::Writer<gearpath_AccelBlock>> block_writer_;
  std::unique_ptr<dds::Topic<gearpath_AccelBlockV2>> block_v2_topic_;
  std::unique_ptr<dds::Writer<gearpath_AccelBlockV2>> block_v2_writer_;
  std::unique_ptr<dds::Topic<gearpath_Status>> status_topic_;
  std::unique_ptr<dds::Reader<gearpath_Status>> status_reader_;
  std::unique_ptr<dds::Topic<gearpath_DominantPath>> dominant_topic_;
  std::unique_ptr<dds::Reader<gearpath_DominantPath>> dominant_reader_;
  std::unique_ptr<dds::Topic<gearpath_SuspectedGear>> gear_topic_;
  std::unique_ptr<dds::Reader<gearpath_SuspectedGear>> gear_reader_;
  std::unique_ptr<dds::Topic<gearpath_EnvelopeIndicators>> indicators_topic_;
  std::unique_ptr<dds::Reader<gearpath_EnvelopeIndicators>> indicators_reader_;
  std::unique_ptr<dds::Topic<gearpath_ConditionIndicators>> condition_topic_;
  std::unique_ptr<dds::Reader<gearpath_ConditionIndicators>> condition_reader_;
  std::unique_ptr<ChildProcess> daemon_;
};

}  // namespace gearpath::testing
