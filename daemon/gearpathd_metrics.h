// gearpathd's metrics: the snapshot the HTTP thread takes and the catalogue of metric names
// it is rendered into (Prometheus text format, metrics_exposition.h). docs/deployment.md
// ("Metrics") lists every name, type, label and unit; keep the two in step.
//
// The snapshot is a copy of the counters the daemon keeps anyway for Status and MachineHealth
// (MachineCounters, under each lane's counters_mutex) and of its daemon-wide atomics, so
// nothing is counted twice and the processing path does no work for a scrape.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "daemon/machine_runtime.h"

namespace gearpath::daemon {

struct MachineMetrics {
  std::string id;
  std::string baseline_epoch;  // analysis.baseline.epoch in force ("" when none is set)
  MachineCounters counters;
};

struct DaemonMetrics {
  std::string daemon_id;
  std::string version;       // GEARPATH_VERSION of the gearpathd binary
  std::string state;         // "starting", "running", "reloading", "stopping", "degraded"
  double uptime_s = 0.0;
  bool publishing_results = true;  // false: a hot standby withholding results
  std::uint64_t foreign_blocks = 0;     // blocks of machines not in the configuration
  std::uint64_t publish_failures = 0;   // DDS writes that failed (results, Status, health)
  std::uint64_t results_withheld = 0;   // blocks whose results a standby did not publish
  std::uint64_t state_save_failures = 0;
  std::vector<MachineMetrics> machines;  // configuration order
};

// Every daemon state name, in the order gearpath_daemon_state lists them.
inline constexpr std::string_view kDaemonStateNames[] = {"starting", "running", "reloading",
                                                          "stopping", "degraded"};

// The exposition text of one scrape.
std::string RenderMetrics(const DaemonMetrics& metrics);

}  // namespace gearpath::daemon
