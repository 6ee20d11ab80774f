// StreamBridge: reads raw sample streams (stream_header.h) from a file descriptor (stdin, a
// FIFO or file, an accepted TCP connection), cuts them into blocks (StreamCutter), publishes
// each and records it in the state file, so that sequence numbers continue across streams,
// connections and restarts of the bridge.
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>

#include "core/common/result.h"
#include "tools/bridge/bridge_state.h"
#include "tools/common/block_sink.h"

namespace gearpath::tools {

struct StreamBridgeOptions {
  std::string machine_id;
  std::uint32_t block_length = 4096;
  std::filesystem::path state_file;
  std::function<std::int64_t()> now_ns{};  // t0 for streams whose header says 0; empty: clock
  // A stream that delivers no byte for this long is ended as a stream error (the connection is
  // then closed by the caller, so that a silent TCP client cannot hold the one connection slot
  // forever); zero: wait for data indefinitely (stdin, FIFOs, files).
  std::chrono::milliseconds idle_timeout{0};
};

struct StreamOutcome {
  std::uint64_t blocks = 0;
  std::uint64_t dropped_samples = 0;  // per channel: the tail short of a block
  std::string stream_error;           // bad input (header, truncation, read error); counted
};

class StreamBridge {
 public:
  // `state` must have been loaded from options.state_file and outlive this.
  StreamBridge(StreamBridgeOptions options, BridgeState* state, BlockSink* sink);

  // Reads one stream from `fd` to its end (or until `stop`). A bad stream is reported in the
  // outcome and counted in the state; the error result is kept for what must stop the bridge:
  // a block the sink did not take, a state file that cannot be written.
  Result<StreamOutcome> Run(int fd, const std::atomic<bool>* stop = nullptr);

 private:
  StreamBridgeOptions options_;
  BridgeState* state_;
  BlockSink* sink_;
};

}  // namespace gearpath::tools
