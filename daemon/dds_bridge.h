// DDS bridge: between the wire types of idl/gearpath.idl and the pipeline's core types.
//
// The daemon's translation of results: a BlockResult becomes the four result samples (blocks
// come in through dds::ViewOfWireBlock, a view over the sample's own float buffer). Result
// samples are filled in place so that their sequence buffers are reused block after block.
// Identifiers longer than the IDL bound are truncated rather than refused (the configuration
// already bounds every id it defines; FRF path names come from files).
// Mapping choices that the IDL leaves open (enumerations that differ between core and wire)
// are documented at each function.
#pragma once

#include <cstdint>
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

// Criterion: band_energy -> CRITERION_BAND_ENERGY, sideband_energy ->
// CRITERION_SIDEBAND_ENERGY, indicator -> CRITERION_INDICATOR; each path's criterion value is
// BlockPathShare::criterion.
void FillDominantPath(std::string_view machine_id, const BlockResult& result,
                      gearpath_DominantPath& out) noexcept;

// State: learning -> LEARNING, no fault -> NO_FAULT (gear_name empty in both), suspected ->
// SUSPECTED, alarm -> ALARM.
void FillSuspectedGear(std::string_view machine_id, const BlockResult& result,
                       gearpath_SuspectedGear& out) noexcept;

// Band: the kurtogram band of the reconstructed (dominant-path) signal, the one the
// reconstructed indicators come from. Speed source: acquisition -> TACHOMETER, configuration
// and estimate -> OTHER.
void FillEnvelopeIndicators(std::string_view machine_id, const BlockResult& result,
                            gearpath_EnvelopeIndicators& out) noexcept;

// What FillConditionIndicators left out because of the IDL bounds (0 on every machine within
// them; docs/topics.md gives the bounds).
struct OmittedIndicators {
  std::uint32_t sets = 0;    // whole sets beyond MAX_INDICATOR_SETS
  std::uint32_t values = 0;  // values beyond MAX_INDICATORS_PER_SET in the published sets
  std::uint32_t names = 0;   // indicator names cut to INDICATOR_NAME_LENGTH characters
  bool any() const noexcept { return sets > 0 || values > 0 || names > 0; }
};

// Names of the entries of each shaft-rate group's indicator vector, by group
// (BlockProcessor::ConditionIndicatorNames(g) for g = 0, 1, ... while non-empty).
using IndicatorNamesByGroup = std::vector<std::span<const std::string>>;
IndicatorNamesByGroup IndicatorNamesOf(const BlockProcessor& processor);

// Every indicator set of the block and its score. BlockResult::condition is signal-major over
// the rate groups and does not store a set's group: set i belongs to group i % groups, groups
// = group_names.size() (== condition.size() / number of signals). Sets and values beyond the
// IDL bounds are left out and counted (in the sample's sets_omitted / values_omitted and in
// the return value); nothing is refused.
OmittedIndicators FillConditionIndicators(std::string_view machine_id, const BlockResult& result,
                                          const IndicatorNamesByGroup& group_names,
                                          gearpath_ConditionIndicators& out) noexcept;

struct StatusFigures {
  std::string_view daemon_id;
  gearpath_DaemonState state = gearpath_RUNNING;
  std::int64_t timestamp_ns = 0;
  double uptime_s = 0.0;
};

// One MachineStatus per configured machine, in `machine_ids` order, for the first
// MAX_MACHINES (64) machines only: the wire type's bound, which a published type cannot change
// (docs/topics.md); MachineHealth reports every machine. last_rejection_reason is
// "<reason>: <message>", the reason being the stable snake_case name (e.g. "non_finite").
void FillStatus(const StatusFigures& figures, std::span<const std::string> machine_ids,
                const std::map<std::string, MachineCounters, std::less<>>& counters,
                gearpath_Status& out) noexcept;

// What MachineHealth says of the daemon beside the machine's own counters.
struct MachineHealthFigures {
  std::string_view daemon_id;
  gearpath_DaemonState state = gearpath_RUNNING;
  std::int64_t timestamp_ns = 0;
  std::uint32_t machine_count = 0;  // machines the daemon serves
  bool publishing_results = true;   // false: a hot standby withholding results
};

// One machine's MachineHealth sample (machine `index` of the configuration, 0-based).
// last_rejection_reason is as on Status.
void FillMachineHealth(const MachineHealthFigures& figures, std::string_view machine_id,
                       std::uint32_t index, const MachineCounters& counters,
                       gearpath_MachineHealth& out) noexcept;

// Copies `text` into a bounded IDL string, truncating if it does not fit; true if it fitted.
template <std::size_t N>
bool CopyTruncated(char (&dst)[N], std::string_view text) noexcept {
  const std::size_t n = text.size() < N ? text.size() : N - 1;
  for (std::size_t i = 0; i < n; ++i) dst[i] = text[i];
  dst[n] = '\0';
  return n == text.size();
}

}  // namespace gearpath::daemon
