// Error reporting for the DDS layer: every dds_* return code is checked, and a failure says
// which call failed, on what, and Cyclone's own wording (dds_strretcode).
//
// Constructors (configuration time) throw std::runtime_error; the per-block read/write path
// returns a gearpath::Status / Result instead, so a daemon worker never unwinds on data.
#pragma once

#include <dds/dds.h>

#include <string>
#include <string_view>

namespace gearpath::dds {

// "<call> failed: <dds_strretcode(rc)> (<rc>)", e.g.
// "dds_create_topic(\"gearpath/AccelBlock\") failed: Bad Parameter (-3)".
std::string DdsErrorMessage(std::string_view call, dds_return_t rc);

// Throws std::runtime_error(DdsErrorMessage(call, rc)) if rc < 0; returns rc otherwise.
// Entity handles are positive and error codes negative, so this also checks dds_create_*.
dds_return_t CheckDds(dds_return_t rc, std::string_view call);

}  // namespace gearpath::dds
