#include "daemon/gearpathd_metrics.h"

#include <set>

#include "core/diagnosis/gear_verdict.h"
#include "core/pipeline/block_validation.h"
#include "daemon/latency_histogram.h"
#include "daemon/metrics_exposition.h"

namespace gearpath::daemon {
namespace {

constexpr FaultState kFaultStates[] = {FaultState::kLearning, FaultState::kNoFault,
                                       FaultState::kSuspected, FaultState::kAlarm};
// Rejections counted by the daemon rather than by the block validation (gearpathd.cc).
constexpr std::string_view kQueueFull = "queue_full";

// Every reason a block can be rejected for, so that each machine's series exist from the
// start at 0 (a counter that appears with its first increment hides that increment from
// rate()). Reasons found in the counters only (a saved state of another version) are added.
// kImplausibleLoad is the last RejectReason: a reason added after it must extend this loop.
std::set<std::string, std::less<>> RejectReasons(const DaemonMetrics& m) {
  std::set<std::string, std::less<>> reasons;
  for (auto r = static_cast<int>(RejectReason::kNone) + 1;
       r <= static_cast<int>(RejectReason::kImplausibleLoad); ++r) {
    reasons.emplace(ToString(static_cast<RejectReason>(r)));
  }
  reasons.emplace(kQueueFull);
  for (const auto& machine : m.machines) {
    for (const auto& [reason, n] : machine.counters.rejected_by_reason) reasons.insert(reason);
  }
  return reasons;
}

void DaemonFamilies(const DaemonMetrics& m, ExpositionWriter& w) {
  w.Family("gearpath_build_info", "The gearpathd version; the value is always 1.",
           MetricType::kGauge);
  w.Sample("gearpath_build_info", {{"version", m.version}, {"daemon", m.daemon_id}}, 1.0);
  w.Family("gearpath_daemon_uptime_seconds", "Seconds since gearpathd started.",
           MetricType::kGauge);
  w.Sample("gearpath_daemon_uptime_seconds", {}, m.uptime_s);
  w.Family("gearpath_daemon_state", "The daemon's state (as on Status): 1 for the current one.",
           MetricType::kGauge);
  for (std::string_view s : kDaemonStateNames) {
    w.Sample("gearpath_daemon_state", {{"state", s}}, s == m.state ? 1.0 : 0.0);
  }
  w.Family("gearpath_daemon_publishing_results",
           "1 while results are published; 0 while a hot standby withholds them.",
           MetricType::kGauge);
  w.Sample("gearpath_daemon_publishing_results", {}, m.publishing_results ? 1.0 : 0.0);
  w.Family("gearpath_machines", "Machines in the configuration in force.", MetricType::kGauge);
  w.Sample("gearpath_machines", {}, static_cast<std::uint64_t>(m.machines.size()));
  w.Family("gearpath_foreign_blocks_total",
           "Blocks of machines not in this daemon's configuration, ignored.",
           MetricType::kCounter);
  w.Sample("gearpath_foreign_blocks_total", {}, m.foreign_blocks);
  w.Family("gearpath_publish_failures_total", "DDS writes of results, Status or MachineHealth "
           "that failed.", MetricType::kCounter);
  w.Sample("gearpath_publish_failures_total", {}, m.publish_failures);
  w.Family("gearpath_results_withheld_total",
           "Blocks processed by a hot standby whose results it did not publish.",
           MetricType::kCounter);
  w.Sample("gearpath_results_withheld_total", {}, m.results_withheld);
  w.Family("gearpath_state_save_failures_total", "Machine state files that could not be written.",
           MetricType::kCounter);
  w.Sample("gearpath_state_save_failures_total", {}, m.state_save_failures);
}

void CounterFamilies(const DaemonMetrics& m, ExpositionWriter& w) {
  w.Family("gearpath_blocks_received_total", "Blocks of the machine taken from DDS.",
           MetricType::kCounter);
  for (const auto& x : m.machines) {
    w.Sample("gearpath_blocks_received_total", {{"machine", x.id}}, x.counters.received);
  }
  w.Family("gearpath_blocks_processed_total", "Blocks of the machine that produced results.",
           MetricType::kCounter);
  for (const auto& x : m.machines) {
    w.Sample("gearpath_blocks_processed_total", {{"machine", x.id}}, x.counters.processed);
  }
  w.Family("gearpath_blocks_rejected_total",
           "Blocks of the machine rejected, by reason (docs/diagnosis.md section 1; "
           "queue_full: dropped at stop while its queue was full).",
           MetricType::kCounter);
  const auto reasons = RejectReasons(m);
  for (const auto& x : m.machines) {
    for (const std::string& reason : reasons) {
      const auto it = x.counters.rejected_by_reason.find(reason);
      const std::uint64_t n = it == x.counters.rejected_by_reason.end() ? 0 : it->second;
      w.Sample("gearpath_blocks_rejected_total", {{"machine", x.id}, {"reason", reason}}, n);
    }
  }
  w.Family("gearpath_blocks_not_judged_total",
           "Accepted blocks that the machine, past learning, did not judge (its state held), "
           "by cause: speed_unknown, speed_outside or load_outside the ranges its baseline "
           "learned at (docs/diagnosis.md section 10).",
           MetricType::kCounter);
  for (const auto& x : m.machines) {
    for (std::size_t i = 1; i < x.counters.not_judged.size(); ++i) {
      w.Sample("gearpath_blocks_not_judged_total",
               {{"machine", x.id}, {"cause", ToString(static_cast<NotJudgedCause>(i))}},
               x.counters.not_judged[i]);
    }
  }
  w.Family("gearpath_blocks_lost_total",
           "Blocks missing from the machine's sequence numbers that no rejection explains "
           "(lost upstream or in transit).",
           MetricType::kCounter);
  for (const auto& x : m.machines) {
    w.Sample("gearpath_blocks_lost_total", {{"machine", x.id}}, x.counters.lost);
  }
  w.Family("gearpath_block_latency_seconds",
           "From a block taken from the DDS reader to its results written, seconds.",
           MetricType::kHistogram);
  for (const auto& x : m.machines) {
    const LatencyHistogram& h = x.counters.latency;
    w.Histogram("gearpath_block_latency_seconds", {{"machine", x.id}}, kLatencyBucketBounds,
                h.per_bucket, h.sum_s);
  }
}

void StateFamilies(const DaemonMetrics& m, ExpositionWriter& w) {
  w.Family("gearpath_machine_state",
           "The machine's verdict state: 1 for the current one (learning, no_fault, "
           "suspected, alarm).",
           MetricType::kGauge);
  for (const auto& x : m.machines) {
    for (FaultState s : kFaultStates) {
      w.Sample("gearpath_machine_state", {{"machine", x.id}, {"state", ToString(s)}},
               x.counters.fault_state == s ? 1.0 : 0.0);
    }
  }
  w.Family("gearpath_machine_baseline_epoch",
           "The machine's analysis.baseline.epoch in force (empty when none is set); the "
           "value is always 1. A new epoch on a reload makes the machine learn a new baseline.",
           MetricType::kGauge);
  for (const auto& x : m.machines) {
    w.Sample("gearpath_machine_baseline_epoch", {{"machine", x.id}, {"epoch", x.baseline_epoch}},
             1.0);
  }
  w.Family("gearpath_machine_last_block_sequence",
           "Sequence number of the machine's last accepted block.", MetricType::kGauge);
  for (const auto& x : m.machines) {
    w.Sample("gearpath_machine_last_block_sequence", {{"machine", x.id}},
             x.counters.last_sequence);
  }
  w.Family("gearpath_machine_last_block_timestamp_seconds",
           "Acquisition time (t0) of the machine's last accepted block, Unix seconds; 0 "
           "before the first.",
           MetricType::kGauge);
  for (const auto& x : m.machines) {
    w.Sample("gearpath_machine_last_block_timestamp_seconds", {{"machine", x.id}},
             static_cast<double>(x.counters.last_t0_ns) * 1e-9);
  }
}

// The last accepted block's figures; a machine without one since start has none of these.
void IndicatorFamilies(const DaemonMetrics& m, ExpositionWriter& w) {
  struct Scalar {
    const char* name;
    const char* help;
    double (*value)(const MachineCounters&);
  };
  static constexpr Scalar kScalars[] = {
      {"gearpath_machine_score",
       "The last block's anomaly score: its largest indicator z over the limit z (1 = at "
       "the limit; 0 while learning).",
       [](const MachineCounters& c) { return c.latest.score; }},
      {"gearpath_machine_score_limit_z", "The z limit in force (0 while learning).",
       [](const MachineCounters& c) { return c.latest.limit_z; }},
      {"gearpath_machine_alarm_window_exceedances",
       "Blocks over the limit in the alarm window after the last block.",
       [](const MachineCounters& c) { return static_cast<double>(c.latest.exceed_count); }},
      {"gearpath_machine_baseline_blocks_learned", "Healthy baseline blocks learned.",
       [](const MachineCounters& c) {
         return static_cast<double>(c.latest.baseline_blocks_learned);
       }},
      {"gearpath_machine_baseline_blocks_needed", "Healthy baseline blocks needed.",
       [](const MachineCounters& c) {
         return static_cast<double>(c.latest.baseline_blocks_needed);
       }},
      {"gearpath_machine_speed_hz", "Input-shaft speed used for the last block, Hz.",
       [](const MachineCounters& c) { return c.latest.speed_hz; }},
      {"gearpath_machine_regularisation_alpha",
       "Median regularisation parameter of the last block's force identification.",
       [](const MachineCounters& c) { return c.last_alpha; }},
      {"gearpath_machine_condition_number",
       "Largest condition number of the inverted FRF operator, last block.",
       [](const MachineCounters& c) { return c.last_condition; }},
      {"gearpath_machine_relative_residual",
       "Relative residual ||x - H F|| / ||x|| of the last block's identification.",
       [](const MachineCounters& c) { return c.last_residual; }},
  };
  for (const Scalar& s : kScalars) {
    w.Family(s.name, s.help, MetricType::kGauge);
    for (const auto& x : m.machines) {
      if (x.counters.latest.valid) w.Sample(s.name, {{"machine", x.id}}, s.value(x.counters));
    }
  }
  w.Family("gearpath_machine_dominant_path_share",
           "Band-energy share [0, 1] of the last block's dominant transfer path (one series "
           "per machine, labelled with the path).",
           MetricType::kGauge);
  for (const auto& x : m.machines) {
    const LatestIndicators& l = x.counters.latest;
    if (!l.valid) continue;
    w.Sample("gearpath_machine_dominant_path_share",
             {{"machine", x.id}, {"path", l.dominant_path.view()}}, l.dominant_path_share);
  }
  // The envelope indicators and their thresholds: one series per shaft and signal each.
  const auto per_shaft = [&](const char* name, const char* help,
                             double LatestShaftIndicators::*raw,
                             double LatestShaftIndicators::*reconstructed) {
    w.Family(name, help, MetricType::kGauge);
    for (const auto& x : m.machines) {
      const LatestIndicators& l = x.counters.latest;
      if (!l.valid) continue;
      for (std::size_t i = 0; i < l.shaft_count; ++i) {
        const LatestShaftIndicators& sh = l.shafts[i];
        w.Sample(name, {{"machine", x.id}, {"shaft", sh.shaft.view()}, {"signal", "raw"}},
                 sh.*raw);
        w.Sample(name,
                 {{"machine", x.id}, {"shaft", sh.shaft.view()}, {"signal", "reconstructed"}},
                 sh.*reconstructed);
      }
    }
  };
  per_shaft("gearpath_machine_envelope_indicator",
            "The last block's envelope fault indicator per shaft (sum of five SES harmonic "
            "amplitudes) of the measured (raw) and the dominant-path (reconstructed) signal.",
            &LatestShaftIndicators::raw, &LatestShaftIndicators::reconstructed);
  per_shaft("gearpath_machine_envelope_threshold",
            "The threshold each envelope indicator is judged against (0 while learning).",
            &LatestShaftIndicators::raw_threshold,
            &LatestShaftIndicators::reconstructed_threshold);
}

}  // namespace

std::string RenderMetrics(const DaemonMetrics& metrics) {
  std::string out;
  out.reserve(4096 + 6000 * metrics.machines.size());
  ExpositionWriter w(out);
  DaemonFamilies(metrics, w);
  CounterFamilies(metrics, w);
  StateFamilies(metrics, w);
  IndicatorFamilies(metrics, w);
  return out;
}

}  // namespace gearpath::daemon
