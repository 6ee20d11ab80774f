#include "tests/interop/fastdds_noise_block.h"

#include <cmath>
#include <random>

namespace gearpath_interop {

gearpath::AccelBlock MakeNoiseBlock(const NoiseBlockShape& shape, std::uint64_t sequence) {
  gearpath::AccelBlock block;
  block.machine_id(shape.machine_id);
  block.sequence_number(sequence);
  // 2026-01-01T00:00:00Z plus whole blocks: a plausible acquisition clock.
  constexpr std::int64_t kEpochStartNs = 1'767'225'600'000'000'000;
  const double block_s = shape.samples_per_channel / shape.sample_rate_hz;
  block.t0_ns(kEpochStartNs + static_cast<std::int64_t>(
                                  std::llround(static_cast<double>(sequence) * block_s * 1e9)));
  block.sample_rate_hz(shape.sample_rate_hz);
  block.speed_hz(shape.speed_hz);
  block.speed_source(gearpath::SPEED_ACQUISITION_TACHOMETER);
  for (const ChannelName& c : shape.channels) {
    gearpath::ChannelInfo info;
    info.sensor_id(c.sensor);
    info.axis(c.axis);
    info.unit("m/s^2");
    info.sensitivity_mv_per_unit(100.0);
    block.channels().push_back(info);
  }
  block.samples_per_channel(shape.samples_per_channel);
  std::mt19937 rng(static_cast<std::uint32_t>(sequence));
  std::normal_distribution<float> noise(0.0f, 1.0f);
  block.samples().resize(shape.channels.size() * shape.samples_per_channel);
  for (float& x : block.samples()) x = noise(rng);
  return block;
}

gearpath::AccelBlockV2 WithLoad(const gearpath::AccelBlock& block, double load,
                                const std::string& load_unit) {
  gearpath::AccelBlockV2 v2;
  v2.machine_id(block.machine_id());
  v2.sequence_number(block.sequence_number());
  v2.t0_ns(block.t0_ns());
  v2.sample_rate_hz(block.sample_rate_hz());
  v2.speed_hz(block.speed_hz());
  v2.speed_source(block.speed_source());
  v2.channels(block.channels());
  v2.samples_per_channel(block.samples_per_channel());
  v2.samples(block.samples());
  v2.load(load);
  v2.load_unit(load_unit);
  return v2;
}

}  // namespace gearpath_interop
