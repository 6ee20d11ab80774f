#include "tools/bridge/stream_bridge.h"

#include <poll.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <vector>

#include "tools/bridge/stream_cutter.h"

namespace gearpath::tools {

StreamBridge::StreamBridge(StreamBridgeOptions options, BridgeState* state, BlockSink* sink)
    : options_(std::move(options)), state_(state), sink_(sink) {}

Result<StreamOutcome> StreamBridge::Run(int fd, const std::atomic<bool>* stop) {
  StreamCutter cutter({.machine_id = options_.machine_id,
                       .block_length = options_.block_length,
                       .first_sequence = state_->next_sequence,
                       .now_ns = options_.now_ns});
  std::string fatal;  // sink or state failure: distinguishes them from a bad stream
  auto on_block = [&](const AccelBlockView& block) -> Status {
    if (Status st = sink_->Publish(block); !st) {
      fatal = "block sequence " + std::to_string(block.sequence) + ": " + st.error();
      return Error{fatal};
    }
    state_->next_sequence = block.sequence + 1;
    ++state_->counters.blocks_published;
    if (Status st = SaveBridgeState(*state_, options_.state_file); !st) {
      fatal = st.error();
      return st;
    }
    return Status::Ok();
  };

  StreamOutcome out;
  std::vector<std::byte> buffer(1 << 16);
  Status stream = Status::Ok();
  bool stopped = false;
  using Clock = std::chrono::steady_clock;
  Clock::time_point last_data = Clock::now();
  for (;;) {
    if (stop && stop->load()) {
      stopped = true;
      break;
    }
    // poll with a short timeout, so a signal's stop flag is seen on a quiet stream.
    int wait_ms = 200;
    if (options_.idle_timeout.count() > 0) {
      const auto idle = Clock::now() - last_data;
      if (idle >= options_.idle_timeout) {
        char seconds[32];
        std::snprintf(seconds, sizeof seconds, "%g",
                      std::chrono::duration<double>(options_.idle_timeout).count());
        stream = Error{std::string("no data for ") + seconds + " s (idle timeout): stream ended" +
                       (cutter.header() ? ", " + std::to_string(cutter.dropped_samples()) +
                                              " frames short of a block not sent"
                                        : std::string(" before its header was complete"))};
        break;
      }
      const auto left =
          std::chrono::duration_cast<std::chrono::milliseconds>(options_.idle_timeout - idle);
      wait_ms = static_cast<int>(std::clamp<long long>(left.count() + 1, 1, 200));
    }
    pollfd p{fd, POLLIN, 0};
    const int ready = ::poll(&p, 1, wait_ms);
    if (ready < 0 && errno == EINTR) continue;
    if (ready == 0) continue;
    const ssize_t n = ready < 0 ? -1 : ::read(fd, buffer.data(), buffer.size());
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      stream = Error{std::string("read: ") + std::strerror(errno)};
      break;
    }
    if (n == 0) break;  // end of stream
    last_data = Clock::now();
    stream = cutter.Feed(std::span<const std::byte>(buffer.data(), static_cast<std::size_t>(n)),
                         on_block);
    if (!stream) break;
  }
  if (!fatal.empty()) return Error{fatal};
  if (stream && !stopped) stream = cutter.Finish();
  out.blocks = cutter.blocks();
  out.dropped_samples = cutter.header() ? cutter.dropped_samples() : 0;
  state_->counters.dropped_samples += out.dropped_samples;
  if (!stream) {
    out.stream_error = stream.error();
    ++state_->counters.stream_errors;
    state_->last_error = stream.error();
  } else if (!stopped) {
    ++state_->counters.streams_ended;
  }
  if (Status st = SaveBridgeState(*state_, options_.state_file); !st) return Error{st.error()};
  return out;
}

}  // namespace gearpath::tools
