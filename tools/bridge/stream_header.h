// The header of a `gearpath bridge` raw sample stream (stdin, a FIFO/file, or a TCP
// connection), then interleaved frames. All fields little-endian; docs/tools.md, "bridge".
//
//   offset  size  field
//   0       4     magic "GPBS"
//   4       2     version, 1
//   6       2     channel count C (1..gearpath_MAX_CHANNELS)
//   8       1     sample format: 1 = int16, 2 = float32
//   9       7     reserved, zero
//   16      8     sample rate, Hz (float64, finite, > 0)
//   24      8     input-shaft speed, Hz (float64, finite, >= 0; 0 = not known)
//   32      8     t0 of the first sample, ns since the Unix epoch, UTC (int64; 0 = arrival time)
//   40      C x 40 bytes, one per channel:
//             0   8   scale (float64, finite, != 0): value in m/s^2 = sample x scale
//             8   32  name, UTF-8, NUL-padded: "A1-X" = sensor A1, axis x (as text exports)
//   then frames: C samples (one per channel, in header order) per sampling instant.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "core/common/accel_block.h"
#include "core/common/result.h"

namespace gearpath::tools {

enum class StreamSampleFormat : std::uint8_t { kInt16 = 1, kFloat32 = 2 };

inline constexpr char kStreamMagic[4] = {'G', 'P', 'B', 'S'};
inline constexpr std::uint16_t kStreamVersion = 1;
inline constexpr std::size_t kStreamFixedHeaderBytes = 40;
inline constexpr std::size_t kStreamChannelBytes = 40;
inline constexpr std::size_t kStreamNameBytes = 32;

struct StreamHeader {
  StreamSampleFormat format = StreamSampleFormat::kFloat32;
  double sample_rate_hz = 0.0;
  double shaft_speed_hz = 0.0;
  std::int64_t t0_ns = 0;
  std::vector<double> scales;         // per channel
  std::vector<ChannelInfo> channels;  // sensor/axis from the names, unit m/s^2

  std::size_t sample_bytes() const { return format == StreamSampleFormat::kInt16 ? 2 : 4; }
  std::size_t frame_bytes() const { return channels.size() * sample_bytes(); }
};

// Bytes of the whole header once its first 8 bytes (magic, version, channel count) are known;
// an error if those are already wrong.
Result<std::size_t> StreamHeaderSize(std::span<const std::byte> first8);

// Parses a complete header (exactly StreamHeaderSize bytes). Errors say which field and why.
Result<StreamHeader> ParseStreamHeader(std::span<const std::byte> bytes);

// The bytes of `header` (for producers and tests; names longer than 31 bytes are an error).
Result<std::vector<std::byte>> EncodeStreamHeader(const StreamHeader& header,
                                                  const std::vector<std::string>& names);

}  // namespace gearpath::tools
