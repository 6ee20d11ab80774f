// `gearpath bridge`: a live acquisition bridge. Publishes AccelBlocks from an acquisition system
// as they come, through the same block publisher as `replay`:
//   --dir DIR        files exported into DIR (text/CSV, UFF 58; replay's readers), each once,
//                    in order, once complete (tools/bridge/directory_bridge.h)
//   --stream FILE|-  a raw sample stream (tools/bridge/stream_header.h) from a file, FIFO or stdin
//   --listen [A:]P   the same streams over TCP, one connection at a time (127.0.0.1 by default)
// What went out is recorded block by block in the --state file, so a restarted bridge continues
// with the next block and the next sequence number. The logic lives in tools/bridge/; this file
// only wires options, signals, DDS and messages.
#include <arpa/inet.h>
#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <thread>

#include "tools/bridge/bridge_state.h"
#include "tools/bridge/directory_bridge.h"
#include "tools/bridge/stream_bridge.h"
#include "tools/bridge/tcp_listener.h"
#include "tools/commands/commands.h"
#include "tools/common/block_publisher.h"
#include "tools/common/cli_checks.h"

namespace gearpath::tools {
namespace {

struct BridgeOptions {
  std::string machine;
  std::string state_file;
  std::string dir;
  std::string stream;
  std::string listen;
  std::uint32_t block_length = 4096;
  double settle_s = 2.0;
  double poll_s = 1.0;
  std::string order = "name";
  std::string failed_dir;
  std::string format = "auto";
  std::vector<std::string> channel_map;
  double sample_rate_hz = 0.0;
  double shaft_speed_hz = 0.0;
  bool once = false;
  std::string topic;
  int domain_id = 0;
  DdsOptions dds;
  int subscribers = 1;
  double wait_s = 60.0;
  double idle_timeout_s = 60.0;
  bool quiet = false;
};

std::atomic<bool> g_stop{false};
extern "C" void OnBridgeStop(int) { g_stop.store(true); }

// Without SA_RESTART, so a blocking call returns and the loops see the flag.
void InstallStopHandlers() {
  struct sigaction sa {};
  sa.sa_handler = OnBridgeStop;
  sigemptyset(&sa.sa_mask);
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
  signal(SIGPIPE, SIG_IGN);  // a TCP peer that goes away is a read error, not a death
}

void Log(const BridgeOptions& opt, const std::string& line) {
  if (!opt.quiet) std::fprintf(stderr, "gearpath bridge: %s\n", line.c_str());
}

// Sleeps up to `seconds`, returning early once a stop was asked for.
void Nap(double seconds) {
  const auto until = std::chrono::steady_clock::now() +
                     std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                         std::chrono::duration<double>(seconds));
  while (!g_stop.load() && std::chrono::steady_clock::now() < until) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
}

int RunDirectory(const BridgeOptions& opt, BridgeState& state, BlockSink& sink) {
  DirectoryBridgeOptions d;
  d.directory = opt.dir;
  d.state_file = opt.state_file;
  d.failed_directory = opt.failed_dir;
  d.input.machine = opt.machine;
  d.input.format = opt.format == "text"  ? ReplayFormat::kText
                   : opt.format == "uff" ? ReplayFormat::kUff58
                                         : ReplayFormat::kAuto;
  d.input.block_length = opt.block_length;
  d.input.channel_map = opt.channel_map;
  d.input.sample_rate_hz = opt.sample_rate_hz;
  d.input.shaft_speed_hz = opt.shaft_speed_hz;
  d.settle = std::chrono::duration_cast<std::chrono::nanoseconds>(
      std::chrono::duration<double>(opt.settle_s));
  d.order = opt.order == "mtime" ? FileOrder::kMtime : FileOrder::kName;
  if (!std::filesystem::is_directory(opt.dir)) {
    std::fprintf(stderr, "gearpath bridge: --dir %s: not a directory\n", opt.dir.c_str());
    return kExitBadInput;
  }
  char settle[32];
  std::snprintf(settle, sizeof settle, "%g", opt.settle_s);
  Log(opt, "watching " + opt.dir + " (settle " + settle + " s, next sequence " +
               std::to_string(state.next_sequence) + ")");
  DirectoryBridge bridge(d, &state, &sink, [&](const std::string& line) { Log(opt, line); });
  std::uint64_t sent = 0;
  while (!g_stop.load()) {
    Result<std::size_t> n = bridge.Poll(&g_stop);
    if (!n && g_stop.load()) {
      Log(opt, n.error());  // asked to stop while waiting for a subscriber: not a failure
      break;
    }
    if (!n) {
      std::fprintf(stderr, "gearpath bridge: %s\n", n.error().c_str());
      std::printf("published %llu blocks (next sequence %llu)\n",
                  static_cast<unsigned long long>(sent),
                  static_cast<unsigned long long>(state.next_sequence));
      return kExitFailure;
    }
    sent += *n;
    if (opt.once) break;
    Nap(opt.poll_s);
  }
  std::printf("published %llu blocks (next sequence %llu)\n", static_cast<unsigned long long>(sent),
              static_cast<unsigned long long>(state.next_sequence));
  return kExitOk;
}

int RunStreams(const BridgeOptions& opt, BridgeState& state, BlockSink& sink) {
  // A TCP client that stops sending is dropped after --idle-timeout: one connection is served
  // at a time, so a silent one would otherwise lock out every producer. stdin, FIFOs and files
  // are waited for indefinitely.
  const bool tcp = opt.stream.empty();
  StreamBridge bridge({.machine_id = opt.machine,
                       .block_length = opt.block_length,
                       .state_file = opt.state_file,
                       .now_ns = {},
                       .idle_timeout = tcp ? std::chrono::milliseconds(
                                                 static_cast<long long>(opt.idle_timeout_s * 1000))
                                           : std::chrono::milliseconds(0)},
                      &state, &sink);
  std::uint64_t sent = 0;
  auto finish = [&](int code) {
    std::printf("published %llu blocks (next sequence %llu)\n",
                static_cast<unsigned long long>(sent),
                static_cast<unsigned long long>(state.next_sequence));
    return code;
  };
  // One stream: its outcome, logged; false if the bridge must stop (sink or state failure).
  auto run_one = [&](int fd, const std::string& from, bool* bad) {
    Result<StreamOutcome> out = bridge.Run(fd, &g_stop);
    if (!out && g_stop.load()) {
      Log(opt, from + ": " + out.error());  // asked to stop while waiting for a subscriber
      return true;
    }
    if (!out) {
      std::fprintf(stderr, "gearpath bridge: %s: %s\n", from.c_str(), out.error().c_str());
      return false;
    }
    sent += out->blocks;
    std::string line = from + ": " + std::to_string(out->blocks) + " blocks published";
    if (out->dropped_samples) {
      line += ", last " + std::to_string(out->dropped_samples) +
              " samples per channel short of a block not sent";
    }
    if (!out->stream_error.empty()) {
      *bad = true;
      std::fprintf(stderr, "gearpath bridge: %s: %s (stream errors so far: %llu)\n", from.c_str(),
                   out->stream_error.c_str(),
                   static_cast<unsigned long long>(state.counters.stream_errors));
    }
    Log(opt, line);
    return true;
  };

  if (!opt.stream.empty()) {
    const bool stdin_input = opt.stream == "-";
    const int fd = stdin_input ? STDIN_FILENO : ::open(opt.stream.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) {
      std::fprintf(stderr, "gearpath bridge: --stream %s: cannot open: %s\n", opt.stream.c_str(),
                   std::strerror(errno));
      return kExitBadInput;
    }
    bool bad = false;
    const bool ok = run_one(fd, stdin_input ? "stdin" : opt.stream, &bad);
    if (!stdin_input) ::close(fd);
    return finish(!ok ? kExitFailure : bad ? kExitBadInput : kExitOk);
  }

  std::string address = "127.0.0.1", port_text = opt.listen;
  if (const std::size_t colon = opt.listen.rfind(':'); colon != std::string::npos) {
    address = opt.listen.substr(0, colon);
    port_text = opt.listen.substr(colon + 1);
  }
  int port = -1;
  try {
    std::size_t used = 0;
    port = std::stoi(port_text, &used);
    if (used != port_text.size()) port = -1;
  } catch (const std::exception&) {
  }
  in_addr parsed{};
  if (port < 0 || port > 65535 || ::inet_pton(AF_INET, address.c_str(), &parsed) != 1) {
    std::fprintf(stderr, "gearpath bridge: --listen %s: expected PORT or IPV4-ADDRESS:PORT\n",
                 opt.listen.c_str());
    return kExitBadInput;
  }
  Result<TcpListener> listener = TcpListener::Listen(address, static_cast<std::uint16_t>(port));
  if (!listener) {
    std::fprintf(stderr, "gearpath bridge: %s\n", listener.error().c_str());
    return kExitFailure;
  }
  // Always said (even with -q): with port 0 it is the only way to learn the port.
  std::fprintf(stderr, "gearpath bridge: listening on %s:%u (next sequence %llu)\n",
               address.c_str(), listener->port(),
               static_cast<unsigned long long>(state.next_sequence));
  while (!g_stop.load()) {
    std::string peer;
    Result<int> fd = listener->Accept(g_stop, &peer);
    if (!fd) {
      std::fprintf(stderr, "gearpath bridge: %s\n", fd.error().c_str());
      return finish(kExitFailure);
    }
    if (*fd < 0) break;
    bool bad = false;
    const bool ok = run_one(*fd, "connection from " + peer, &bad);
    ::close(*fd);
    if (!ok) return finish(kExitFailure);
    if (opt.once) break;
  }
  return finish(kExitOk);
}

int RunBridge(const BridgeOptions& opt) {
  const int modes = !opt.dir.empty() + !opt.stream.empty() + !opt.listen.empty();
  if (modes != 1) {
    std::fprintf(stderr, "gearpath bridge: give exactly one of --dir, --stream, --listen\n");
    return kExitBadInput;
  }
  Result<BridgeState> loaded = LoadBridgeState(opt.state_file);
  if (!loaded) {
    std::fprintf(stderr, "gearpath bridge: %s\n", loaded.error().c_str());
    return kExitBadInput;
  }
  BridgeState& state = *loaded;
  if (!state.machine_id.empty() && state.machine_id != opt.machine) {
    // Sequence numbers are per machine: continuing another machine's would make gaps.
    std::fprintf(stderr,
                 "gearpath bridge: %s: the state file belongs to machine \"%s\", not \"%s\" "
                 "(one state file per machine)\n",
                 opt.state_file.c_str(), state.machine_id.c_str(), opt.machine.c_str());
    return kExitBadInput;
  }
  state.machine_id = opt.machine;
  if (Status st = SaveBridgeState(state, opt.state_file); !st) {  // writable before any block
    std::fprintf(stderr, "gearpath bridge: %s\n", st.error().c_str());
    return kExitFailure;
  }

  PublisherOptions po;
  po.domain_id = opt.domain_id;
  po.dds = opt.dds;
  po.topic = opt.topic;
  po.speedup = 0.0;            // live data: publish as soon as it is there
  po.acknowledge_each = true;  // recorded as published only once a subscriber has it
  po.min_subscribers = opt.subscribers;
  po.match_timeout = std::chrono::milliseconds(static_cast<long long>(opt.wait_s * 1000));
  po.stop = &g_stop;
  BlockPublisher publisher(po);

  g_stop.store(false);
  InstallStopHandlers();
  const int code =
      !opt.dir.empty() ? RunDirectory(opt, state, publisher) : RunStreams(opt, state, publisher);
  signal(SIGINT, SIG_DFL);
  signal(SIGTERM, SIG_DFL);
  return code;
}

}  // namespace

