// ToWire: a core AccelBlock copied into an AccelBlock wire sample (the acquisition bridge's job,
// done here by the tests and the by-hand simulator publisher).
#pragma once

#include "core/common/accel_block.h"
#include "idl/dds/gearpath_topics.h"

namespace gearpath::testing {

// Copies a core block into a wire sample (test side: the acquisition bridge's job).
inline bool ToWire(const AccelBlock& b, dds::Owned<gearpath_AccelBlock>& s) {
  if (!dds::SetString(s->machine_id, b.machine_id)) return false;
  s->sequence_number = b.sequence;
  s->t0_ns = b.t0_ns;
  s->sample_rate_hz = b.sample_rate_hz;
  s->speed_hz = b.speed_hz;
  s->speed_source = b.speed_source == SpeedSource::kUnknown ? gearpath_SPEED_UNKNOWN
                                                            : gearpath_SPEED_ACQUISITION_TACHOMETER;
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
