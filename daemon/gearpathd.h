// Gearpathd: the daemon's lifecycle - DDS endpoints, the reader, the worker pool, status,
// reload, stop.
//
// Threads (no work in Cyclone listeners, none in signal handlers):
//  - the lifecycle thread (the caller of Run, normally main): reads SIGTERM/SIGINT/SIGHUP from a
//    signalfd; on SIGHUP it re-reads the configuration and rebuilds every machine (FRF sets,
//    processors) itself, off the processing threads, and hands the result over; on SIGTERM it
//    asks the reader to stop and joins it.
//  - the reader thread: one WaitSet with the AccelBlock ReadCondition and a GuardCondition
//    (stop / reload handover). It takes one block at a time and queues it on its machine's
//    lane (daemon/lane_pool.h); when that lane is full it waits for room rather than drop, so
//    DDS flow control slows the writers. It publishes Status and MachineHealth when due (the
//    WaitSet timeout is the status timer), also while it waits.
//  - the workers (`daemon.workers`, 0 = one per hardware thread): each takes the next machine
//    with queued blocks, processes its blocks in order and publishes the results. One machine
//    is never on two workers at once (sequence tracking and baseline learning need its blocks
//    in order); different machines run in parallel. Block buffers circulate between the reader
//    and the workers, so nothing is allocated per block once warm.
// A stop request is seen between two blocks, so the blocks in hand are finished and published.
//
//  - the metrics thread (metrics.enabled; libmicrohttpd's, daemon/metrics_server.h): on each
//    scrape it copies every lane's counters under that lane's counters_mutex, as Status does;
//    the workers do nothing for it beyond a histogram bucket and a few figures of the last
//    block, written with their other counters. The lifecycle thread starts it, and restarts
//    it on a reload that changes `metrics`.
//
// systemd: READY=1 once the DDS endpoints exist and every machine is built; RELOADING=1 /
// READY=1 around a reload; STOPPING=1 on stop; STATUS= lines; WATCHDOG=1 from the reader
// loop on every iteration - also when idle. The watchdog proves the loop is alive (not wedged
// in a block or in DDS); it does not require blocks to flow, since a machine at standstill is
// not a daemon failure (missing blocks are visible on Status as received counts that stop).
#pragma once

#include <memory>
#include <string>

#include "core/common/result.h"
#include "daemon/daemon_config.h"
#include "daemon/machine_runtime.h"
#include "daemon/signal_events.h"

namespace gearpath::daemon {

struct DaemonOptions {
  std::string config_path;         // re-read on SIGHUP; empty: the embedded default
  std::string log_level_override;  // --log-level; empty: the configuration's
  std::string version;             // GEARPATH_VERSION, for the metrics' build info
};

class Gearpathd {
 public:
  // Creates the DDS endpoints for `config` and takes over its built machines (BuildMachines).
  // Errors name the DDS call that failed.
  static Result<std::unique_ptr<Gearpathd>> Create(DaemonConfig config, MachineSet machines,
                                                   DaemonOptions options);
  ~Gearpathd();

  // Runs until SIGTERM/SIGINT; returns the process exit code (0 after a clean stop).
  int Run(const SignalEvents& signals);

 private:
  struct Impl;
  explicit Gearpathd(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

// Applies a spdlog level name ("info", "warn", ...); false if unknown.
bool ApplyLogLevel(const std::string& level);

}  // namespace gearpath::daemon
