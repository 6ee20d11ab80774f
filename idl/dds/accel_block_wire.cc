#include "idl/dds/accel_block_wire.h"

#include <string>

#include "idl/dds/sequence.h"

namespace gearpath::dds {
namespace {

gearpath_Axis WireAxis(Axis axis) {
  switch (axis) {
    case Axis::kY: return gearpath_AXIS_Y;
    case Axis::kZ: return gearpath_AXIS_Z;
    case Axis::kX: break;
  }
  return gearpath_AXIS_X;
}

Axis CoreAxis(gearpath_Axis axis) {
  switch (axis) {
    case gearpath_AXIS_Y: return Axis::kY;
    case gearpath_AXIS_Z: return Axis::kZ;
    default: return Axis::kX;
  }
}

SpeedSource CoreSpeedSource(gearpath_SpeedSource source) {
  switch (source) {
    case gearpath_SPEED_ACQUISITION_TACHOMETER: return SpeedSource::kAcquisition;
    case gearpath_SPEED_OTHER: return SpeedSource::kConfiguration;
    default: return SpeedSource::kUnknown;
  }
}

}  // namespace

// Configuration and estimates are not something an acquisition supplies; a publisher that
// knows the speed from elsewhere says SPEED_OTHER.
gearpath_SpeedSource WireSpeedSource(SpeedSource source) noexcept {
  switch (source) {
    case SpeedSource::kAcquisition: return gearpath_SPEED_ACQUISITION_TACHOMETER;
    case SpeedSource::kConfiguration:
    case SpeedSource::kEstimated: return gearpath_SPEED_OTHER;
    case SpeedSource::kUnknown: break;
  }
  return gearpath_SPEED_UNKNOWN;
}

namespace {

// Both wire block types share every field but AccelBlockV2's load.
template <typename Wire>
Status FillCommonFields(const AccelBlockView& block, Wire& out) noexcept {
  if (!SetString(out.machine_id, block.machine_id)) {
    return Error{"machine_id '" + std::string(block.machine_id) + "' is longer than " +
                 std::to_string(gearpath_ID_LENGTH) + " characters"};
  }
  if (block.channels.size() > gearpath_MAX_CHANNELS) {
    return Error{std::to_string(block.channels.size()) + " channels exceed the IDL bound of " +
                 std::to_string(gearpath_MAX_CHANNELS)};
  }
  if (block.samples_per_channel > gearpath_MAX_SAMPLES_PER_CHANNEL) {
    return Error{"samples_per_channel " + std::to_string(block.samples_per_channel) +
                 " exceeds the IDL bound of " + std::to_string(gearpath_MAX_SAMPLES_PER_CHANNEL)};
  }
  if (block.samples.size() != block.channels.size() * block.samples_per_channel) {
    return Error{"samples holds " + std::to_string(block.samples.size()) + " values, expected " +
                 std::to_string(block.channels.size()) + " channels x " +
                 std::to_string(block.samples_per_channel)};
  }
  if (block.samples.size() > gearpath_MAX_BLOCK_SAMPLES) {
    return Error{std::to_string(block.samples.size()) + " samples exceed the IDL bound of " +
                 std::to_string(gearpath_MAX_BLOCK_SAMPLES)};
  }
  out.sequence_number = block.sequence;
  out.t0_ns = block.t0_ns;
  out.sample_rate_hz = block.sample_rate_hz;
  out.speed_hz = block.speed_hz;
  out.speed_source = WireSpeedSource(block.speed_source);
  out.samples_per_channel = block.samples_per_channel;
  if (!Resize(out.channels, static_cast<std::uint32_t>(block.channels.size()))) {
    return Error{"out of memory for the channel descriptions"};
  }
  auto wire_channels = MutableView(out.channels);
  for (std::size_t c = 0; c < block.channels.size(); ++c) {
    const ChannelInfo& in = block.channels[c];
    if (!SetString(wire_channels[c].sensor_id, in.sensor)) {
      return Error{"channels[" + std::to_string(c) + "].sensor '" + in.sensor +
                   "' does not fit the IDL bound"};
    }
    if (!SetString(wire_channels[c].unit, in.unit)) {
      return Error{"channels[" + std::to_string(c) + "].unit '" + in.unit +
                   "' does not fit the IDL bound"};
    }
    wire_channels[c].axis = WireAxis(in.axis);
    wire_channels[c].sensitivity_mv_per_unit = in.sensitivity;
  }
  if (!Assign(out.samples, block.samples)) return Error{"out of memory for the samples"};
  return Status::Ok();
}

template <typename Wire>
AccelBlockView ViewOfCommonFields(const Wire& sample, std::vector<ChannelInfo>& channels) {
  const auto wire = View(sample.channels);
  channels.resize(wire.size());
  for (std::size_t c = 0; c < wire.size(); ++c) {
    channels[c].sensor.assign(GetString(wire[c].sensor_id));
    channels[c].axis = CoreAxis(wire[c].axis);
    channels[c].unit.assign(GetString(wire[c].unit));
    channels[c].sensitivity = wire[c].sensitivity_mv_per_unit;
  }
  AccelBlockView view;
  view.machine_id = GetString(sample.machine_id);
  view.sequence = sample.sequence_number;
  view.t0_ns = sample.t0_ns;
  view.sample_rate_hz = sample.sample_rate_hz;
  view.speed_hz = sample.speed_hz;
  view.speed_source = CoreSpeedSource(sample.speed_source);
  view.channels = channels;
  view.samples_per_channel = sample.samples_per_channel;
  view.samples = View(sample.samples);
  return view;
}

}  // namespace

Status FillWireBlock(const AccelBlockView& block, gearpath_AccelBlock& out) noexcept {
  return FillCommonFields(block, out);
}

Status FillWireBlock(const AccelBlockView& block, std::string_view load_unit,
                     gearpath_AccelBlockV2& out) noexcept {
  if (!SetString(out.load_unit, load_unit)) {
    return Error{"load_unit '" + std::string(load_unit) + "' is longer than 16 characters"};
  }
  out.load = block.load;
  return FillCommonFields(block, out);
}

AccelBlockView ViewOfWireBlock(const gearpath_AccelBlock& sample,
                               std::vector<ChannelInfo>& channels) {
  return ViewOfCommonFields(sample, channels);
}

AccelBlockView ViewOfWireBlock(const gearpath_AccelBlockV2& sample,
                               std::vector<ChannelInfo>& channels) {
  AccelBlockView view = ViewOfCommonFields(sample, channels);
  view.load = sample.load;
  return view;
}

}  // namespace gearpath::dds
