// DDS Security over loopback (issue 11). At test time tools/make-security-fixtures.sh makes a
// test PKI (CA, signed governance, identities gearpathd / acquisition / monitor with their
// permissions) and a second, foreign one; gearpathd runs with its identity (`dds.security`) on a
// deployment file (`dds.config`: the loopback configuration plus a per-test discovery tag).
//   (a) the authorised publisher's blocks (`gearpath sim --publish --dds-security
//       acquisition...`) are processed and the authorised monitor (`gearpath monitor
//       --dds-security monitor...`) reads the results;
//   (b) participants without valid credentials (no security at all; a foreign CA's identities
//       with permissions of their own) can neither inject a block that gets processed, nor read
//       a fault topic, nor publish a SuspectedGear that the monitor shows;
//   (c) a participant whose permissions allow only reading (the monitor identity) cannot
//       publish blocks, in process or through `gearpath sim`.
// Nothing is skipped: without openssl the fixture script fails and so does the test.
//
// Each in-process participant has its own local domain (ids D+1...) joined to the daemon's
// domain D on the wire by Discovery/ExternalDomainId, so everything goes through UDP on
// 127.0.0.1 and through the security plugins; one identity per domain also avoids a crash of
// Cyclone 0.10.2 when a secure participant is deleted from a domain that has an unsecured one.
// Every wait has a deadline; ctest's TIMEOUT is the watchdog.
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "daemon/daemon_config.h"
#include "daemon/machine_setup_builder.h"
#include "idl/dds/domain.h"
#include "idl/dds/gearpath_topics.h"
#include "idl/dds/security.h"
#include "tests/daemon/child_process.h"
#include "tests/integration/wire_block.h"
#include "tests/tools/tool_process.h"

namespace gearpath::testing {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;
using nlohmann::json;
using tools::testing::ReadText;
using tools::testing::ToolProcess;
using Clock = std::chrono::steady_clock;

constexpr int kBlocks = 3;  // the authorised publisher's blocks

dds::SecurityFiles FilesOf(const fs::path& pki, const std::string& who) {
  const auto f = [&](const std::string& name) { return (pki / name).string(); };
  return {f("ca_cert.pem"), f(who + "_cert.pem"), f(who + "_key.pem"),
          f("ca_cert.pem"), f("governance.p7s"),  f(who + "_permissions.p7s")};
}

// One participant on its own local domain, `external` on the wire.
struct Peer {
  Peer(dds_domainid_t local, int external, const std::string& tag,
       const dds::SecurityFiles& security = {})
      : domain(local,
               std::string(dds::kLoopbackConfigXml) +
                   ",<CycloneDDS><Domain Id=\"any\"><Discovery><ExternalDomainId>" +
                   std::to_string(external) + "</ExternalDomainId><Tag>" + tag +
                   "</Tag></Discovery></Domain></CycloneDDS>",
               dds::EnvironmentConfig::kIgnore),
        participant(domain, security) {}
  dds::Domain domain;
  dds::Participant participant;
};

std::vector<json> JsonLines(const std::string& text) {
  std::vector<json> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    json j = json::parse(line, nullptr, /*allow_exceptions=*/false);
    if (!j.is_discarded()) lines.push_back(std::move(j));
  }
  return lines;
}

