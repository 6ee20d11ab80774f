// DDS bridge: between the wire types of idl/gearpath.idl and the pipeline's core types.
//
// The daemon's translation of results: a BlockResult becomes the three result samples (blocks
// come in through dds::ViewOfWireBlock, a view over the sample's own float buffer). Result
// samples are filled in place so that their sequence buffers are reused block after block. Identifiers longer than the IDL bound are truncated rather than refused (the
// configuration already bounds every id it defines; FRF path names come from files).
// Mapping choices that the IDL leaves open (enumerations that differ between core and wire)
// are documented at each function.
#pragma once

#include <map>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "core/common/accel_block.h"
#include "core/pipeline/block_processor.h"
#include "daemon/machine_runtime.h"
#include "idl/gearpath.h"

namespace gearpath::daemon {

// Criterion: band_energy -> CRITERION_BAND_ENERGY; sideband_energy and indicator ->
// CRITERION_OTHER (documented in docs/configuration.md).
void FillDominantPath(std::string_view machine_id, const BlockResult& result,
                      gearpath_DominantPath& out) noexcept;

// State: learning and no fault -> NO_FAULT (gear_name empty, the reason says "learning ..."),
// suspected -> SUSPECTED, alarm -> ALARM.
void FillSuspectedGear(std::string_view machine_id, const BlockResult& result,
                       gearpath_SuspectedGear& out) noexcept;

// Band: the kurtogram band of the reconstructed (dominant-path) signal, the one the
// reconstructed indicators come from. Speed source: acquisition -> TACHOMETER, configuration
// and estimate -> OTHER.
void FillEnvelopeIndicators(std::string_view machine_id, const BlockResult& result,
                            gearpath_EnvelopeIndicators& out) noexcept;

struct StatusFigures {
  std::string_view daemon_id;
  gearpath_DaemonState state = gearpath_RUNNING;
  std::int64_t timestamp_ns = 0;
  double uptime_s = 0.0;
};

// One MachineStatus per configured machine, in `machine_ids` order. last_rejection_reason is
// "<reason>: <message>", the reason being the stable snake_case name (e.g. "non_finite").
void FillStatus(const StatusFigures& figures, std::span<const std::string> machine_ids,
                const std::map<std::string, MachineCounters, std::less<>>& counters,
                gearpath_Status& out) noexcept;

// Copies `text` into a bounded IDL string, truncating if it does not fit.
template <std::size_t N>
void CopyTruncated(char (&dst)[N], std::string_view text) noexcept {
  const std::size_t n = text.size() < N ? text.size() : N - 1;
  for (std::size_t i = 0; i < n; ++i) dst[i] = text[i];
  dst[n] = '\0';
}

}  // namespace gearpath::daemon
