// MachineRuntime: one configured machine, ready to process blocks; and its counters.
//
// BuildMachines turns a validated DaemonConfig into one BlockProcessor per machine (FRF set
// loaded, everything that depends only on the FRFs precomputed, and every block length of
// acquisition.prepare_samples_per_channel configured, machines in parallel; any other length
// is configured by its first block), all or nothing: a reload that fails for one machine
// changes none. It runs before READY=1 and, on reload, on the lifecycle thread before the swap. MachineCounters live apart from the processors so that they survive a reload (Status
// keeps counting across SIGHUP).
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "core/common/result.h"
#include "core/pipeline/block_processor.h"
#include "core/pipeline/block_scratch.h"
#include "daemon/daemon_config.h"
#include "daemon/frf_registry.h"
#include "daemon/latency_histogram.h"
#include "daemon/latest_indicators.h"

namespace gearpath::daemon {

struct MachineRuntime {
  std::string id;
  std::string summary;  // one line for the start-up log: FRF shape, band, paths, method
  BlockProcessor processor;
  BlockResult result;   // reused block after block (allocation-free once sized)
  // acquisition.prepare_samples_per_channel: the lengths configured at build, for which every
  // worker's scratch is readied too (PrepareWorkerScratch).
  std::vector<std::uint32_t> prepared_samples;
  // Names of each shaft-rate group's condition indicators (views into `processor`, whose
  // Impl does not move), for the ConditionIndicators topic.
  std::vector<std::span<const std::string>> indicator_names;
};

// Everything one configuration needs to run: machines by id, and the registry their FRF sets
// came from (a reload builds from the same one, so unchanged sets stay shared).
struct MachineSet {
  std::map<std::string, std::unique_ptr<MachineRuntime>, std::less<>> machines;
  std::shared_ptr<FrfRegistry> frf_registry;
};

// Loads every distinct FRF set once (machines on one set share it and its operators,
// frf_registry.h), builds and prepares every processor (in parallel). Errors name the
// machine's key. Without a registry a new one is made.
Result<MachineSet> BuildMachines(const DaemonConfig& config,
                                 std::shared_ptr<FrfRegistry> registry = nullptr);

// Readies each of `scratch` (one per worker thread) for every machine of `set` at each of its
// prepared lengths (BlockProcessor::Prepare(n, scratch)): a machine's first block then
// allocates nothing on whichever worker runs it. Machines of one shape share one area per
// scratch. The scratch objects must not be in use meanwhile. Errors name the machine.
Status PrepareWorkerScratch(MachineSet& set, std::span<BlockScratch> scratch);

struct MachineCounters {
  std::uint64_t received = 0;
  std::uint64_t processed = 0;
  std::uint64_t rejected = 0;
  std::uint64_t lost = 0;           // blocks missing from the sequence: gaps that rejected
                                    // blocks do not explain (lost upstream or in transit)
  std::uint64_t rejected_in_gap = 0;  // rejected blocks numbered after the last accepted one
  std::map<std::string, std::uint64_t, std::less<>> rejected_by_reason;
  std::string last_rejection;       // "<reason>: <message>" of the last rejection
  // Accepted blocks that a learned machine did not judge, by NotJudgedCause (index 0 unused):
  // the speed unknown, or outside the speeds or loads the baseline learned at.
  std::array<std::uint64_t, static_cast<std::size_t>(kLastNotJudgedCause) + 1> not_judged{};
  double last_alpha = 0.0;
  double last_condition = 0.0;
  double last_residual = 0.0;
  double latency_last_ms = 0.0;
  double latency_max_ms = 0.0;
  // For the metrics endpoint (not saved): block taken -> results written, and the last
  // accepted block's figures. Updated with the counters above, under the same lock.
  LatencyHistogram latency;
  LatestIndicators latest;
  // The last accepted block and its verdict state, for MachineHealth (not saved: the state
  // is restored from the saved alarm model, the block comes again).
  FaultState fault_state = FaultState::kLearning;
  std::uint64_t last_sequence = 0;
  std::int64_t last_t0_ns = 0;
  // Condition indicators left off the wire by the IDL bounds (docs/topics.md): sets, values
  // and truncated names, summed over blocks; warned about once per machine.
  std::uint64_t indicators_omitted = 0;
  // Rejection log lines: written this throughput period, and left out (rate limit) since start.
  std::uint64_t rejection_lines_this_period = 0;
  std::uint64_t rejection_lines_suppressed = 0;
};

}  // namespace gearpath::daemon
