// bench_daemon_load: gearpathd under load over loopback DDS (127.0.0.1, multicast off; a
// private domain). N machines on one FRF set, one block per machine per period, spread evenly
// over the period; measures block written -> SuspectedGear received (same process, same clock)
// p50 / p99 / max, results missing, blocks the daemon dropped (queue_full lines), the busy
// fraction of every core and the daemon's CPU and RSS, and what the daemon's MachineHealth
// topic says of every machine at the end (instances seen, blocks processed, rejected, lost).
// Not a test: it prints figures.
//
//   bench_daemon_load [--machines 64] [--period 2] [--blocks 10] [--workers 0] [--reference]
//
// There is no machine cap (the configuration's sanity bound is 4096): --machines 100 and more
// run; Status lists the first 64, MachineHealth every machine.
//
// Workload: by default the embedded default machine (builtin:table1: 3 channels x 3 paths,
// 8 kHz) with 8192-sample blocks of the simulated healthy Table-1 gearbox, lighter than the
// 12 x 12 reference workload of bench_reference. --reference: the reference workload instead
// (tests/bench/reference_workload.h: 12 paths x 12 channels, 8 kHz, 16 000-sample blocks, MWI
// K = 50, kurtogram depth 6, the 8001-bin FRF set). The set is written once, in the FRF set
// format (core/io/frf_set_io.h), to the run's temporary directory, and every machine names that
// directory: the daemon loads it from files and shares it (daemon/frf_registry.h).
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "core/io/frf_set_io.h"
#include "core/model/gear_train.h"
#include "core/model/lumped_gearbox_model.h"
#include "core/simulation/gearbox_simulator.h"
#include "daemon/daemon_config.h"
#include "idl/dds/gearpath_topics.h"
#include "idl/dds/loopback_config_xml.h"
#include "tests/bench/reference_workload.h"
#include "tests/daemon/child_process.h"
#include "tests/integration/wire_block.h"

namespace {

using namespace gearpath;
using Clock = std::chrono::steady_clock;
using namespace std::chrono_literals;

struct CpuTimes {
  std::vector<std::pair<unsigned long long, unsigned long long>> cores;  // busy, total
};

CpuTimes ReadCpu() {
  CpuTimes t;
  std::ifstream in("/proc/stat");
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("cpu", 0) != 0 || line.size() < 4 || line[3] == ' ') continue;
    std::istringstream s(line.substr(line.find(' ')));
    unsigned long long v[8] = {};
    for (auto& x : v) s >> x;  // user nice system idle iowait irq softirq steal
    const unsigned long long idle = v[3] + v[4];
    unsigned long long total = 0;
    for (auto x : v) total += x;
    t.cores.emplace_back(total - idle, total);
  }
  return t;
}

// User + system CPU seconds from the text of a /proc/<pid>/stat or /proc/<pid>/task/<tid>/stat
// file (fields 14 and 15, counted after the parenthesised name, which may hold spaces).
double StatCpuSeconds(const std::string& stat) {
  const auto close = stat.rfind(')');
  if (close == std::string::npos || close + 2 > stat.size()) return 0.0;
  std::istringstream s(stat.substr(close + 2));
  std::string field;
  unsigned long long utime = 0, stime = 0;
  for (int i = 3; i <= 15; ++i) {
    s >> field;
    if (i == 14) utime = std::stoull(field);
    if (i == 15) stime = std::stoull(field);
  }
  return static_cast<double>(utime + stime) / static_cast<double>(sysconf(_SC_CLK_TCK));
}

std::string ReadAll(const std::filesystem::path& path) {
  std::ifstream in(path);
  return std::string((std::istreambuf_iterator<char>(in)), {});
}

double ProcessCpuSeconds(pid_t pid) {
  return StatCpuSeconds(ReadAll("/proc/" + std::to_string(pid) + "/stat"));
}

// CPU seconds of every thread of `pid` (/proc/<pid>/task), by thread id, with its name (Cyclone
// names its threads; the daemon's workers and reader keep the process name).
std::map<int, std::pair<std::string, double>> ThreadCpuSeconds(pid_t pid) {
  std::map<int, std::pair<std::string, double>> out;
  const std::filesystem::path task = "/proc/" + std::to_string(pid) + "/task";
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(task, ec)) {
    const std::string all = ReadAll(entry.path() / "stat");
    const auto open = all.find('(');
    const auto close = all.rfind(')');
    if (open == std::string::npos || close == std::string::npos) continue;
    out[std::stoi(entry.path().filename().string())] = {all.substr(open + 1, close - open - 1),
                                                         StatCpuSeconds(all)};
  }
  return out;
}

