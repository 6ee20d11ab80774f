// A valid AccelBlock built with fastddsgen's type, as a plant's acquisition bridge on Fast DDS
// would publish it: Gaussian noise on every channel the machine expects. Noise is enough for the
// interoperability test: gearpathd accepts and processes it (a healthy-looking block) and
// publishes every result; what the results say is not the point, that both stacks agree is.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "gearpath.h"  // fastddsgen's output (build tree)

namespace gearpath_interop {

struct ChannelName {
  std::string sensor;  // sensor id as in the machine's FRF set, e.g. "p1"
  gearpath::Axis axis;
};

struct NoiseBlockShape {
  std::string machine_id;
  std::vector<ChannelName> channels;
  std::uint32_t samples_per_channel = 0;
  double sample_rate_hz = 0.0;
  double speed_hz = 0.0;  // input shaft speed carried by the block (tachometer)
};

// Block `sequence` (1, 2, ...) of the stream: t0 advances by one block length per sequence
// number, the noise is seeded by the sequence so a run is reproducible.
gearpath::AccelBlock MakeNoiseBlock(const NoiseBlockShape& shape, std::uint64_t sequence);

// The same block as an AccelBlockV2 (contract version 4) carrying `load` in `load_unit`.
gearpath::AccelBlockV2 WithLoad(const gearpath::AccelBlock& block, double load,
                                const std::string& load_unit);

}  // namespace gearpath_interop