class SecureGearpathd : public ::testing::Test {
 protected:
  void SetUp() override {
    const int pid = static_cast<int>(getpid());
    domain_id_ = 20 + pid % 180;  // D + 6 stays inside the governance's 0..230
    machine_id_ = "sec_" + std::to_string(pid);
    daemon_id_ = "gearpathd_sec_" + std::to_string(pid);
    tag_ = "gearpath-security-test-" + std::to_string(pid);
    dir_ = fs::temp_directory_path() /
           ("gearpath_sec_" + std::to_string(pid) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    MakePki(dir_ / "pki");
    MakePki(dir_ / "foreign");
    if (HasFatalFailure()) return;

    // The deployment file: loopback, multicast off, and this test's discovery tag.
    std::string net(dds::kLoopbackConfigXml);
    const std::string end = "</Discovery>";
    net.insert(net.find(end), "<Tag>" + tag_ + "</Tag>");
    net_path_ = (dir_ / "cyclonedds.xml").string();
    std::ofstream(net_path_) << net;

    json config = json::parse(daemon::DefaultConfigText());
    config["daemon"]["id"] = daemon_id_;
    config["daemon"]["status_period_s"] = 0.1;
    config["dds"]["domain_id"] = domain_id_;
    config["dds"]["config"] = net_path_;
    config["dds"]["security"] = json::parse(ReadText(dir_ / "pki" / "gearpathd.security.json"));
    config["machines"][0]["id"] = machine_id_;
    config["machines"][0]["analysis"]["baseline"]["learning_blocks"] = kBlocks;
    const std::string config_path = (dir_ / "gearpathd.json").string();
    std::ofstream(config_path) << config.dump(2);

    auto set = daemon::BuiltinFrfSet("table1");
    ASSERT_TRUE(set.ok()) << set.error();
    for (const auto& ch : set->channels) {
      channels_.push_back({ch.sensor,
                           ch.axis == "y"   ? Axis::kY
                           : ch.axis == "z" ? Axis::kZ
                                            : Axis::kX,
                           "m/s^2", 0.0});
    }

    daemon_ = std::make_unique<ChildProcess>(GEARPATHD_PATH,
                                             std::vector<std::string>{"--config", config_path},
                                             (dir_ / "gearpathd.log").string());
    ASSERT_TRUE(daemon_->started());

    // The test's own authorised subscriber (monitor identity): Status and SuspectedGear.
    watcher_ =
        std::make_unique<Peer>(domain_id_ + 1, domain_id_, tag_, FilesOf(dir_ / "pki", "monitor"));
    status_topic_ = std::make_unique<dds::Topic<gearpath_Status>>(watcher_->participant);
    status_reader_ = std::make_unique<dds::Reader<gearpath_Status>>(*status_topic_);
    gear_topic_ = std::make_unique<dds::Topic<gearpath_SuspectedGear>>(watcher_->participant);
    gear_reader_ = std::make_unique<dds::Reader<gearpath_SuspectedGear>>(*gear_topic_);
    ASSERT_TRUE(WaitStatus([](const gearpath_MachineStatus&) { return true; }, 60s))
        << "no Status of the secured gearpathd reached an authorised subscriber" << Logs();
    EXPECT_NE(daemon_->Log().find("DDS Security on"), std::string::npos) << Logs();
  }

  void TearDown() override {
    if (HasFailure()) std::cerr << Logs() << "\n";
    if (daemon_ && daemon_->running()) {
      daemon_->Signal(SIGTERM);
      (void)daemon_->WaitExit(10s);
    }
    daemon_.reset();
    gear_reader_.reset();
    gear_topic_.reset();
    status_reader_.reset();
    status_topic_.reset();
    watcher_.reset();
    fs::remove_all(dir_);
  }

  static void MakePki(const fs::path& dir) {
    const std::string log = dir.string() + ".log";
    const std::string command = "bash '" GEARPATH_SOURCE_DIR "/tools/make-security-fixtures.sh' '" +
                                dir.string() + "' >'" + log + "' 2>&1";
    ASSERT_EQ(std::system(command.c_str()), 0)
        << "tools/make-security-fixtures.sh failed (is openssl installed?):\n"
        << ReadText(log);
  }

  // The options that put a tool on this test's secured domain as `who` (of `pki`).
  std::vector<std::string> ToolDds(const std::string& who, const std::string& pki = "pki") const {
    return {"--domain",       std::to_string(domain_id_),
            "--dds-config",   net_path_,
            "--dds-security", (dir_ / pki / (who + ".security.json")).string()};
  }

  ToolProcess StartMonitor(int count) {
    std::vector<std::string> args = {"monitor",   "--json",  "--machine",
                                     machine_id_, "--count", std::to_string(count),
                                     "--timeout", "90"};
    const auto dds_args = ToolDds("monitor");
    args.insert(args.end(), dds_args.begin(), dds_args.end());
    return ToolProcess(args, dir_, "monitor");
  }

  ToolProcess StartSim(const std::string& who, const std::string& name) {
    std::vector<std::string> args = {"sim",
                                     "--publish",
                                     "--machine-id",
                                     machine_id_,
                                     "--fast",
                                     "--blocks",
                                     std::to_string(kBlocks),
                                     "--healthy-blocks",
                                     std::to_string(kBlocks)};
    const auto dds_args = ToolDds(who);
    args.insert(args.end(), dds_args.begin(), dds_args.end());
    return ToolProcess(args, dir_, name);
  }

  // Waits for a Status of our daemon whose entry for our machine satisfies `pred`.
  bool WaitStatus(const std::function<bool(const gearpath_MachineStatus&)>& pred,
                  std::chrono::milliseconds timeout) {
    const auto deadline = Clock::now() + timeout;
    std::vector<dds::Owned<gearpath_Status>> samples(8);
    std::vector<dds::SampleInfo> infos(8);
    while (Clock::now() < deadline) {
      auto n = status_reader_->Take(samples, infos);
      if (!n) return false;
      for (std::size_t i = 0; i < *n; ++i) {
        if (!infos[i].valid_data || dds::GetString(samples[i]->daemon_id) != daemon_id_) continue;
        for (const auto& m : dds::View(samples[i]->machines)) {
          if (dds::GetString(m.machine_id) != machine_id_) continue;
          last_status_ = m;
          if (pred(m)) return true;
        }
      }
      if (daemon_->WaitExit(0ms).has_value()) return false;  // gearpathd exited
      std::this_thread::sleep_for(20ms);
    }
    return false;
  }

  // SuspectedGear samples of our machine seen by the authorised subscriber so far.
  void CollectVerdicts() {
    std::vector<dds::Owned<gearpath_SuspectedGear>> samples(8);
    std::vector<dds::SampleInfo> infos(8);
    for (;;) {
      auto n = gear_reader_->Take(samples, infos);
      if (!n || *n == 0) return;
      for (std::size_t i = 0; i < *n; ++i) {
        if (infos[i].valid_data && dds::GetString(samples[i]->machine_id) == machine_id_) {
          verdicts_.push_back(std::string(dds::GetString(samples[i]->gear_name)) + "#" +
                              std::to_string(samples[i]->block_sequence));
        }
      }
    }
  }

  // A valid-looking block of our machine: noise on the expected channels.
  dds::Owned<gearpath_AccelBlock> Block(std::uint64_t sequence) {
    AccelBlock b;
    b.machine_id = machine_id_;
    b.sequence = sequence;
    b.t0_ns = static_cast<std::int64_t>(sequence) * 1'000'000'000;
    b.sample_rate_hz = 8000.0;
    b.speed_hz = 10.0;
    b.speed_source = SpeedSource::kAcquisition;
    b.channels = channels_;
    b.samples_per_channel = 8192;
    std::normal_distribution<float> noise(0.0f, 1.0f);
    b.samples.resize(channels_.size() * b.samples_per_channel);
    for (float& x : b.samples) x = noise(rng_);
    dds::Owned<gearpath_AccelBlock> sample;
    EXPECT_TRUE(ToWire(b, sample));
    return sample;
  }

  std::string Logs() const {
    std::string s = "\n--- gearpathd log:\n" + (daemon_ ? daemon_->Log() : std::string());
    for (const char* name : {"monitor", "sim", "readonly_sim"}) {
      for (const char* ext : {".out", ".err"}) {
        const fs::path f = dir_ / (std::string(name) + ext);
        if (fs::exists(f)) s += "\n--- " + f.filename().string() + ":\n" + ReadText(f);
      }
    }
    return s;
  }

  int domain_id_ = 0;
  std::string machine_id_;
  std::string daemon_id_;
  std::string tag_;
  fs::path dir_;
  std::string net_path_;
  std::vector<ChannelInfo> channels_;
  std::mt19937 rng_{4242};
  gearpath_MachineStatus last_status_{};
  std::vector<std::string> verdicts_;  // "gear#block" of our machine, authorised subscriber

  std::unique_ptr<ChildProcess> daemon_;
  std::unique_ptr<Peer> watcher_;
  std::unique_ptr<dds::Topic<gearpath_Status>> status_topic_;
  std::unique_ptr<dds::Reader<gearpath_Status>> status_reader_;
  std::unique_ptr<dds::Topic<gearpath_SuspectedGear>> gear_topic_;
  std::unique_ptr<dds::Reader<gearpath_SuspectedGear>> gear_reader_;
};

// Waits for the monitor's first Status line (it has been admitted and discovered the daemon).
::testing::AssertionResult MonitorReady(ToolProcess& monitor, const std::function<void()>& poll) {
  const auto deadline = Clock::now() + 60s;
  while (monitor.Out().find(R"("topic":"Status")") == std::string::npos) {
    if (monitor.Wait(0ms).has_value()) return ::testing::AssertionFailure() << "monitor exited";
    if (Clock::now() > deadline) {
      return ::testing::AssertionFailure() << "the monitor saw no Status within 60 s";
    }
    poll();
    std::this_thread::sleep_for(20ms);
  }
  return ::testing::AssertionSuccess();
}

TEST_F(SecureGearpathd, AnAuthorisedPublishersBlocksAreProcessedAndAnAuthorisedMonitorReadsThem) {
  ToolProcess monitor = StartMonitor(kBlocks);
  ASSERT_TRUE(MonitorReady(monitor, [] {})) << Logs();
  ToolProcess sim = StartSim("acquisition", "sim");
  const std::optional<int> sim_code = sim.Wait(60s);
  ASSERT_EQ(sim_code, std::optional<int>(0)) << Logs();
  ASSERT_TRUE(WaitStatus([](const auto& m) { return m.blocks_processed == kBlocks; }, 60s))
      << Logs();
  EXPECT_EQ(last_status_.blocks_received, static_cast<std::uint64_t>(kBlocks));
  EXPECT_EQ(last_status_.blocks_rejected, 0u);

  // The monitor stops by itself after kBlocks verdicts of our machine.
  ASSERT_EQ(monitor.Wait(60s), std::optional<int>(0)) << Logs();
  std::vector<int> blocks;
  for (const json& j : JsonLines(monitor.Out())) {
    if (j["topic"] == "SuspectedGear" && j["machine"] == machine_id_) {
      blocks.push_back(j["block"].get<int>());
    }
  }
  EXPECT_EQ(blocks, (std::vector<int>{0, 1, 2})) << monitor.Out();
}

TEST_F(SecureGearpathd, ParticipantsWithoutValidCredentialsCanNeitherInjectNorReadNorSpoof) {
  // Rogues: an unsecured participant doing all three, and a foreign CA's identities, each
  // valid under its own CA with permissions for what it tries.
  Peer plain(domain_id_ + 2, domain_id_, tag_);
  Peer foreign_acquisition(domain_id_ + 3, domain_id_, tag_,
                           FilesOf(dir_ / "foreign", "acquisition"));
  Peer foreign_monitor(domain_id_ + 4, domain_id_, tag_, FilesOf(dir_ / "foreign", "monitor"));
  Peer foreign_daemon(domain_id_ + 5, domain_id_, tag_, FilesOf(dir_ / "foreign", "gearpathd"));
  dds::Topic<gearpath_AccelBlock> plain_blocks(plain.participant);
  dds::Topic<gearpath_SuspectedGear> plain_gear(plain.participant);
  dds::Topic<gearpath_AccelBlock> foreign_blocks(foreign_acquisition.participant);
  dds::Topic<gearpath_SuspectedGear> foreign_gear_in(foreign_monitor.participant);
  dds::Topic<gearpath_SuspectedGear> foreign_gear_out(foreign_daemon.participant);
  std::vector<dds::Writer<gearpath_AccelBlock>> block_writers;
  block_writers.emplace_back(plain_blocks);
  block_writers.emplace_back(foreign_blocks);
  std::vector<dds::Writer<gearpath_SuspectedGear>> spoofers;
  spoofers.emplace_back(plain_gear);
  spoofers.emplace_back(foreign_gear_out);
  std::vector<dds::Reader<gearpath_SuspectedGear>> eavesdroppers;
  eavesdroppers.emplace_back(plain_gear);
  eavesdroppers.emplace_back(foreign_gear_in);

  dds::Owned<gearpath_SuspectedGear> spoof;
  ASSERT_TRUE(dds::SetString(spoof->machine_id, machine_id_));
  ASSERT_TRUE(dds::SetString(spoof->gear_name, "SPOOFED"));
  ASSERT_TRUE(dds::SetString(spoof->shaft_name, "input"));
  ASSERT_TRUE(dds::SetString(spoof->reason, "SPOOFED alarm"));
  spoof->state = gearpath_ALARM;
  spoof->confidence = 1.0;

  // Every poll: each rogue writes a block and a fake alarm and tries to read a verdict.
  std::uint64_t rogue_sequence = 0;
  std::size_t overheard = 0;     // the daemon's verdicts read by a rogue
  std::size_t rogue_echoes = 0;  // the rogues' own fakes read by a rogue (they are live)
  std::vector<dds::Owned<gearpath_SuspectedGear>> samples(4);
  std::vector<dds::SampleInfo> infos(4);
  auto act = [&] {
    const auto block = Block(rogue_sequence);
    spoof->block_sequence = rogue_sequence++;
    for (auto& w : block_writers) (void)w.Write(*block);
    for (auto& w : spoofers) (void)w.Write(*spoof);
    for (auto& r : eavesdroppers) {  // the rogues hear each other's fakes; not the daemon
      auto n = r.Take(samples, infos);
      for (std::size_t i = 0; n && i < *n; ++i) {
        if (!infos[i].valid_data) continue;
        (dds::GetString(samples[i]->gear_name) == "SPOOFED" ? rogue_echoes : overheard) += 1;
      }
    }
  };

  ToolProcess monitor = StartMonitor(kBlocks);
  ASSERT_TRUE(MonitorReady(monitor, act)) << Logs();
  act();
  // The authorised publisher's blocks are processed and reach the monitor, with the rogues
  // at it throughout: they had every chance the authorised ones had.
  ToolProcess sim = StartSim("acquisition", "sim");
  const auto deadline = Clock::now() + 90s;
  while (monitor.Wait(0ms) == std::nullopt && Clock::now() < deadline) {
    act();
    CollectVerdicts();
    std::this_thread::sleep_for(50ms);
  }
  ASSERT_EQ(monitor.Wait(0ms), std::optional<int>(0))
      << "the monitor did not get its verdicts" << Logs();
  ASSERT_EQ(sim.Wait(30s), std::optional<int>(0)) << Logs();
  ASSERT_TRUE(WaitStatus([](const auto& m) { return m.blocks_processed >= kBlocks; }, 30s))
      << Logs();
  // Positive control: the rogues are live on the wire (the foreign CA's spoofer and
  // eavesdropper authenticate each other and exchange fakes), so what they did not get through
  // was refused, not missed.
  const auto echo_deadline = Clock::now() + 30s;
  while (rogue_echoes == 0 && Clock::now() < echo_deadline) {
    act();
    std::this_thread::sleep_for(50ms);
  }
  EXPECT_GT(rogue_echoes, 0u) << "the rogue participants never heard each other";
  act();
  CollectVerdicts();

  // No rogue block was received (let alone processed): only the authorised ones count.
  EXPECT_EQ(last_status_.blocks_received, static_cast<std::uint64_t>(kBlocks));
  EXPECT_EQ(last_status_.blocks_processed, static_cast<std::uint64_t>(kBlocks));
  EXPECT_EQ(last_status_.blocks_rejected, 0u);
  // No rogue read one of the daemon's verdicts (the authorised subscriber read them all), and
  // no block writer of a rogue was matched with a reader (the daemon's is the only one).
  EXPECT_EQ(overheard, 0u);
  EXPECT_GE(verdicts_.size(), static_cast<std::size_t>(kBlocks));
  for (auto& w : block_writers) EXPECT_EQ(w.MatchedReaders().value(), 0u);
  // The monitor shows the daemon's verdicts only, never the fake alarm.
  EXPECT_EQ(monitor.Out().find("SPOOFED"), std::string::npos) << monitor.Out();
  int shown = 0;
  for (const json& j : JsonLines(monitor.Out())) {
    shown += j["topic"] == "SuspectedGear" && j["machine"] == machine_id_ ? 1 : 0;
  }
  EXPECT_EQ(shown, kBlocks) << monitor.Out();
  for (const std::string& v : verdicts_) EXPECT_EQ(v.find("SPOOFED"), std::string::npos) << v;
}

TEST_F(SecureGearpathd, AParticipantAllowedOnlyToReadCannotPublishBlocks) {
  // In process: the monitor identity may not even create the block topic.
  {
    Peer reader_only(domain_id_ + 6, domain_id_, tag_, FilesOf(dir_ / "pki", "monitor"));
    try {
      dds::Topic<gearpath_AccelBlock> topic(reader_only.participant);
      dds::Writer<gearpath_AccelBlock> writer(topic);
      ADD_FAILURE() << "a read-only identity created a block writer";
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find("Not Allowed By Security"), std::string::npos)
          << e.what();
    }
  }
  // Through the tool: `gearpath sim --publish` with the monitor's credentials fails and says why.
  ToolProcess sim = StartSim("monitor", "readonly_sim");
  const std::optional<int> code = sim.Wait(60s);
  ASSERT_TRUE(code.has_value()) << "sim still running" << Logs();
  EXPECT_NE(*code, 0) << Logs();
  EXPECT_NE(sim.Err().find("Not Allowed By Security"), std::string::npos) << Logs();
  // And the daemon received nothing: three fresh Status samples after the attempt say 0.
  for (int i = 0; i < 3; ++i) {
    ASSERT_TRUE(WaitStatus([](const auto&) { return true; }, 10s)) << Logs();
    EXPECT_EQ(last_status_.blocks_received, 0u);
  }
}

}  // namespace
}  // namespace gearpath::testing
