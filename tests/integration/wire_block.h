// ToWire: a core AccelBlock copied into an AccelBlock wire sample, UNCHECKED. Publishers use
// dds::FillWireBlock, which refuses a block whose samples do not match its layout; the
// daemon's bad-block tests must publish exactly such blocks, so they copy without checks.
#pragma once

#include "core/common/accel_block.h"
#include "idl/dds/accel_block_wire.h"
#include "idl/dds/gearpath_topics.h"

namespace gearpath::testing {

inline bool ToWire(const AccelBlock& b, dds::Owned<gearpath_AccelBlock>& s) {
  if (!dds::SetString(s->machine_id, b.machine_id)) return false;
  s->sequence_number = b.sequence;
  s->t0_ns = b.t0_ns;
  s->sample_rate_hz = b.sample_rate_hz;
  s->speed_hz = b.speed_hz;
  s->speed_source = dds::WireSpeedSource(b.speed_source);
  if (!dds::Resize(s->channels, static_cast<std::uint32_t>(b.channels.size()))) return false;
  for (std::size_t c = 0; c < b.channels.size(); ++c) {
    auto& w = s->channels._buffer[c];
    if (!dds::SetString(w.sensor_id, b.channels[c].sensor)) return false;
    w.axis = b.channels[c].axis == Axis::kX   ? gearpath_AXIS_X
             : b.channels[c].axis == Axis::kY ? gearpath_AXIS_Y
                                              : gearpath_AXIS_Z;
    (void)dds::SetString(w.unit, b.channels[c].unit);
    w.sensitivity_mv_per_unit = b.channels[c].sensitivity;
  }
  s->samples_per_channel = b.samples_per_channel;
  return dds::Assign(s->samples, std::span<const float>(b.samples));
}

}  // namespace gearpath::testing
