#include "core/evaluation/simulated_block_header.h"

#include <cmath>

namespace gearpath {

void SimulatedBlockHeader::Stamp(std::uint64_t index, std::uint32_t len,
                                 const std::vector<ChannelInfo>& channels,
                                 AccelBlock& block) const {
  const std::int64_t first = static_cast<std::int64_t>(index) * len;
  block.machine_id = machine_id;
  block.sequence = first_sequence + index;
  block.t0_ns = start_time_ns + std::llround(static_cast<double>(first) * 1e9 / sample_rate_hz);
  block.sample_rate_hz = sample_rate_hz;
  block.speed_hz = input_speed_hz;
  block.speed_source = SpeedSource::kAcquisition;
  block.channels = channels;
  block.samples_per_channel = len;
}

}  // namespace gearpath
