// `gearpath record`: subscribes to the AccelBlock and AccelBlockV2 topics and writes what arrives
// as recordings (docs/recording_format.md), so a plant can capture a period and replay it later;
// an AccelBlockV2's load and unit are kept with its block.
//
// Each machine's blocks go to OUT/<machine id>/ (one recording per machine; a block whose layout
// changes, e.g. another block length or load unit, starts OUT/<machine id>.part2/ and so on).
// Stops after --count blocks, after --duration seconds, or on SIGINT/SIGTERM; in every case the
// recordings are finished (header and manifest written) before it exits. The reader is reliable keep-all
// like the daemon's, so a publisher that waits for it (replay --fast) loses nothing.
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "core/io/recording.h"
#include "idl/dds/accel_block_wire.h"
#include "idl/dds/domain.h"
#include "idl/dds/gearpath_topics.h"
#include "idl/dds/topic.h"
#include "idl/dds/waitset.h"
#include "tools/commands/commands.h"
#include "tools/common/cli_checks.h"
#include "tools/common/dds_options.h"
#include "tools/common/replay_input.h"

namespace gearpath::tools {
namespace {

namespace fs = std::filesystem;

struct RecordOptions {
  int domain_id = 0;
  std::vector<std::string> machines;  // empty = all
  std::string out;
  std::size_t count = 0;    // stop after this many blocks (all machines together); 0 = never
  double duration_s = 0.0;  // stop after this long; 0 = never
  bool quiet = false;
  DdsOptions dds;
};

std::atomic<bool> g_stop{false};
extern "C" void OnStopSignal(int) { g_stop.store(true); }

struct MachineStream {
  std::unique_ptr<RecordingWriter> writer;
  int part = 1;
  std::size_t blocks = 0;
  std::vector<fs::path> dirs;
};

int RunRecord(const RecordOptions& opt) {
  const std::set<std::string> wanted(opt.machines.begin(), opt.machines.end());
  const fs::path out(opt.out);
  if (fs::exists(out) && !(fs::is_directory(out) && fs::is_empty(out))) {
    std::fprintf(stderr, "gearpath record: %s already exists and is not an empty directory\n",
                 opt.out.c_str());
    return kExitBadInput;
  }

  dds::Domain domain(opt.domain_id, ToolDomainConfig(opt.dds));
  dds::Participant participant(domain, ToolSecurityFiles(opt.dds));
  dds::Topic<gearpath_AccelBlock> topic(participant);
  dds::Reader<gearpath_AccelBlock> reader(topic);
  dds::ReadCondition condition(reader);
  dds::Topic<gearpath_AccelBlockV2> topic_v2(participant);
  dds::Reader<gearpath_AccelBlockV2> reader_v2(topic_v2);
  dds::ReadCondition condition_v2(reader_v2);
  dds::WaitSet waitset(participant);
  waitset.Attach(condition, 1);
  waitset.Attach(condition_v2, 2);

  g_stop.store(false);
  std::signal(SIGINT, OnStopSignal);
  std::signal(SIGTERM, OnStopSignal);

  std::fprintf(stderr, "gearpath record: subscribed to %s and %s on domain %d, recording into %s\n",
               std::string(topic.name()).c_str(), std::string(topic_v2.name()).c_str(),
               opt.domain_id, opt.out.c_str());
  std::fflush(stderr);

  std::map<std::string, MachineStream> streams;
  std::vector<dds::Owned<gearpath_AccelBlock>> samples(16);
  std::vector<dds::SampleInfo> infos(16);
  std::vector<dds::Owned<gearpath_AccelBlockV2>> samples_v2(16);
  std::vector<dds::SampleInfo> infos_v2(16);
  std::vector<ChannelInfo> channels;
  std::vector<dds_attach_t> triggered(2);
  // What one wake took from both topics, in the order the blocks were written.
  struct Taken {
    bool with_load;
    std::size_t index;
    dds_time_t written;
  };
  std::vector<Taken> order;
  std::size_t total = 0, foreign = 0;
  int exit_code = kExitOk;
  const auto start = std::chrono::steady_clock::now();
  bool timed_out = false;

  auto finish = [&](MachineStream& s) -> bool {
    if (!s.writer) return true;
    Status st = s.writer->Close();
    if (!st) {
      std::fprintf(stderr, "gearpath record: %s\n", st.error().c_str());
      return false;
    }
    return true;
  };

  while (!g_stop.load() && (opt.count == 0 || total < opt.count)) {
    std::chrono::nanoseconds wait = std::chrono::milliseconds(100);
    if (opt.duration_s > 0) {
      const auto left =
          start + std::chrono::duration<double>(opt.duration_s) - std::chrono::steady_clock::now();
      if (left <= std::chrono::nanoseconds::zero()) {
        timed_out = true;
        break;
      }
      wait = std::min(wait, std::chrono::duration_cast<std::chrono::nanoseconds>(left));
    }
    auto woke = waitset.Wait(triggered, wait);
    if (!woke) {
      std::fprintf(stderr, "gearpath record: %s\n", woke.error().c_str());
      exit_code = kExitFailure;
      break;
    }
    auto taken = reader.Take(samples, infos);
    auto taken_v2 = taken ? reader_v2.Take(samples_v2, infos_v2) : taken;
    if (!taken || !taken_v2) {
      std::fprintf(stderr, "gearpath record: %s\n", (taken ? taken_v2 : taken).error().c_str());
      exit_code = kExitFailure;
      break;
    }
    order.clear();
    for (std::size_t i = 0; i < *taken; ++i) {
      if (infos[i].valid_data) order.push_back({false, i, infos[i].source_timestamp});
    }
    for (std::size_t i = 0; i < *taken_v2; ++i) {
      if (infos_v2[i].valid_data) order.push_back({true, i, infos_v2[i].source_timestamp});
    }
    std::stable_sort(order.begin(), order.end(),
                     [](const Taken& a, const Taken& b) { return a.written < b.written; });
    for (const Taken& t : order) {
      if (opt.count != 0 && total >= opt.count) break;
      const AccelBlockView block = t.with_load
                                       ? dds::ViewOfWireBlock(*samples_v2[t.index], channels)
                                       : dds::ViewOfWireBlock(*samples[t.index], channels);
      const std::string_view load_unit =
          t.with_load ? std::string_view(samples_v2[t.index]->load_unit) : std::string_view();
      const std::string machine(block.machine_id);
      if (!wanted.empty() && !wanted.count(machine)) {
        ++foreign;
        continue;
      }
      MachineStream& s = streams[machine];
      if (s.writer && !MatchesLayout(s.writer->layout(), block, load_unit)) {
        if (!finish(s)) return kExitFailure;
        s.writer.reset();
        ++s.part;
        std::fprintf(stderr,
                     "gearpath record: %s: block %llu changes the layout (channels, rate, "
                     "length or load unit); starting part %d\n",
                     machine.c_str(), static_cast<unsigned long long>(block.sequence), s.part);
      }
      if (!s.writer) {
        std::string name = MachineDirectoryName(machine);
        if (s.part > 1) name += ".part" + std::to_string(s.part);
        auto opened = RecordingWriter::Open(out / name, LayoutOf(block, std::string(load_unit)));
        if (!opened) {
          std::fprintf(stderr, "gearpath record: %s\n", opened.error().c_str());
          return kExitFailure;
        }
        s.writer = std::move(*opened);
        s.dirs.push_back(out / name);
      }
      if (Status st = s.writer->Append(block); !st) {
        std::fprintf(stderr, "gearpath record: %s: %s\n", machine.c_str(), st.error().c_str());
        exit_code = kExitFailure;
        break;
      }
      ++s.blocks;
      ++total;
    }
    if (exit_code != kExitOk) break;
  }
  std::signal(SIGINT, SIG_DFL);
  std::signal(SIGTERM, SIG_DFL);

  for (auto& [machine, s] : streams) {
    if (!finish(s)) exit_code = kExitFailure;
  }
  for (const auto& [machine, s] : streams) {
    for (const fs::path& dir : s.dirs) {
      std::printf("%s: %zu blocks -> %s\n", machine.c_str(), s.blocks, dir.string().c_str());
    }
  }
  if (!opt.quiet) {
    std::fprintf(
        stderr, "gearpath record: %zu blocks from %zu machines%s%s\n", total, streams.size(),
        foreign ? (", " + std::to_string(foreign) + " of other machines ignored").c_str() : "",
        g_stop.load() ? " (stopped by signal)" : "");
  }
  for (const std::string& m : opt.machines) {
    if (!streams.count(m)) {
      std::fprintf(stderr, "gearpath record: no block from machine \"%s\"\n", m.c_str());
      if (exit_code == kExitOk) exit_code = kExitFailure;
    }
  }
  if (timed_out && opt.count > 0 && total < opt.count && exit_code == kExitOk) {
    std::fprintf(stderr, "gearpath record: --duration %.1f s ended with %zu of %zu blocks\n",
                 opt.duration_s, total, opt.count);
    exit_code = kExitFailure;
  }
  return exit_code;
}

}  // namespace

void AddRecordCommand(CLI::App& app, int& exit_code) {
  auto opt = std::make_shared<RecordOptions>();
  CLI::App* cmd = app.add_subcommand(
      "record",
      "Record AccelBlocks (and AccelBlockV2s, with their load) from DDS into recordings "
      "(docs/recording_format.md), one per "
      "machine under --out; stops after --count blocks, --duration seconds, or Ctrl-C");
  cmd->add_option("--out,-o", opt->out, "Output directory (new or empty)")->required();
  cmd->add_option("--machine", opt->machines, "Only these machine ids (repeatable; default all)");
  cmd->add_option("--count", opt->count, "Stop after this many blocks in total; 0 = never")
      ->check(NonNegative());
  cmd->add_option("--duration", opt->duration_s, "Stop after this many seconds; 0 = never")
      ->check(NonNegative());
  cmd->add_option("--domain", opt->domain_id, "DDS domain id")
      ->capture_default_str()
      ->check(CLI::Range(0, 232));
  AddDdsOptions(cmd, &opt->dds);
  cmd->add_flag("--quiet,-q", opt->quiet, "No summary on stderr");
  cmd->callback([opt, &exit_code] {
    try {
      exit_code = RunRecord(*opt);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "gearpath record: %s\n", e.what());
      exit_code = kExitFailure;
    }
  });
}

}  // namespace gearpath::tools
