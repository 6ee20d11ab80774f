// Identity FRF set: monitoring a gearbox before its FRFs have been measured (issue 8 item 7).
//
// Until the hammer test is done there is no decoupled FRF matrix, yet the condition
// indicators, the healthy baseline and the alarm model need nothing but the measured signals.
// MakeIdentityFrfSet makes every sensor channel its own transfer path: path "<sensor>/<axis>"
// with decoupled H = I (channels x channels) at every frequency, decoupling "identity". The
// identified "forces" and the path contributions then equal the measured responses (up to the
// regulariser's filter factor on a unit singular value), so every stage of the pipeline runs
// unchanged; localisation by mesh relies on which gears each sensor sits near
// (`gears_per_channel`), as the FRF set's path gears do for a measured set.
//
// Because H does not depend on frequency, any grid that spans the blocks' bins gives the exact
// H after the pipeline's linear interpolation: the caller may pass a coarse one.
#pragma once

#include <Eigen/Dense>
#include <string>
#include <vector>

#include "core/common/result.h"
#include "core/frf/frf_set.h"

namespace gearpath {

inline constexpr char kIdentityDecoupling[] = "identity";

// channels: the response channels (sensor id non-empty, axis "x", "y" or "z", no sensor/axis
// twice); gears_per_channel: for each channel, the gears nearest to that sensor (at least one,
// names non-empty and distinct); frequency_hz: the grid (at least one point, finite, >= 0,
// strictly increasing). Errors name the offending argument and index, e.g.
// `gears_per_channel[2]: no gear named (each sensor needs the gears it sits near)`.
Result<FrfSet> MakeIdentityFrfSet(const std::vector<ResponseChannel>& channels,
                                  const std::vector<std::vector<std::string>>& gears_per_channel,
                                  const Eigen::VectorXd& frequency_hz);

}  // namespace gearpath
