#include "tools/bridge/stream_cutter.h"

#include <chrono>
#include <cmath>
#include <cstring>

#include "idl/gearpath.h"

namespace gearpath::tools {

StreamCutter::StreamCutter(StreamCutterOptions options) : options_(std::move(options)) {
  if (!options_.now_ns) {
    options_.now_ns = [] {
      return std::chrono::duration_cast<std::chrono::nanoseconds>(
                 std::chrono::system_clock::now().time_since_epoch())
          .count();
    };
  }
}

Status StreamCutter::TakeHeader(std::span<const std::byte>& bytes) {
  auto take = [&](std::size_t want) {
    const std::size_t n = std::min(want - std::min(want, pending_.size()), bytes.size());
    pending_.insert(pending_.end(), bytes.begin(), bytes.begin() + static_cast<long>(n));
    bytes = bytes.subspan(n);
    return pending_.size() >= want;
  };
  if (header_size_ == 0) {
    const bool have8 = take(8);
    // Say "not a bridge stream" as soon as the magic is wrong, even for a stream of 3 bytes.
    const std::size_t n = std::min<std::size_t>(pending_.size(), 4);
    if (!have8 && std::memcmp(pending_.data(), kStreamMagic, n) != 0) {
      std::vector<std::byte> padded = pending_;
      padded.resize(8, std::byte{0});
      return Error{StreamHeaderSize(padded).error()};
    }
    if (!have8) return Status::Ok();
    Result<std::size_t> size = StreamHeaderSize(pending_);
    if (!size) return Error{size.error()};
    header_size_ = *size;
  }
  if (!take(header_size_)) return Status::Ok();
  Result<StreamHeader> h = ParseStreamHeader(pending_);
  if (!h) return Error{h.error()};
  const std::size_t channels = h->channels.size();
  const std::uint32_t length = options_.block_length;
  if (length == 0 || length > gearpath_MAX_SAMPLES_PER_CHANNEL ||
      std::size_t{length} * channels > gearpath_MAX_BLOCK_SAMPLES) {
    return Error{"--block-length " + std::to_string(length) + " x " + std::to_string(channels) +
                 " channels exceeds the AccelBlock bounds (" +
                 std::to_string(gearpath_MAX_SAMPLES_PER_CHANNEL) + " per channel, " +
                 std::to_string(gearpath_MAX_BLOCK_SAMPLES) + " per block)"};
  }
  t0_ns_ = h->t0_ns != 0 ? h->t0_ns : options_.now_ns();
  channels_ = h->channels;
  block_.assign(channels * length, 0.0f);
  header_ = std::move(*h);
  pending_.clear();
  return Status::Ok();
}

void StreamCutter::DecodeFrame(const std::byte* frame) {
  const StreamHeader& h = *header_;
  const std::size_t length = options_.block_length;
  for (std::size_t c = 0; c < channels_.size(); ++c) {
    double raw;
    if (h.format == StreamSampleFormat::kInt16) {
      std::int16_t v;
      std::memcpy(&v, frame + 2 * c, 2);
      raw = v;
    } else {
      float v;
      std::memcpy(&v, frame + 4 * c, 4);
      if (h.scales[c] == 1.0) {  // kept bit for bit (NaN payloads, -0)
        block_[c * length + frames_in_block_] = v;
        continue;
      }
      raw = v;
    }
    block_[c * length + frames_in_block_] = static_cast<float>(raw * h.scales[c]);
  }
  ++frames_in_block_;
}

Status StreamCutter::Feed(std::span<const std::byte> bytes, const BlockHandler& on_block) {
  if (!error_.empty()) return Error{error_};
  auto fail = [&](std::string e) {
    error_ = std::move(e);
    return Status(Error{error_});
  };
  if (!header_) {
    if (Status st = TakeHeader(bytes); !st) return fail(st.error());
    if (!header_) return Status::Ok();
  }
  const std::size_t frame = header_->frame_bytes();
  while (!bytes.empty()) {
    const std::byte* data = nullptr;
    if (!pending_.empty() || bytes.size() < frame) {
      const std::size_t n = std::min(frame - pending_.size(), bytes.size());
      pending_.insert(pending_.end(), bytes.begin(), bytes.begin() + static_cast<long>(n));
      bytes = bytes.subspan(n);
      if (pending_.size() < frame) break;
      data = pending_.data();
    } else {
      data = bytes.data();
      bytes = bytes.subspan(frame);
    }
    DecodeFrame(data);
    pending_.clear();
    if (frames_in_block_ < options_.block_length) continue;
    const std::uint64_t first_sample = blocks_ * options_.block_length;
    AccelBlockView v;
    v.machine_id = options_.machine_id;
    v.sequence = options_.first_sequence + blocks_;
    const double offset_ns = static_cast<double>(first_sample) / header_->sample_rate_hz * 1e9;
    // A header t0 near the end of int64 time must not wrap around (nor be undefined).
    if (!(offset_ns < 9.2e18) ||
        __builtin_add_overflow(t0_ns_, std::llround(offset_ns), &v.t0_ns)) {
      return fail("stream t0 " + std::to_string(t0_ns_) + " ns plus " +
                  std::to_string(first_sample) + " samples overflows the int64 time");
    }
    v.sample_rate_hz = header_->sample_rate_hz;
    v.speed_hz = header_->shaft_speed_hz;
    v.speed_source =
        header_->shaft_speed_hz > 0 ? SpeedSource::kAcquisition : SpeedSource::kUnknown;
    v.channels = channels_;
    v.samples_per_channel = options_.block_length;
    v.samples = block_;
    if (Status st = on_block(v); !st) return fail(st.error());
    ++blocks_;
    frames_in_block_ = 0;
  }
  return Status::Ok();
}

Status StreamCutter::Finish() {
  if (!error_.empty()) return Error{error_};
  if (!header_) {
    return Error{"stream ended inside its header (" + std::to_string(pending_.size()) + " bytes" +
                 (header_size_ ? " of " + std::to_string(header_size_) : std::string()) + ")"};
  }
  if (!pending_.empty()) {
    return Error{"stream truncated: it ends " + std::to_string(pending_.size()) +
                 " bytes into a frame of " + std::to_string(header_->frame_bytes()) +
                 " bytes (after " + std::to_string(blocks_) + " blocks)"};
  }
  return Status::Ok();
}

}  // namespace gearpath::tools
