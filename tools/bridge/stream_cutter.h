// StreamCutter: turns the bytes of one raw sample stream (stream_header.h) into AccelBlocks of
// a fixed length, with consecutive sequence numbers and t0 = header t0 + samples / rate.
//
// Push-style and free of I/O: the bridge feeds whatever read() returned, tests feed bytes in
// any split. Samples are de-interleaved into the block's planar layout and scaled to m/s^2.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "core/common/accel_block.h"
#include "core/common/result.h"
#include "tools/bridge/stream_header.h"

namespace gearpath::tools {

struct StreamCutterOptions {
  std::string machine_id;
  std::uint32_t block_length = 4096;  // samples per channel per block
  std::uint64_t first_sequence = 0;
  std::function<std::int64_t()> now_ns{};  // t0 when the header says 0; empty: system clock
};

class StreamCutter {
 public:
  using BlockHandler = std::function<Status(const AccelBlockView&)>;
  explicit StreamCutter(StreamCutterOptions options);

  // Consumes `bytes`, handing each completed block to `on_block` in order. A malformed header,
  // or an error from `on_block`, is returned and ends the stream (later calls return it again).
  Status Feed(std::span<const std::byte> bytes, const BlockHandler& on_block);

  // End of input. An error if the header is incomplete or the stream stops inside a frame
  // (truncated); whole frames short of a block are not sent, see dropped_samples().
  Status Finish();

  const std::optional<StreamHeader>& header() const { return header_; }
  std::uint64_t blocks() const { return blocks_; }
  std::uint64_t next_sequence() const { return options_.first_sequence + blocks_; }
  std::uint64_t dropped_samples() const { return frames_in_block_; }  // per channel, at Finish

 private:
  Status TakeHeader(std::span<const std::byte>& bytes);
  void DecodeFrame(const std::byte* frame);

  StreamCutterOptions options_;
  std::vector<std::byte> pending_;  // header bytes, or a partial frame
  std::optional<StreamHeader> header_;
  std::size_t header_size_ = 0;
  std::int64_t t0_ns_ = 0;
  std::vector<ChannelInfo> channels_;
  std::vector<float> block_;  // planar, being filled
  std::uint32_t frames_in_block_ = 0;
  std::uint64_t blocks_ = 0;
  std::string error_;
};

}  // namespace gearpath::tools