std::string StatusField(pid_t pid, const std::string& key) {
  std::ifstream in("/proc/" + std::to_string(pid) + "/status");
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind(key, 0) == 0) return line.substr(key.size() + 1);
  }
  return "?";
}

double Percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[static_cast<std::size_t>(p * static_cast<double>(v.size() - 1))];
}

}  // namespace

int main(int argc, char** argv) {
  int machines = 64, blocks = 10, workers = 0;
  double period = 2.0;
  bool reference = false;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--reference") {
      reference = true;
      continue;
    }
    if (i + 1 >= argc) break;
    if (a == "--machines") machines = std::stoi(argv[i + 1]);
    if (a == "--period") period = std::stod(argv[i + 1]);
    if (a == "--blocks") blocks = std::stoi(argv[i + 1]);
    if (a == "--workers") workers = std::stoi(argv[i + 1]);
    ++i;
  }
  const int pid = static_cast<int>(getpid());
  const int domain_id = 150 + pid % 80;
  const auto dir = std::filesystem::temp_directory_path() / ("gearpath_load_" + std::to_string(pid));
  std::filesystem::create_directories(dir);
  nlohmann::json config = nlohmann::json::parse(daemon::DefaultConfigText());
  config["daemon"]["log_level"] = "warn";
  config["daemon"]["workers"] = workers;
  config["dds"]["domain_id"] = domain_id;
  nlohmann::json one = config["machines"][0];
  const std::uint32_t block_length = reference ? 16000 : 8192;
  FrfSet reference_set;
  if (reference) {
    // The reference workload's FRF set, written once; every machine loads this directory.
    reference_set = reference::ReferenceFrfSet(12, 12);
    const auto frf_dir = dir / "reference_frf";
    if (Status st = WriteFrfSet(reference_set, frf_dir); !st) {
      std::fprintf(stderr, "writing the reference FRF set: %s\n", st.error().c_str());
      return 1;
    }
    one["frf_set"] = frf_dir.string();
    one["description"] = "the reference workload of issue 9 (tests/bench/reference_workload.h)";
    one["nominal_speed_hz"] = reference::kSpeedHz;
    one["acquisition"]["sample_rate_hz"] = reference::kFs;
    one["analysis"]["inverse"]["iterations"] = 50;
    one["analysis"]["envelope"]["kurtogram_max_level"] = 6;
  }
  config["machines"] = nlohmann::json::array();
  auto id_of = [](int i) {
    char id[16];
    std::snprintf(id, sizeof id, "load%04d", i);
    return std::string(id);
  };
  for (int i = 0; i < machines; ++i) {
    nlohmann::json m = one;
    m["id"] = id_of(i);
    m["acquisition"]["prepare_samples_per_channel"] = nlohmann::json::array({block_length});
    config["machines"].push_back(m);
  }
  const std::string config_path = (dir / "gearpathd.json").string();
  std::ofstream(config_path) << config.dump(2);

  // Blocks: a few simulated healthy Table-1 blocks, relabelled per machine and sequence.
  auto model = LumpedGearboxModel::Create(Table1Parameters());
  SimulatorConfig sc;
  sc.machine_id = id_of(0);
  sc.sample_rate_hz = 8000.0;
  sc.block_length = 8192;
  sc.noise_relative = 0.05;
  sc.include_housing_channel = false;
  auto sim = GearboxSimulator::Create(model.value(), GearTrain::Table1(), sc);
  if (!sim.ok()) {
    std::fprintf(stderr, "simulator: %s\n", sim.error().c_str());
    return 1;
  }
  std::vector<dds::Owned<gearpath_AccelBlock>> wire(4);
  for (std::size_t k = 0; k < wire.size(); ++k) {
    AccelBlock b;
    if (reference) {
      reference::BlockVariant v;
      v.noise_seed = 7 + k;  // four blocks with their own noise
      b = reference::ReferenceBlock(reference_set, block_length, v);
    } else {
      sim->NextBlock(b);
    }
    if (!testing::ToWire(b, wire[k])) return 1;
  }

  const auto build_start = Clock::now();
  testing::ChildProcess gearpathd(GEARPATHD_PATH, {"--config", config_path},
                                  (dir / "gearpathd.log").string());
  dds::Domain domain(domain_id, dds::kLoopbackConfigXml, dds::EnvironmentConfig::kIgnore);
  dds::Participant participant(domain);
  dds::Topic<gearpath_AccelBlock> block_topic(participant);
  // One writer for every machine: its instance limit must hold them all (the profile's 256 is
  // per writer; a bridge normally writes one machine).
  const std::int32_t instances = std::max(dds::kMaxMachinesPerDomain, machines);
  dds::Qos writer_qos = dds::WriterQos(dds::TopicClass::kBlockStream);
  writer_qos.ResourceLimits(dds::kBlockHistoryDepth * instances, instances,
                            dds::kBlockHistoryDepth);
  dds::Writer<gearpath_AccelBlock> writer(block_topic, writer_qos);
  dds::Topic<gearpath_SuspectedGear> gear_topic(participant);
  dds::Reader<gearpath_SuspectedGear> reader(gear_topic);
  dds::Topic<gearpath_MachineHealth> health_topic(participant);
  dds::Reader<gearpath_MachineHealth> health_reader(health_topic);
  bool up = false;  // a configuration the daemon refuses ends it: stop waiting then
  for (int s = 0; s < 600 && !up && gearpathd.running(); ++s) {
    up = writer.WaitForReaders(1, 1s).ok();
  }
  if (!up) {
    std::fprintf(stderr, "gearpathd did not come up; log:\n%s\n", gearpathd.Log().c_str());
    return 1;
  }
  const double startup_s = std::chrono::duration<double>(Clock::now() - build_start).count();
  std::this_thread::sleep_for(1s);  // the daemon's result writers match our reader

  const std::size_t expected = static_cast<std::size_t>(machines) * static_cast<std::size_t>(blocks);
  std::vector<Clock::time_point> sent(expected);
  std::vector<double> latency_ms;
  latency_ms.reserve(expected);
  std::atomic<bool> done{false};
  std::thread receiver([&] {
    std::vector<dds::Owned<gearpath_SuspectedGear>> samples(64);
    std::vector<dds::SampleInfo> infos(64);
    while (!done.load()) {
      auto n = reader.Take(samples, infos);
      const auto now = Clock::now();
      if (!n || *n == 0) {
        std::this_thread::sleep_for(1ms);  // polling: adds up to 1 ms to a latency
        continue;
      }
      for (std::size_t k = 0; k < *n; ++k) {
        if (!infos[k].valid_data) continue;
        const int m = std::stoi(std::string(dds::GetString(samples[k]->machine_id)).substr(4));
        const std::size_t at = static_cast<std::size_t>(m) * static_cast<std::size_t>(blocks) +
                               static_cast<std::size_t>(samples[k]->block_sequence);
        if (at < expected) {
          latency_ms.push_back(std::chrono::duration<double, std::milli>(now - sent[at]).count());
        }
      }
      if (latency_ms.size() >= expected) done = true;
    }
  });

  const CpuTimes cpu0 = ReadCpu();
  const double daemon_cpu0 = ProcessCpuSeconds(gearpathd.pid());
  const auto threads0 = ThreadCpuSeconds(gearpathd.pid());
  const auto t0 = Clock::now();
  std::size_t write_failures = 0;
  for (int r = 0; r < blocks; ++r) {
    for (int i = 0; i < machines; ++i) {
      std::this_thread::sleep_until(
          t0 + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(
                   period * (r + static_cast<double>(i) / machines))));
      gearpath_AccelBlock& s = *wire[static_cast<std::size_t>(r + i) % wire.size()];
      (void)dds::SetString(s.machine_id, id_of(i));
      s.sequence_number = static_cast<std::uint64_t>(r);
      s.t0_ns = static_cast<std::int64_t>(r) * 1'000'000'000;
      sent[static_cast<std::size_t>(i) * static_cast<std::size_t>(blocks) +
           static_cast<std::size_t>(r)] = Clock::now();
      if (!writer.Write(s).ok()) ++write_failures;
    }
  }
  const auto deadline = Clock::now() + 60s;
  while (!done.load() && Clock::now() < deadline) std::this_thread::sleep_for(10ms);
  const double wall = std::chrono::duration<double>(Clock::now() - t0).count();
  const CpuTimes cpu1 = ReadCpu();
  const double daemon_cpu = ProcessCpuSeconds(gearpathd.pid()) - daemon_cpu0;
  const auto threads1 = ThreadCpuSeconds(gearpathd.pid());
  const std::string rss = StatusField(gearpathd.pid(), "VmRSS:");
  const std::string hwm = StatusField(gearpathd.pid(), "VmHWM:");
  // The daemon's own account, per machine, once a status period has passed after the last
  // result: the latest MachineHealth of every instance (keep-last 1 per instance).
  std::this_thread::sleep_for(std::chrono::duration<double>(1.5));
  std::size_t health_machines = 0;
  unsigned long long health_processed = 0, health_rejected = 0, health_lost = 0;
  {
    std::vector<dds::Owned<gearpath_MachineHealth>> hs(256);
    std::vector<dds::SampleInfo> hi(256);
    std::map<std::string, std::array<unsigned long long, 3>> latest;
    for (;;) {
      auto n = health_reader.Take(hs, hi);
      if (!n || *n == 0) break;
      for (std::size_t k = 0; k < *n; ++k) {
        if (!hi[k].valid_data) continue;
        latest[std::string(dds::GetString(hs[k]->machine_id))] = {
            hs[k]->blocks_processed, hs[k]->blocks_rejected, hs[k]->blocks_lost};
      }
    }
    health_machines = latest.size();
    for (const auto& [id, c] : latest) {
      health_processed += c[0];
      health_rejected += c[1];
      health_lost += c[2];
    }
  }
  done = true;
  receiver.join();
  gearpathd.Signal(SIGTERM);
  (void)gearpathd.WaitExit(10s);
  const std::string log = gearpathd.Log();
  std::size_t drop_lines = 0;
  for (std::size_t p = log.find("dropped before"); p != std::string::npos;
       p = log.find("dropped before", p + 1)) {
    ++drop_lines;
  }

  std::printf("workload: %s\n",
              reference ? "reference (12 x 12, 8 kHz, 16000 samples, 8001-bin FRF set from files)"
                        : "builtin:table1 (3 x 3, 8 kHz, 8192 samples)");
  std::printf("machines %d, one block each per %.2f s, %d blocks each (%zu), workers %s\n",
              machines, period, blocks, expected,
              workers == 0 ? "0 (hardware threads)" : std::to_string(workers).c_str());
  std::printf("start-up (config to block reader matched): %.2f s\n", startup_s);
  std::printf("results received %zu of %zu (missing %zu), write failures %zu, daemon drop "
              "lines %zu\n",
              latency_ms.size(), expected, expected - std::min(expected, latency_ms.size()),
              write_failures, drop_lines);
  std::printf("MachineHealth: %zu of %d machines reported; blocks processed %llu, rejected %llu, "
              "lost %llu\n",
              health_machines, machines, health_processed, health_rejected, health_lost);
  std::printf("latency block written -> SuspectedGear received: p50 %.1f ms, p99 %.1f ms, max "
              "%.1f ms\n",
              Percentile(latency_ms, 0.5), Percentile(latency_ms, 0.99),
              Percentile(latency_ms, 1.0));
  std::printf("over %.1f s: gearpathd CPU %.2f cores;", wall, daemon_cpu / wall);
  for (std::size_t c = 0; c < cpu1.cores.size() && c < cpu0.cores.size(); ++c) {
    const double busy = static_cast<double>(cpu1.cores[c].first - cpu0.cores[c].first);
    const double total = static_cast<double>(cpu1.cores[c].second - cpu0.cores[c].second);
    std::printf(" cpu%zu %.0f %% busy;", c, total > 0 ? 100.0 * busy / total : 0.0);
  }
  std::printf(" (whole host, other jobs included)\ngearpathd threads over 0.02 cores:");
  for (const auto& [tid, t] : threads1) {
    const auto before = threads0.find(tid);
    const double used = t.second - (before != threads0.end() ? before->second.second : 0.0);
    if (used / wall >= 0.02) std::printf(" %s[%d] %.2f;", t.first.c_str(), tid, used / wall);
  }
  std::printf("\ngearpathd RSS %s (peak %s)\n", rss.c_str(),
              hwm.c_str());
  std::filesystem::remove_all(dir);
  return 0;
}
