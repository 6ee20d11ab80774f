// The header every simulated plant stream writes on its blocks: the scenario's machine, the
// stream's clock and sequence, and the speed the acquisition reports. Shared by the linear
// (plant_simulator.h) and the time-domain (parametric_plant_simulator.h) streams, so both
// number and time their blocks the same way.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/common/accel_block.h"

namespace gearpath {

struct SimulatedBlockHeader {
  std::string machine_id;
  double sample_rate_hz = 8000.0;
  double input_speed_hz = 10.0;  // reported by every block (SpeedSource::kAcquisition)
  std::int64_t start_time_ns = 0;
  std::uint64_t first_sequence = 0;

  // Writes the header of the stream's block `index` (blocks of `len` samples per channel, the
  // first starting at start_time_ns); the samples are the caller's.
  void Stamp(std::uint64_t index, std::uint32_t len, const std::vector<ChannelInfo>& channels,
             AccelBlock& block) const;
};

}  // namespace gearpath
