#include "tools/bridge/stream_header.h"

#include <bit>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstring>

#include "core/io/text_export.h"
#include "idl/gearpath.h"

namespace gearpath::tools {
namespace {

static_assert(std::endian::native == std::endian::little,
              "the stream is little-endian and read as such; add byte swaps for this target");

template <typename T>
T Read(std::span<const std::byte> bytes, std::size_t offset) {
  T value;
  std::memcpy(&value, bytes.data() + offset, sizeof(T));
  return value;
}

template <typename T>
void Write(std::vector<std::byte>& out, std::size_t offset, T value) {
  std::memcpy(out.data() + offset, &value, sizeof(T));
}

bool ValidUtf8(const std::string& s) {
  std::size_t i = 0;
  while (i < s.size()) {
    const auto c = static_cast<unsigned char>(s[i]);
    const std::size_t n = c < 0x80         ? 1
                          : (c >> 5) == 6  ? 2
                          : (c >> 4) == 14 ? 3
                          : (c >> 3) == 30 ? 4
                                           : 0;
    if (n == 0 || i + n > s.size()) return false;
    for (std::size_t k = 1; k < n; ++k) {
      if ((static_cast<unsigned char>(s[i + k]) >> 6) != 2) return false;
    }
    i += n;
  }
  return true;
}

}  // namespace

Result<std::size_t> StreamHeaderSize(std::span<const std::byte> first8) {
  if (first8.size() < 8) return Error{"stream header: fewer than 8 bytes"};
  if (std::memcmp(first8.data(), kStreamMagic, 4) != 0) {
    std::string got;
    for (std::size_t i = 0; i < 4; ++i) {
      const auto c = static_cast<unsigned char>(first8[i]);
      got += std::isprint(c) ? std::string(1, static_cast<char>(c)) : "\\x" + [&] {
        char hex[3];
        std::snprintf(hex, sizeof hex, "%02x", c);
        return std::string(hex);
      }();
    }
    return Error{"stream header: bad magic \"" + got +
                 "\" (expected \"GPBS\"): not a gearpath "
                 "bridge stream (docs/tools.md, \"bridge\")"};
  }
  const auto version = Read<std::uint16_t>(first8, 4);
  if (version != kStreamVersion) {
    return Error{"stream header: version " + std::to_string(version) +
                 " is not supported (this "
                 "bridge reads version " +
                 std::to_string(kStreamVersion) + ")"};
  }
  const auto channels = Read<std::uint16_t>(first8, 6);
  if (channels == 0 || channels > gearpath_MAX_CHANNELS) {
    return Error{"stream header: channel count " + std::to_string(channels) + " outside 1.." +
                 std::to_string(gearpath_MAX_CHANNELS)};
  }
  return kStreamFixedHeaderBytes + channels * kStreamChannelBytes;
}

Result<StreamHeader> ParseStreamHeader(std::span<const std::byte> bytes) {
  Result<std::size_t> size = StreamHeaderSize(bytes);
  if (!size) return Error{size.error()};
  if (bytes.size() != *size) {
    return Error{"stream header: " + std::to_string(bytes.size()) + " bytes, expected " +
                 std::to_string(*size)};
  }
  StreamHeader h;
  const auto format = Read<std::uint8_t>(bytes, 8);
  if (format != 1 && format != 2) {
    return Error{"stream header: sample format " + std::to_string(format) +
                 " unknown (1 = int16, 2 = float32)"};
  }
  h.format = static_cast<StreamSampleFormat>(format);
  for (std::size_t i = 9; i < 16; ++i) {
    if (bytes[i] != std::byte{0}) return Error{"stream header: reserved bytes 9..15 not zero"};
  }
  h.sample_rate_hz = Read<double>(bytes, 16);
  if (!std::isfinite(h.sample_rate_hz) || h.sample_rate_hz <= 0) {
    return Error{"stream header: sample rate " + std::to_string(h.sample_rate_hz) +
                 " Hz is not a finite positive number"};
  }
  h.shaft_speed_hz = Read<double>(bytes, 24);
  if (!std::isfinite(h.shaft_speed_hz) || h.shaft_speed_hz < 0) {
    return Error{"stream header: shaft speed " + std::to_string(h.shaft_speed_hz) +
                 " Hz is not a finite number >= 0"};
  }
  h.t0_ns = Read<std::int64_t>(bytes, 32);
  if (h.t0_ns < 0) return Error{"stream header: start time " + std::to_string(h.t0_ns) + " < 0"};
  const std::size_t n = (bytes.size() - kStreamFixedHeaderBytes) / kStreamChannelBytes;
  for (std::size_t c = 0; c < n; ++c) {
    const std::size_t at = kStreamFixedHeaderBytes + c * kStreamChannelBytes;
    const std::string where = "stream header: channel " + std::to_string(c + 1) + ": ";
    const double scale = Read<double>(bytes, at);
    if (!std::isfinite(scale) || scale == 0) {
      return Error{where + "scale " + std::to_string(scale) + " is not a finite non-zero number"};
    }
    const char* name_bytes = reinterpret_cast<const char*>(bytes.data() + at + 8);
    const std::string name(name_bytes, strnlen(name_bytes, kStreamNameBytes));
    if (name.empty()) return Error{where + "empty name"};
    if (!ValidUtf8(name)) return Error{where + "name is not UTF-8"};
    ChannelInfo info;
    SplitChannelName(name, &info.sensor, &info.axis);
    info.unit = "m/s^2";
    h.scales.push_back(scale);
    h.channels.push_back(std::move(info));
  }
  return h;
}

Result<std::vector<std::byte>> EncodeStreamHeader(const StreamHeader& header,
                                                  const std::vector<std::string>& names) {
  if (names.size() != header.scales.size() || names.empty()) {
    return Error{"stream header: one name and one scale per channel"};
  }
  std::vector<std::byte> out(kStreamFixedHeaderBytes + names.size() * kStreamChannelBytes);
  std::memcpy(out.data(), kStreamMagic, 4);
  Write<std::uint16_t>(out, 4, kStreamVersion);
  Write<std::uint16_t>(out, 6, static_cast<std::uint16_t>(names.size()));
  Write<std::uint8_t>(out, 8, static_cast<std::uint8_t>(header.format));
  Write<double>(out, 16, header.sample_rate_hz);
  Write<double>(out, 24, header.shaft_speed_hz);
  Write<std::int64_t>(out, 32, header.t0_ns);
  for (std::size_t c = 0; c < names.size(); ++c) {
    if (names[c].size() >= kStreamNameBytes) {
      return Error{"stream header: channel name \"" + names[c] + "\" longer than 31 bytes"};
    }
    const std::size_t at = kStreamFixedHeaderBytes + c * kStreamChannelBytes;
    Write<double>(out, at, header.scales[c]);
    std::memcpy(out.data() + at + 8, names[c].data(), names[c].size());
  }
  return out;
}

}  // namespace gearpath::tools
