// libFuzzer target: block validation and the sequence tracker. The input is read as a block
// header (sequence, sample rate, speed, channel count, samples per channel) then float
// samples, so every field, including inconsistent sizes, NaN and flat channels, is fuzzed.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <vector>

#include "core/pipeline/block_validation.h"

namespace {

template <typename T>
T Take(const std::uint8_t*& data, std::size_t& size) {
  T value{};
  const std::size_t n = std::min(size, sizeof(T));
  std::memcpy(&value, data, n);
  data += n;
  size -= n;
  return value;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace gearpath;
  static SequenceTracker tracker;  // state across inputs, as in the daemon
  BlockExpectations expected;
  expected.machine_id = "gb1";
  expected.channels = {{"A1", Axis::kX}, {"A1", Axis::kY}, {"A2", Axis::kZ}};
  expected.sample_rate_hz = 8000.0;
  expected.min_samples_per_channel = 4;
  expected.max_samples_per_channel = 4096;
  expected.max_total_samples = 3 * 4096;
  expected.min_speed_hz = 4.0;
  expected.max_speed_hz = 24.0;

  AccelBlockView block;
  block.machine_id = "gb1";
  block.sequence = Take<std::uint64_t>(data, size);
  block.sample_rate_hz = Take<std::uint8_t>(data, size) < 200 ? 8000.0 : Take<double>(data, size);
  block.speed_hz = Take<double>(data, size);
  const std::size_t channels = Take<std::uint8_t>(data, size) % 5;
  block.samples_per_channel = Take<std::uint16_t>(data, size);
  std::vector<ChannelInfo> layout = {{"A1", Axis::kX, "m/s^2", 0.0},
                                     {"A1", Axis::kY, "m/s^2", 0.0},
                                     {"A2", Axis::kZ, "m/s^2", 0.0},
                                     {"A3", Axis::kX, "m/s^2", 0.0}};
  layout.resize(channels);
  block.channels = layout;
  std::vector<float> samples(size / sizeof(float));
  if (!samples.empty()) std::memcpy(samples.data(), data, samples.size() * sizeof(float));
  block.samples = samples;

  MessageText message;
  const RejectReason reason = ValidateBlock(block, expected, message);
  if (reason == RejectReason::kNone) {
    const auto verdict = tracker.Observe(block.sequence, "gb1", message);
    // A restart or a counted gap, never a gap wider than the tracker's bound.
    if (verdict.gap > SequenceTracker::kDefaultMaxGap) __builtin_trap();
  } else if (message.empty()) {
    __builtin_trap();  // every rejection says why
  }
  return 0;
}
