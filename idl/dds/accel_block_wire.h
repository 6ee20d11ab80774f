// Filling the wire AccelBlock (idl/gearpath.idl) from core's AccelBlockView, for publishers
// (the simulator, replay). Status and errors name the field that does not fit the IDL bounds,
// so a publisher refuses a block the daemon could never receive instead of truncating it.
#pragma once

#include <string_view>
#include <vector>

#include "core/common/accel_block.h"
#include "core/common/result.h"
#include "idl/gearpath.h"

namespace gearpath::dds {

// Copies `block` into `out`, reusing out's sequence buffers (no allocation once they have
// grown). Fails, leaving `out` unspecified, when an id, unit or sequence exceeds its IDL bound
// or the samples do not match channels x samples_per_channel.
Status FillWireBlock(const AccelBlockView& block, gearpath_AccelBlock& out) noexcept;
// The same for AccelBlockV2, with the block's load (unit: `load_unit`, at most 16 characters).
Status FillWireBlock(const AccelBlockView& block, std::string_view load_unit,
                     gearpath_AccelBlockV2& out) noexcept;

// The inverse, for subscribers outside the daemon (`gearpath record`): a view of `sample`'s
// samples (no copy; valid while `sample` and `channels` live) with the channel descriptions
// decoded into `channels` (reused, so no allocation once it has grown). Speed sources map so
// that FillWireBlock(ViewOfWireBlock(w)) == w field for field: TACHOMETER <-> kAcquisition,
// OTHER <-> kConfiguration (a speed from outside the acquisition), UNKNOWN <-> kUnknown.
// The wire speed source for a core one: TACHOMETER for kAcquisition, OTHER for a speed from
// outside the acquisition (configuration, estimate), UNKNOWN otherwise.
gearpath_SpeedSource WireSpeedSource(SpeedSource source) noexcept;

AccelBlockView ViewOfWireBlock(const gearpath_AccelBlock& sample,
                               std::vector<ChannelInfo>& channels);
// The same for AccelBlockV2; the view carries its load.
AccelBlockView ViewOfWireBlock(const gearpath_AccelBlockV2& sample,
                               std::vector<ChannelInfo>& channels);

}  // namespace gearpath::dds
