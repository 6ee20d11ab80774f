#include "daemon/dds_bridge.h"

#include <algorithm>

#include "idl/dds/accel_block_wire.h"
#include "idl/dds/sequence.h"

namespace gearpath::daemon {
namespace {

template <typename Seq>
std::uint32_t ResizeBounded(Seq& seq, std::size_t wanted, std::size_t bound) noexcept {
  const auto n = static_cast<std::uint32_t>(std::min(wanted, bound));
  if (!dds::Resize(seq, n)) {
    seq._length = 0;
    return 0;
  }
  return n;
}

}  // namespace

void FillDominantPath(std::string_view machine_id, const BlockResult& r,
                      gearpath_DominantPath& out) noexcept {
  CopyTruncated(out.machine_id, machine_id);
  out.block_sequence = r.sequence;
  out.block_t0_ns = r.t0_ns;
  out.path_index = r.dominant_path < 0 ? 0u : static_cast<std::uint32_t>(r.dominant_path);
  CopyTruncated(out.path_name, r.dominant_path_name);
  const std::uint32_t n = ResizeBounded(out.paths, r.paths.size(), gearpath_MAX_PATHS);
  auto paths = dds::MutableView(out.paths);
  for (std::uint32_t i = 0; i < n; ++i) {
    CopyTruncated(paths[i].name, r.paths[i].name);
    paths[i].share = r.paths[i].share;
    paths[i].criterion = r.paths[i].criterion;
  }
  out.band_lo_hz = r.analysis_band_lo_hz;
  out.band_hi_hz = r.analysis_band_hi_hz;
  switch (r.criterion) {
    case AnalysisOptions::DominantCriterion::kBandEnergy:
      out.criterion = gearpath_CRITERION_BAND_ENERGY;
      break;
    case AnalysisOptions::DominantCriterion::kSidebandEnergy:
      out.criterion = gearpath_CRITERION_SIDEBAND_ENERGY;
      break;
    case AnalysisOptions::DominantCriterion::kIndicator:
      out.criterion = gearpath_CRITERION_INDICATOR;
      break;
    default: out.criterion = gearpath_CRITERION_OTHER; break;
  }
}

namespace {

gearpath_FaultState WireFaultState(FaultState state) noexcept {
  switch (state) {
    case FaultState::kLearning: return gearpath_LEARNING;
    case FaultState::kSuspected: return gearpath_SUSPECTED;
    case FaultState::kAlarm: return gearpath_ALARM;
    default: return gearpath_NO_FAULT;
  }
}

}  // namespace

void FillSuspectedGear(std::string_view machine_id, const BlockResult& r,
                       gearpath_SuspectedGear& out) noexcept {
  const GearVerdict& v = r.verdict;
  CopyTruncated(out.machine_id, machine_id);
  out.block_sequence = r.sequence;
  out.block_t0_ns = r.t0_ns;
  out.state = WireFaultState(v.state);
  const bool named = out.state == gearpath_SUSPECTED || out.state == gearpath_ALARM;
  CopyTruncated(out.gear_name, named ? v.gear_name : std::string_view());
  CopyTruncated(out.shaft_name, named ? v.shaft_name : std::string_view());
  out.characteristic_frequency_hz = named ? v.characteristic_hz : 0.0;
  out.confidence = v.confidence;
  const std::size_t candidates = named && v.candidate_names.size() > 1 ? v.candidate_names.size()
                                                                        : 0;
  const std::uint32_t n = ResizeBounded(out.candidates, candidates, gearpath_MAX_CANDIDATES);
  auto names = dds::MutableView(out.candidates);
  for (std::uint32_t i = 0; i < n; ++i) CopyTruncated(names[i], v.candidate_names[i]);
  CopyTruncated(out.reason, v.reason.view());
}

void FillEnvelopeIndicators(std::string_view machine_id, const BlockResult& r,
                            gearpath_EnvelopeIndicators& out) noexcept {
  CopyTruncated(out.machine_id, machine_id);
  out.block_sequence = r.sequence;
  out.block_t0_ns = r.t0_ns;
  out.band.centre_hz = r.reconstructed_band.centre_hz;
  out.band.width_hz = r.reconstructed_band.width_hz;
  out.band.level = r.reconstructed_band.level;
  out.band.kurtosis = r.reconstructed_band.kurtosis;
  out.band.significant = r.reconstructed_band.significant;
  const std::uint32_t n = ResizeBounded(out.shafts, r.shafts.size(), gearpath_MAX_SHAFTS);
  auto shafts = dds::MutableView(out.shafts);
  for (std::uint32_t i = 0; i < n; ++i) {
    const BlockShaftIndicator& s = r.shafts[i];
    CopyTruncated(shafts[i].shaft_name, s.shaft);
    shafts[i].characteristic_frequency_hz = s.characteristic_hz;
    shafts[i].raw_indicator = s.raw;
    shafts[i].reconstructed_indicator = s.reconstructed;
    shafts[i].enhancement_percent = s.enhancement_percent;
    shafts[i].raw_threshold = s.raw_threshold;
    shafts[i].reconstructed_threshold = s.reconstructed_threshold;
    for (std::size_t h = 0; h < gearpath_HARMONICS && h < kIndicatorHarmonics; ++h) {
      shafts[i].raw_harmonics[h] = s.raw_harmonics[h];
      shafts[i].reconstructed_harmonics[h] = s.reconstructed_harmonics[h];
    }
  }
  out.speed_hz = r.speed_hz;
  out.speed_source = dds::WireSpeedSource(r.speed_source);
}

IndicatorNamesByGroup IndicatorNamesOf(const BlockProcessor& processor) {
  IndicatorNamesByGroup names;
  for (std::size_t g = 0;; ++g) {
    const std::span<const std::string> group = processor.ConditionIndicatorNames(g);
    if (group.empty()) break;
    names.push_back(group);
  }
  return names;
}

namespace {

gearpath_SignalSource WireSignalSource(ConditionSource source) noexcept {
  switch (source) {
    case ConditionSource::kContribution: return gearpath_SIGNAL_CONTRIBUTION;
    case ConditionSource::kForce: return gearpath_SIGNAL_FORCE;
    default: return gearpath_SIGNAL_MEASURED;
  }
}

std::uint32_t NonNegative(int v) noexcept { return v < 0 ? 0u : static_cast<std::uint32_t>(v); }

}  // namespace

OmittedIndicators FillConditionIndicators(std::string_view machine_id, const BlockResult& r,
                                          const IndicatorNamesByGroup& group_names,
                                          gearpath_ConditionIndicators& out) noexcept {
  OmittedIndicators omitted;
  CopyTruncated(out.machine_id, machine_id);
  out.block_sequence = r.sequence;
  out.block_t0_ns = r.t0_ns;
  const BlockScore& score = r.score;
  out.limit_z = score.limit_z;
  out.clear_level = score.clear_level;
  out.score = score.score;
  CopyTruncated(out.top_indicator, score.indicator);
  CopyTruncated(out.top_signal, score.signal);
  CopyTruncated(out.top_shaft, score.shaft);
  out.exceed_count = NonNegative(score.exceed_count);
  out.window = NonNegative(score.window);
  out.baseline_blocks_learned = NonNegative(score.baseline_blocks_learned);
  out.baseline_blocks_needed = NonNegative(score.baseline_blocks_needed);

  const std::uint32_t n = ResizeBounded(out.sets, r.condition.size(), gearpath_MAX_INDICATOR_SETS);
  omitted.sets = static_cast<std::uint32_t>(r.condition.size() - n);
  const std::size_t groups = group_names.size();
  auto sets = dds::MutableView(out.sets);
  for (std::uint32_t i = 0; i < n; ++i) {
    const BlockConditionIndicators& c = r.condition[i];
    gearpath_IndicatorSet& set = sets[i];
    set.source = WireSignalSource(c.source);
    CopyTruncated(set.signal, c.signal);
    CopyTruncated(set.shaft, c.shaft);
    set.shaft_hz = c.shaft_hz;
    set.revolutions = c.revolutions;
    set.score = c.score;
    // The set's group is not stored: sets are signal-major over the groups.
    const std::span<const std::string> names =
        groups > 0 ? group_names[i % groups] : std::span<const std::string>();
    const std::size_t count = std::min(c.value.size(), c.z.size());
    const std::uint32_t m = ResizeBounded(set.values, count, gearpath_MAX_INDICATORS_PER_SET);
    omitted.values += static_cast<std::uint32_t>(count - m);
    auto values = dds::MutableView(set.values);
    for (std::uint32_t k = 0; k < m; ++k) {
      const std::string_view name = k < names.size() ? std::string_view(names[k]) : "";
      if (!CopyTruncated(values[k].name, name)) ++omitted.names;
      values[k].value = c.value[k];
      values[k].z = c.z[k];
    }
  }
  out.sets_omitted = omitted.sets;
  out.values_omitted = omitted.values;
  return omitted;
}

namespace {

// The per-machine counters that Status (MachineStatus) and MachineHealth both carry: two wire
// types with the same field names, so one template fills either.
template <class WireCounters>
void FillCommonCounters(const MachineCounters& c, WireCounters& out) noexcept {
  out.blocks_received = c.received;
  out.blocks_processed = c.processed;
  out.blocks_rejected = c.rejected;
  CopyTruncated(out.last_rejection_reason, c.last_rejection);
  out.last_alpha = c.last_alpha;
  out.last_condition_number = c.last_condition;
  out.last_relative_residual = c.last_residual;
  out.latency_last_ms = c.latency_last_ms;
  out.latency_max_ms = c.latency_max_ms;
}

}  // namespace

void FillStatus(const StatusFigures& figures, std::span<const std::string> machine_ids,
                const std::map<std::string, MachineCounters, std::less<>>& counters,
                gearpath_Status& out) noexcept {
  CopyTruncated(out.daemon_id, figures.daemon_id);
  out.state = figures.state;
  out.timestamp_ns = figures.timestamp_ns;
  out.uptime_s = figures.uptime_s;
  const std::uint32_t n = ResizeBounded(out.machines, machine_ids.size(), gearpath_MAX_MACHINES);
  auto machines = dds::MutableView(out.machines);
  static const MachineCounters kNone;
  for (std::uint32_t i = 0; i < n; ++i) {
    const auto it = counters.find(machine_ids[i]);
    const MachineCounters& c = it == counters.end() ? kNone : it->second;
    gearpath_MachineStatus& m = machines[i];
    CopyTruncated(m.machine_id, machine_ids[i]);
    FillCommonCounters(c, m);
  }
}

void FillMachineHealth(const MachineHealthFigures& figures, std::string_view machine_id,
                       std::uint32_t index, const MachineCounters& c,
                       gearpath_MachineHealth& out) noexcept {
  CopyTruncated(out.daemon_id, figures.daemon_id);
  CopyTruncated(out.machine_id, machine_id);
  out.daemon_state = figures.state;
  out.timestamp_ns = figures.timestamp_ns;
  out.machine_index = index;
  out.machine_count = figures.machine_count;
  out.fault_state = WireFaultState(c.fault_state);
  out.publishing_results = figures.publishing_results;
  out.last_block_sequence = c.last_sequence;
  out.last_block_t0_ns = c.last_t0_ns;
  out.blocks_lost = c.lost;
  FillCommonCounters(c, out);
}

}  // namespace gearpath::daemon
