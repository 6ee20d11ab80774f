// `gearpath replay`: recorded acquisitions back onto the AccelBlock topic (AccelBlockV2 for a
// recording whose blocks carry their load, or with --load), paced like the
// acquisition (real time), N times faster (--speed N), or as fast as the subscribers take them
// with nothing lost (--fast: the block topic is reliable keep-all, so the writer blocks instead
// of dropping, and replay waits for every block to be acknowledged before it exits).
//
// Inputs (tools/common/replay_input.h): a recording or a directory of recordings (blocks are
// sent exactly as recorded, several machines interleaved by t0), a DH8303-style text export, or
// UFF 58 time histories (both cut into --block-length blocks). With --loop the input repeats
// with t0 and sequence numbers continuing, so the daemon sees one uninterrupted stream.
// --write-recording converts instead of publishing (no DDS), e.g. a text export to a recording.
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/io/recording.h"
#include "tools/commands/commands.h"
#include "tools/common/block_publisher.h"
#include "tools/common/cli_checks.h"
#include "tools/common/progress.h"
#include "tools/common/replay_input.h"

namespace gearpath::tools {
namespace {

struct ReplayOptions {
  std::string input;
  std::string format = "auto";
  ReplayInputOptions in;
  int domain_id = 0;
  DdsOptions dds;
  double speed = 1.0;
  bool fast = false;
  bool loop = false;
  std::size_t loops = 0;  // with --loop: stop after this many passes; 0 = until Ctrl-C
  int subscribers = 1;
  double wait_s = 10.0;
  std::string write_recording;
  bool quiet = false;
};

std::atomic<bool> g_stop{false};
extern "C" void OnReplayStop(int) { g_stop.store(true); }

// The next block across all streams in t0 order (ties: stream order).
struct Cursor {
  std::size_t stream = 0, index = 0;
};

int RunReplay(ReplayOptions opt) {
  if (opt.format == "recording")
    opt.in.format = ReplayFormat::kRecording;
  else if (opt.format == "text")
    opt.in.format = ReplayFormat::kText;
  else if (opt.format == "uff")
    opt.in.format = ReplayFormat::kUff58;
  Result<ReplayInput> loaded = LoadReplayInput(opt.input, opt.in);
  if (!loaded) {
    std::fprintf(stderr, "gearpath replay: %s\n", loaded.error().c_str());
    return kExitBadInput;
  }
  ReplayInput& input = *loaded;
  std::size_t total = 0;
  for (const Recording& r : input.recordings) total += r.block_count();
  if (!opt.quiet) {
    std::fprintf(stderr, "gearpath replay: %s: %zu blocks", input.description.c_str(), total);
    for (const Recording& r : input.recordings) {
      std::fprintf(stderr, "%s machine %s (%zu ch x %u samples at %g Hz)",
                   &r == &input.recordings.front() ? "," : ";", r.layout.machine_id.c_str(),
                   r.layout.channels.size(), r.layout.samples_per_channel, r.layout.sample_rate_hz);
    }
    std::fprintf(stderr, "\n");
    if (input.dropped_samples > 0) {
      std::fprintf(stderr,
                   "gearpath replay: the last %zu samples per channel do not fill a block and "
                   "are not sent\n",
                   input.dropped_samples);
    }
  }
  if (total == 0) {
    std::fprintf(stderr, "gearpath replay: nothing to replay (no block in the selected range)\n");
    return kExitBadInput;
  }

  if (!opt.write_recording.empty()) {
    for (const Recording& r : input.recordings) {
      const std::filesystem::path dir = input.recordings.size() == 1
                                            ? std::filesystem::path(opt.write_recording)
                                            : std::filesystem::path(opt.write_recording) /
                                                  MachineDirectoryName(r.layout.machine_id);
      if (Status st = WriteRecording(r, dir); !st) {
        std::fprintf(stderr, "gearpath replay: %s\n", st.error().c_str());
        return kExitFailure;
      }
      std::printf("%s: %zu blocks -> %s\n", r.layout.machine_id.c_str(), r.block_count(),
                  dir.string().c_str());
    }
    return kExitOk;
  }

  // Each recording goes out as it was recorded: with its load (AccelBlockV2, in its unit) or
  // without (AccelBlock).
  std::vector<std::optional<std::string>> load_unit_of(input.recordings.size());
  for (std::size_t s = 0; s < input.recordings.size(); ++s) {
    if (input.recordings[s].carries_load()) load_unit_of[s] = input.recordings[s].layout.load_unit;
  }
  PublisherOptions po;
  po.domain_id = opt.domain_id;
  po.dds = opt.dds;
  po.speedup = opt.fast ? 0.0 : opt.speed;
  po.min_subscribers = opt.subscribers;
  po.match_timeout = std::chrono::milliseconds(static_cast<long long>(opt.wait_s * 1000));
  po.load_unit = load_unit_of.front();  // the kind whose topic is made first
  BlockPublisher publisher(po);

  g_stop.store(false);
  std::signal(SIGINT, OnReplayStop);
  std::signal(SIGTERM, OnReplayStop);

  // Per pass, each stream's t0 and sequence advance by its span so loops continue seamlessly.
  std::vector<std::int64_t> t0_span(input.recordings.size(), 0);
  std::vector<std::uint64_t> seq_span(input.recordings.size(), 0);
  for (std::size_t s = 0; s < input.recordings.size(); ++s) {
    const Recording& r = input.recordings[s];
    if (r.blocks.empty()) continue;
    const double block_s = r.layout.samples_per_channel / r.layout.sample_rate_hz;
    t0_span[s] = r.blocks.back().t0_ns - r.blocks.front().t0_ns + std::llround(block_s * 1e9);
    seq_span[s] = r.blocks.back().sequence - r.blocks.front().sequence + 1;
  }

  std::map<std::string, bool> last_with_load;  // per machine id: its last block's kind
  Progress progress(stderr, "replay", opt.loop ? (opt.loops ? opt.loops * total : 0) : total);
  std::size_t sent = 0;
  int exit_code = kExitOk;
  for (std::size_t pass = 0; !g_stop.load(); ++pass) {
    if (pass > 0 && !opt.loop) break;
    if (opt.loop && opt.loops > 0 && pass >= opt.loops) break;
    std::vector<std::size_t> next(input.recordings.size(), 0);
    for (;;) {
      if (g_stop.load()) break;
      // Earliest pending block.
      std::size_t best = input.recordings.size();
      for (std::size_t s = 0; s < input.recordings.size(); ++s) {
        if (next[s] >= input.recordings[s].block_count()) continue;
        if (best == input.recordings.size() ||
            input.recordings[s].blocks[next[s]].t0_ns <
                input.recordings[best].blocks[next[best]].t0_ns) {
          best = s;
        }
      }
      if (best == input.recordings.size()) break;
      AccelBlockView block = input.recordings[best].block(next[best]++);
      const auto k = static_cast<std::int64_t>(pass);
      block.t0_ns += k * t0_span[best];
      block.sequence += static_cast<std::uint64_t>(k) * seq_span[best];
      // A machine whose blocks change topic (a part with a load after one without): its
      // earlier blocks are acknowledged before the next one goes out on the other topic, so
      // that the subscriber cannot take them out of order.
      const std::string& machine = input.recordings[best].layout.machine_id;
      const bool with_load = load_unit_of[best].has_value();
      if (auto [last, first] = last_with_load.try_emplace(machine, with_load);
          !first && last->second != with_load) {
        last->second = with_load;
        if (Status st = publisher.Flush(std::chrono::milliseconds(30000)); !st) {
          std::fprintf(stderr, "\ngearpath replay: %s\n", st.error().c_str());
          exit_code = kExitFailure;
          break;
        }
      }
      if (Status st = publisher.Publish(block, load_unit_of[best]); !st) {
        std::fprintf(stderr, "\ngearpath replay: %s\n", st.error().c_str());
        exit_code = kExitFailure;
        break;
      }
      ++sent;
      if (!opt.quiet) progress.Update(sent);
    }
    if (exit_code != kExitOk) break;
  }
  std::signal(SIGINT, SIG_DFL);
  std::signal(SIGTERM, SIG_DFL);
  if (exit_code == kExitOk) {
    // Reliable delivery: do not exit (and tear the writer down) before every block is acked.
    if (Status st = publisher.Flush(std::chrono::milliseconds(30000)); !st) {
      std::fprintf(stderr, "gearpath replay: not every block was acknowledged: %s\n",
                   st.error().c_str());
      exit_code = kExitFailure;
    }
  }
  if (!opt.quiet) progress.Finish(sent);
  std::printf("sent %zu blocks%s\n", sent, g_stop.load() ? " (stopped by signal)" : "");
  return exit_code;
}

}  // namespace

void AddReplayCommand(CLI::App& app, int& exit_code) {
  auto opt = std::make_shared<ReplayOptions>();
  CLI::App* cmd = app.add_subcommand(
      "replay",
      "Publish recorded acquisitions as AccelBlocks: a recording (or a directory of "
      "them), a DH8303-style text export, or UFF 58 time histories");
  cmd->add_option("input", opt->input, "Recording directory, text export, or .unv/.uff file")
      ->required();
  cmd->add_option("--format", opt->format, "Input format (default: from the path)")
      ->check(CLI::IsMember({"auto", "recording", "text", "uff"}))
      ->capture_default_str();
  cmd->add_option("--speed", opt->speed, "Pacing: N times real time (1 = real time)")
      ->check(Positive())
      ->capture_default_str();
  cmd->add_flag("--fast", opt->fast,
                "As fast as the subscribers take the blocks, nothing lost (reliable)");
  cmd->add_option("--start", opt->in.start_s, "Start at this offset from the first sample, s")
      ->check(NonNegative());
  cmd->add_option("--end", opt->in.end_s, "Stop at this offset from the first sample, s")
      ->check(NonNegative());
  cmd->add_flag("--loop", opt->loop, "Repeat the input until Ctrl-C (t0 and sequence continue)");
  cmd->add_option("--loops", opt->loops, "With --loop: stop after this many passes")
      ->check(NonNegative());
  cmd->add_option("--machine", opt->in.machine,
                  "Machine id to publish under (default: the recording's, or the file name)");
  cmd->add_option("--select", opt->in.select,
                  "From a directory of recordings, only these machines (repeatable)");
  cmd->add_option("--block-length", opt->in.block_length,
                  "Continuous inputs: samples per channel per block (default 4096)")
      ->check(Positive());
  cmd->add_option("--channel", opt->in.channel_map,
                  "Rename or drop a channel: COLUMN=SENSOR:AXIS or COLUMN=- (repeatable)");
  cmd->add_option("--sample-rate", opt->in.sample_rate_hz,
                  "Text exports: sample rate in Hz when the header states none")
      ->check(Positive());
  cmd->add_option("--shaft-speed", opt->in.shaft_speed_hz,
                  "Continuous inputs: input-shaft speed in Hz to send with every block")
      ->check(NonNegative());
  cmd->add_option("--load", opt->in.load,
                  "Continuous inputs: operating load to send with every block (as AccelBlockV2)")
      ->check(NonNegative());
  cmd->add_option("--load-unit", opt->in.load_unit, "Unit of --load (at most 16 characters)");
  AddPublishingOptions(cmd, &opt->domain_id, &opt->dds, &opt->subscribers, &opt->wait_s);
  cmd->add_option("--write-recording", opt->write_recording,
                  "Write the blocks as a recording into this directory instead of publishing");
  cmd->add_flag("--quiet,-q", opt->quiet, "No summary or progress on stderr");
  cmd->callback([opt, &exit_code] {
    try {
      exit_code = RunReplay(*opt);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "gearpath replay: %s\n", e.what());
      exit_code = kExitFailure;
    }
  });
}

}  // namespace gearpath::tools