void AddBridgeCommand(CLI::App& app, int& exit_code) {
  auto opt = std::make_shared<BridgeOptions>();
  CLI::App* cmd = app.add_subcommand(
      "bridge",
      "Live acquisition bridge: publish AccelBlocks from files exported into a directory "
      "(text/CSV, UFF 58) or from a raw sample stream (stdin, file, TCP), resuming across "
      "restarts through a state file");
  cmd->add_option("--machine", opt->machine, "Machine id to publish under")->required();
  cmd->add_option("--state", opt->state_file,
                  "State file: what was published and the next sequence number (created if "
                  "missing; one per machine)")
      ->required();
  cmd->add_option("--dir", opt->dir, "Directory mode: watch this export directory");
  cmd->add_option("--stream", opt->stream, "Stream mode: read a raw stream from FILE (- = stdin)");
  cmd->add_option("--listen", opt->listen,
                  "Stream mode: accept raw streams on [ADDRESS:]PORT (address 127.0.0.1 unless "
                  "given; port 0 = any free port)");
  cmd->add_option("--block-length", opt->block_length, "Samples per channel per block")
      ->capture_default_str()
      ->check(Positive());
  cmd->add_option("--settle", opt->settle_s,
                  "Directory mode: seconds a file's size and mtime must stay unchanged before "
                  "it is read")
      ->capture_default_str()
      ->check(NonNegative());
  cmd->add_option("--poll", opt->poll_s, "Directory mode: seconds between scans")
      ->capture_default_str()
      ->check(Positive());
  cmd->add_option("--order", opt->order, "Directory mode: file order")
      ->check(CLI::IsMember({"name", "mtime"}))
      ->capture_default_str();
  cmd->add_option("--failed-dir", opt->failed_dir,
                  "Directory mode: move files that fail to parse here (default: leave them, "
                  "remembered in the state file)");
  cmd->add_option("--format", opt->format, "Directory mode: file format (default: from the name)")
      ->check(CLI::IsMember({"auto", "text", "uff"}))
      ->capture_default_str();
  cmd->add_option("--channel", opt->channel_map,
                  "Directory mode: rename or drop a channel: COLUMN=SENSOR:AXIS or COLUMN=- "
                  "(repeatable)");
  cmd->add_option("--sample-rate", opt->sample_rate_hz,
                  "Directory mode: sample rate in Hz for text exports that state none")
      ->check(Positive());
  cmd->add_option("--shaft-speed", opt->shaft_speed_hz,
                  "Directory mode: input-shaft speed in Hz to send with every block")
      ->check(NonNegative());
  cmd->add_option("--idle-timeout", opt->idle_timeout_s,
                  "--listen: seconds without data after which a connection is closed (counted "
                  "as a stream error) so that the next producer can connect; 0 = never")
      ->capture_default_str()
      ->check(NonNegative());
  cmd->add_flag("--once", opt->once, "One directory scan, or one TCP connection, then exit");
  cmd->add_option("--topic", opt->topic, "Block topic name (default gearpath/AccelBlock)");
  AddPublishingOptions(cmd, &opt->domain_id, &opt->dds, &opt->subscribers, &opt->wait_s);
  cmd->add_flag("--quiet,-q", opt->quiet, "No per-file / per-stream lines on stderr");
  cmd->callback([opt, &exit_code] {
    try {
      exit_code = RunBridge(*opt);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "gearpath bridge: %s\n", e.what());
      exit_code = kExitFailure;
    }
  });
}

}  // namespace gearpath::tools
