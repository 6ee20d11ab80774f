// AccelBlock: one block of housing accelerations, as core/ sees it (independent of DDS).
//
// Samples are in engineering units (m/s^2) in PLANAR layout: all samples of channel 0, then all
// of channel 1, ... (samples.size() == channels.size() * samples_per_channel). float holds a
// 24-bit acquisition exactly enough (~7 significant digits) at half the bandwidth of double;
// the pipeline computes in double. The daemon fills an AccelBlockView from the DDS sample
// without copying; simulators and readers fill an owning AccelBlock.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace gearpath {

enum class Axis : std::uint8_t { kX, kY, kZ };

// Where the input-shaft speed used for a result came from (reported with every result).
enum class SpeedSource : std::uint8_t {
  kUnknown,        // not known (yet)
  kAcquisition,    // supplied with the block (tachometer / acquisition)
  kConfiguration,  // nominal speed from the machine's configuration
  kEstimated,      // estimated from the spectrum (mesh-frequency tracking)
};

struct ChannelInfo {
  std::string sensor;         // sensor id, e.g. "A1"
  Axis axis = Axis::kX;
  std::string unit = "m/s^2";
  double sensitivity = 0.0;   // mV per unit; 0 when unknown
};

struct AccelBlockView {
  std::string_view machine_id;
  std::uint64_t sequence = 0;
  std::int64_t t0_ns = 0;             // time of the first sample, ns since the Unix epoch (UTC)
  double sample_rate_hz = 0.0;
  double speed_hz = 0.0;              // input-shaft speed; 0 when the block does not carry it
  SpeedSource speed_source = SpeedSource::kUnknown;
  // Operating load (torque, power, current: the plant's own unit, the same for every block of a
  // machine); 0 when the block does not carry it. The baseline judges only the loads it learned.
  double load = 0.0;
  std::span<const ChannelInfo> channels;
  std::uint32_t samples_per_channel = 0;
  std::span<const float> samples;     // planar, channels.size() * samples_per_channel

  std::span<const float> channel(std::size_t c) const {
    return samples.subspan(c * samples_per_channel, samples_per_channel);
  }
};

struct AccelBlock {
  std::string machine_id;
  std::uint64_t sequence = 0;
  std::int64_t t0_ns = 0;
  double sample_rate_hz = 0.0;
  double speed_hz = 0.0;
  SpeedSource speed_source = SpeedSource::kUnknown;
  double load = 0.0;
  std::vector<ChannelInfo> channels;
  std::uint32_t samples_per_channel = 0;
  std::vector<float> samples;  // planar

  AccelBlockView view() const {
    return {machine_id,   sequence, t0_ns,    sample_rate_hz,      speed_hz,
            speed_source, load,     channels, samples_per_channel, samples};
  }
};

}  // namespace gearpath
