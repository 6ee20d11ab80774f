#include "daemon/gearpathd.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <array>
#include <atomic>
#include <chrono>
#include <mutex>
#include <optional>
#include <span>
#include <stdexcept>
#include <thread>
#include <utility>

#include "daemon/dds_bridge.h"
#include "daemon/dds_setup.h"
#include "daemon/gearpathd_metrics.h"
#include "daemon/heap_trim.h"
#include "daemon/lane_pool.h"
#include "idl/dds/accel_block_wire.h"
#include "daemon/machine_id_filter.h"
#include "daemon/machine_runtime.h"
#include "daemon/machine_state_store.h"
#include "daemon/metrics_server.h"
#include "daemon/systemd_notify.h"
#include "idl/dds/gearpath_topics.h"

namespace gearpath::daemon {
namespace {

using Clock = std::chrono::steady_clock;
using std::chrono::duration;
using std::chrono::duration_cast;
using std::chrono::milliseconds;
using std::chrono::nanoseconds;

std::int64_t RealtimeNs() {
  return duration_cast<nanoseconds>(std::chrono::system_clock::now().time_since_epoch())
      .count();
}

Clock::duration Seconds(double s) { return duration_cast<Clock::duration>(duration<double>(s)); }

constexpr dds_attach_t kBlocksToken = 1;
constexpr dds_attach_t kGuardToken = 2;
constexpr dds_attach_t kBlocksV2Token = 3;
constexpr std::uint64_t kRejectionLinesPerPeriod = 10;
// How long the reader waits at a time for room in a full machine queue before it runs the
// housekeeping (Status, watchdog) and waits again.
constexpr std::chrono::milliseconds kRoomWait{100};

// A configuration and its built machines, handed from the lifecycle thread to the loop.
struct Generation {
  DaemonConfig config;
  MachineSet machines;
};

}  // namespace

bool ApplyLogLevel(const std::string& level) {
  const auto parsed = spdlog::level::from_str(level);
  if (parsed == spdlog::level::off && level != "off") return false;
  spdlog::set_level(parsed);
  return true;
}

// What the processing thread knows about a machine's saved state.
struct SaveMark {
  FaultState last_state = FaultState::kLearning;  // verdict state of the last accepted block
  bool dirty = false;                             // changed since the last save
  Clock::time_point dirty_since{};
  bool failing = false;                           // the last save failed (said once)
};

// One block taken from DDS, waiting for its machine's worker.
struct QueuedBlock {
  dds::Owned<gearpath_AccelBlock> sample;
  dds::Owned<gearpath_AccelBlockV2> sample_v2;  // the block, when it came with its load
  bool with_load = false;                       // sample_v2 holds it, not sample
  dds::SampleInfo info{};
  std::uint64_t dropped_before = 0;  // blocks of the machine dropped (queue full) just before
  Clock::time_point taken_at{};      // taken from the DDS reader (the latency histogram's start)
};
using BlockLanes = LanePool<QueuedBlock>;

// A machine as the worker pool sees it. The reader thread owns the map of lanes and changes
// `runtime` only while the pool is paused; a worker handles one block of a lane at a time.
struct MachineLane : BlockLanes::Lane {
  MachineLane(std::string machine_id, std::size_t capacity)
      : Lane(capacity), id(std::move(machine_id)) {}
  const std::string id;
  MachineRuntime* runtime = nullptr;
  std::uint64_t pending_drops = 0;  // reader thread: dropped since the last queued block
  std::mutex processor_mutex;       // held while the processor is used (a block, a save)
  SaveMark mark;                    // under processor_mutex
  std::mutex counters_mutex;        // the worker writes the counters, Status reads them
  MachineCounters counters;
};

// What a worker fills and publishes: its own, so workers share no sample and allocate nothing
// per block once the samples are sized.
struct WorkerScratch {
  // The processing scratch lent to whichever machine the worker runs (block_scratch.h).
  BlockScratch block;
  std::vector<ChannelInfo> channels;
  dds::Owned<gearpath_DominantPath> dominant;
  dds::Owned<gearpath_SuspectedGear> gear;
  dds::Owned<gearpath_EnvelopeIndicators> indicators;
  dds::Owned<gearpath_ConditionIndicators> condition;
};

std::size_t WorkerCount(const DaemonConfig& c) {
  if (c.workers > 0) return static_cast<std::size_t>(c.workers);
  return std::max(1u, std::thread::hardware_concurrency());
}

// The block reader's instance limit: every configured machine, with room for a reload to
// double them (a reload beyond it is refused: resource limits are fixed when the reader is
// created), and never below the profile's kMaxMachinesPerDomain. Only admitted machines'
// instances ever exist in the reader (MachineIdFilter), so the limit is a bound, not memory.
std::size_t BlockInstanceLimit(const DaemonConfig& c) {
  return std::max(static_cast<std::size_t>(dds::kMaxMachinesPerDomain), 2 * c.machines.size());
}

dds::Qos BlockReaderQos(std::size_t instances) {
  dds::Qos qos = dds::ReaderQos(dds::TopicClass::kBlockStream);
  const auto n = static_cast<std::int32_t>(instances);
  qos.ResourceLimits(dds::kBlockHistoryDepth * n, n, dds::kBlockHistoryDepth);
  return qos;
}

// The configured machines' ids, in configuration order.
std::vector<std::string> MachineIds(const DaemonConfig& c) {
  std::vector<std::string> ids;
  ids.reserve(c.machines.size());
  for (const auto& m : c.machines) ids.push_back(m.id);
  return ids;
}

// The block topic with the machine filter set, ready for the block reader. The configured
// machines are admitted before the reader exists: a publisher may write as soon as the reader
// matches, and a block that arrived while the start-up still prepared the machines (Adopt) was
// dropped as foreign (the demo's first healthy block, so its baseline took in a faulty one).
const dds::Topic<gearpath_AccelBlock>& FilteredByMachine(dds::Topic<gearpath_AccelBlock>& topic,
                                                         MachineIdFilter& filter,
                                                         const DaemonConfig& c) {
  filter.Admit(MachineIds(c));
  topic.SetSampleFilter(&MachineIdFilter::Accept, &filter);
  return topic;
}

struct Gearpathd::Impl {
  Impl(Generation first, DaemonOptions opts, std::optional<MachineStateStore> state_store)
      : options(std::move(opts)),
        store(std::move(state_store)),
        lifecycle_config(first.config),
        frf_registry(first.machines.frf_registry),
        domain(first.config.domain_id, DaemonDomainConfig(first.config)),
        participant(domain, DaemonSecurityFiles(first.config)),
        block_topic(participant, first.config.topics.accel_block),
        dominant_topic(participant, first.config.topics.dominant_path),
        gear_topic(participant, first.config.topics.suspected_gear),
        indicators_topic(participant, first.config.topics.envelope_indicators),
        condition_topic(participant, first.config.topics.condition_indicators),
        status_topic(participant, first.config.topics.status),
        health_topic(participant, first.config.topics.machine_health),
        block_instances(BlockInstanceLimit(first.config)),
        block_reader(FilteredByMachine(block_topic, machine_filter, first.config),
                     BlockReaderQos(block_instances)),
        status_reader(status_topic),
        dominant_writer(dominant_topic),
        gear_writer(gear_topic),
        indicators_writer(indicators_topic),
        condition_writer(condition_topic),
        status_writer(status_topic),
        health_writer(health_topic),
        blocks_ready(block_reader),
        guard(participant),
        waitset(participant),
        queue_capacity(static_cast<std::size_t>(first.config.queue_blocks)),
        workers(WorkerCount(first.config)),
        scratch(workers),
        // Spares: enough buffers for every worker's next block and a burst, not every queue.
        pool(std::make_unique<BlockLanes>(
            workers, 2 * workers + 2,
            [this](std::size_t w, BlockLanes::Lane& lane, QueuedBlock& block) {
              HandleBlock(scratch[w], static_cast<MachineLane&>(lane), block);
            })) {
    waitset.Attach(blocks_ready, kBlocksToken);
    if (const std::string& name = first.config.topics.accel_block_v2; !name.empty()) {
      block_v2_topic.emplace(participant, name);
      block_v2_topic->SetSampleFilter(&MachineIdFilter::AcceptV2, &machine_filter);
      block_v2_reader.emplace(*block_v2_topic, BlockReaderQos(block_instances));
      blocks_v2_ready.emplace(*block_v2_reader);
      waitset.Attach(*blocks_v2_ready, kBlocksV2Token);
      samples_v2.resize(1);
      infos_v2.resize(1);
    }
    waitset.Attach(guard, kGuardToken);
    spdlog::info("processing on {} worker thread(s), up to {} block(s) queued per machine",
                 workers, queue_capacity);
    Adopt(std::move(first));
    samples.resize(1);
    infos.resize(1);
    status_samples.resize(8);
    status_infos.resize(8);
  }

  // ---- lifecycle thread ----
  int Run(const SignalEvents& signals);
  void Reload();

  // ---- processing thread ----
  void Loop();
  void Adopt(Generation generation);
  void AdoptPending();
  void DrainBlocks();
  void Dispatch(bool with_load);
  void HandleBlock(WorkerScratch& ws, MachineLane& lane, QueuedBlock& block);
  void CountDrops(MachineLane& lane, std::uint64_t dropped, std::uint64_t before_sequence);
  void SnapshotCounters(bool new_period);
  void Housekeeping(bool force_status);
  void PublishStatus(gearpath_DaemonState state);
  void PublishHealth(gearpath_DaemonState state, std::int64_t timestamp_ns);
  void DisposeHealth(const std::string& of_daemon, std::span<const std::string> machine_ids);
  void LogThroughput();
  void Resume(MachineLane& lane, MachineSet& previous);
  void MarkChanged(MachineLane& lane, FaultState verdict_state);
  void SaveMachine(MachineLane& lane);
  void SaveDueMachines(bool all);
  void WatchPrimary();

  // ---- metrics thread ----
  DaemonMetrics CollectMetrics();
  // ---- lifecycle thread ----
  Status StartMetrics(const MetricsConfig& config);
  Status ChangeMetrics(const MetricsConfig& next, const MetricsConfig& previous);

  DaemonOptions options;
  std::optional<MachineStateStore> store;  // none: nothing is kept across restarts
  MachineIdFilter machine_filter;  // before the block reader, which it filters
  DaemonConfig lifecycle_config;  // the configuration in force, as the lifecycle thread knows it
  // Where reloads get their FRF sets: unchanged ones stay shared with the running machines.
  std::shared_ptr<FrfRegistry> frf_registry;
  const Clock::time_point started = Clock::now();

  dds::Domain domain;
  dds::Participant participant;
  dds::Topic<gearpath_AccelBlock> block_topic;
  dds::Topic<gearpath_DominantPath> dominant_topic;
  dds::Topic<gearpath_SuspectedGear> gear_topic;
  dds::Topic<gearpath_EnvelopeIndicators> indicators_topic;
  dds::Topic<gearpath_ConditionIndicators> condition_topic;
  dds::Topic<gearpath_Status> status_topic;
  dds::Topic<gearpath_MachineHealth> health_topic;
  const std::size_t block_instances;  // the block reader's instance limit (BlockInstanceLimit)
  dds::Reader<gearpath_AccelBlock> block_reader;
  dds::Reader<gearpath_Status> status_reader;  // a standby watches its primary's Status
  dds::Writer<gearpath_DominantPath> dominant_writer;
  dds::Writer<gearpath_SuspectedGear> gear_writer;
  dds::Writer<gearpath_EnvelopeIndicators> indicators_writer;
  dds::Writer<gearpath_ConditionIndicators> condition_writer;
  dds::Writer<gearpath_Status> status_writer;
  dds::Writer<gearpath_MachineHealth> health_writer;
  dds::ReadCondition blocks_ready;
  // The blocks with their load (AccelBlockV2), unless dds.topics.accel_block_v2 is empty.
  std::optional<dds::Topic<gearpath_AccelBlockV2>> block_v2_topic;
  std::optional<dds::Reader<gearpath_AccelBlockV2>> block_v2_reader;
  std::optional<dds::ReadCondition> blocks_v2_ready;
  dds::GuardCondition guard;
  dds::WaitSet waitset;

  // Shared between the threads.
  std::atomic<bool> stop_requested{false};
  std::atomic<bool> publishing{true};  // hot standby: results are published only while set
  std::atomic<std::uint64_t> results_withheld{0};
  std::atomic<std::uint64_t> publish_failures{0};
  std::atomic<std::uint64_t> state_save_failures{0};
  std::atomic<bool> loop_failed{false};
  std::atomic<int> state{gearpath_STARTING};
  // Blocks of machines not (or no longer) configured; the reader counts, Status and the
  // metrics read.
  std::atomic<std::uint64_t> foreign_blocks{0};
  // Held by the reader thread while it changes the lanes map, machine_ids or daemon_id (a
  // reload), and by the metrics thread while it reads them; the reader reads them without it.
  std::mutex metrics_view_mutex;
  std::mutex pending_mutex;
  std::optional<Generation> pending;

  // Processing thread only (after construction).
  MachineSet machines;
  std::vector<std::string> machine_ids;  // configuration order, for Status
  std::string daemon_id;
  Clock::duration status_period{};
  Clock::duration throughput_period{};
  Clock::duration watchdog_period{};  // half of systemd's WatchdogSec; zero: no watchdog
  // The lanes' counters as of the last Status or summary (SnapshotCounters).
  std::map<std::string, MachineCounters, std::less<>> counters;
  std::map<std::string, MachineCounters, std::less<>> counters_at_last_summary;
  Clock::duration save_period{};
  // Hot standby (`publishing` above); a primary always publishes.
  std::string primary_id;
  Clock::duration takeover_after{};
  Clock::time_point primary_last_seen{};
  Clock::time_point next_primary_check{};
  bool primary_seen = false;  // its Status has arrived at least once (logged once)
  std::vector<dds::Owned<gearpath_Status>> status_samples;
  std::vector<dds::SampleInfo> status_infos;
  std::uint64_t foreign_blocks_at_last_summary = 0;
  Clock::time_point next_status{};
  Clock::time_point next_throughput{};
  Clock::time_point next_watchdog{};
  Clock::time_point last_summary = Clock::now();
  HeapTrimmer heap_trimmer;  // freed heap back to the kernel every 30 s (heap_trim.h)
  std::vector<dds::Owned<gearpath_AccelBlock>> samples;
  std::vector<dds::Owned<gearpath_AccelBlockV2>> samples_v2;
  std::vector<dds::SampleInfo> infos;
  std::vector<dds::SampleInfo> infos_v2;
  // Taken and not yet dispatched (DrainBlocks): samples[0], samples_v2[0].
  bool held_block = false;
  bool held_block_v2 = false;
  QueuedBlock offered;  // the block being handed to its lane
  dds::Owned<gearpath_Status> status_sample;
  dds::Owned<gearpath_MachineHealth> health_sample;

  // The worker pool, last: its threads stop before anything they use goes.
  const std::size_t queue_capacity;  // daemon.queue_blocks at start-up
  const std::size_t workers;         // daemon.workers at start-up
  std::vector<WorkerScratch> scratch;  // one per worker
  std::map<std::string, std::unique_ptr<MachineLane>, std::less<>> lanes;  // reader thread
  std::unique_ptr<BlockLanes> pool;
  // Lifecycle thread. Last: it stops (and its thread with it) before anything it reads goes.
  std::unique_ptr<MetricsServer> metrics_server;
};

namespace {

// A machine given a new analysis.baseline.epoch (after maintenance) forgets on purpose. The
// learned state names the epoch it was learned under (from the previous generation, or from the
// saved file unless an earlier build saved it), so both paths tell it apart from a refusal the
// same way, and say it the same way. False when the epoch did not change (or is not recorded).
bool LogIfNewEpoch(const MachineRuntime& m, const LearnedState& learned) {
  const std::string& now = m.processor.setup().options.baseline_epoch;
  if (!learned.baseline_epoch || *learned.baseline_epoch == now) return false;
  spdlog::warn(
      "{}: baseline epoch \"{}\" -> \"{}\": forgetting the healthy baseline and its alarm "
      "state, learning a new baseline",
      m.id, *learned.baseline_epoch, now);
  return true;
}

// A configuration with fewer operating bands than the state it resumes keeps what fits.
void LogDroppedBands(const MachineRuntime& m) {
  if (const std::size_t dropped = m.processor.operating_bands_dropped(); dropped > 0) {
    spdlog::warn("{}: analysis.baseline.operating_bands {} holds fewer bands than were learned: "
                 "{} band(s) dropped, the learned ones kept first",
                 m.id, m.processor.setup().options.operating_bands, dropped);
  }
}

}  // namespace

// A machine of a new generation takes over what its predecessor learned (reload) or what was
// saved (start-up, or a machine added by a reload); else it learns. The pool is paused.
void Gearpathd::Impl::Resume(MachineLane& lane, MachineSet& previous) {
  MachineRuntime& m = *lane.runtime;
  if (auto old = previous.machines.find(m.id); old != previous.machines.end()) {
    const LearnedState learned = old->second->processor.ExportLearnedState();
    if (Status st = m.processor.ImportLearnedState(learned); !st) {
      if (!LogIfNewEpoch(m, learned)) {
        spdlog::warn(
            "{}: the reloaded configuration changes what the baseline measures ({}); "
            "learning a new baseline",
            m.id, st.error());
      }
      lane.mark = SaveMark{FaultState::kLearning, true, Clock::now(), false};
      lane.counters.fault_state = FaultState::kLearning;
    }
    LogDroppedBands(m);
    return;  // counters and save marks carry over as they are
  }
  lane.counters = MachineCounters{};
  lane.mark = SaveMark{};
  if (!store) return;
  auto saved = store->Load(m.id);
  if (!saved) {
    spdlog::warn("{}: saved state not used ({}); learning a new baseline", m.id, saved.error());
    return;
  }
  if (!saved.value()) {
    spdlog::info("{}: no saved state in {}; learning the healthy baseline", m.id,
                 store->directory());
    return;
  }
  SavedMachine& s = **saved;
  lane.counters = std::move(s.counters);
  const double age_s = static_cast<double>(RealtimeNs() - s.saved_at_ns) * 1e-9;
  if (Status st = m.processor.ImportLearnedState(s.learned); !st) {
    if (LogIfNewEpoch(m, s.learned)) return;  // asked for, not a fault of the file
    spdlog::warn("{}: saved state not used ({}); learning a new baseline (counters kept)", m.id,
                 st.error());
    return;
  }
  LogDroppedBands(m);
  lane.mark.last_state = s.learned.alarm.state;
  lane.counters.fault_state = s.learned.alarm.state;
  spdlog::info("{}: resumed from {} (saved {:.0f} s ago): baseline {} of {} blocks, verdict "
               "state {}",
               m.id, store->PathOf(m.id), age_s, m.processor.baseline_blocks_learned(),
               m.processor.baseline_blocks_needed(), ToString(s.learned.alarm.state));
}

void Gearpathd::Impl::Adopt(Generation generation) {
  const DaemonConfig& c = generation.config;
  if (static_cast<std::size_t>(c.queue_blocks) != queue_capacity || WorkerCount(c) != workers) {
    spdlog::warn("daemon.workers and daemon.queue_blocks take effect at the next start: still "
                 "{} worker(s), {} block(s) per machine",
                 workers, queue_capacity);
  }
  // The workers' processing scratch for the new machines, made before the pause (no worker
  // sees it yet) and swapped in during it: every machine's first block allocates nothing, and
  // the areas of shapes no longer configured go with the old scratch.
  std::vector<BlockScratch> block_scratch(workers);
  if (Status st = PrepareWorkerScratch(generation.machines, block_scratch); !st) {
    spdlog::warn("{}; the first such block configures it", st.error());
  }
  // No block is processed while the machines change hands; blocks queued meanwhile wait.
  pool->Pause();
  for (std::size_t w = 0; w < workers; ++w) std::swap(scratch[w].block, block_scratch[w]);
  std::lock_guard metrics_view(metrics_view_mutex);
  MachineSet previous = std::move(machines);
  machines = std::move(generation.machines);
  const std::vector<std::string> previous_ids = std::exchange(machine_ids, MachineIds(c));
  machine_filter.Admit(machine_ids);
  // MachineHealth instances of machines this daemon no longer serves (all of them if its id
  // changed) are disposed, so that subscribers and late joiners stop seeing them.
  if (!previous_ids.empty()) {
    std::vector<std::string> gone;
    for (const std::string& id : previous_ids) {
      if (c.daemon_id != daemon_id || !machines.machines.contains(id)) gone.push_back(id);
    }
    DisposeHealth(daemon_id, gone);
  }
  if (machine_ids.size() > gearpath_MAX_MACHINES) {
    spdlog::info("{} machines: Status lists the first {} (its wire bound, configuration order); "
                 "topic \"{}\" reports every machine",
                 machine_ids.size(), gearpath_MAX_MACHINES, c.topics.machine_health);
  }
  // Lanes of machines no longer configured go, with their counters and queued blocks.
  for (auto it = lanes.begin(); it != lanes.end();) {
    if (machines.machines.contains(it->first)) {
      ++it;
      continue;
    }
    foreign_blocks += pool->Detach(*it->second);
    it = lanes.erase(it);
  }
  std::erase_if(counters, [&](const auto& e) { return !machines.machines.contains(e.first); });
  for (auto& [id, m] : machines.machines) {
    auto lane = lanes.find(id);
    if (lane == lanes.end()) {
      lane = lanes.emplace(id, std::make_unique<MachineLane>(id, queue_capacity)).first;
    }
    pool->Attach(*lane->second, machines.machines.size());
    lane->second->runtime = m.get();
    Resume(*lane->second, previous);
  }
  pool->Resume();
  save_period = Seconds(c.state_save_period_s);
  if (c.standby_primary != primary_id) {
    primary_id = c.standby_primary;
    // A new standby gives its primary one takeover period to show itself before it publishes.
    publishing = primary_id.empty();
    primary_last_seen = Clock::now();
    primary_seen = false;
    if (!primary_id.empty()) {
      spdlog::info("standby for daemon \"{}\": results are published only while its Status "
                   "is missing for {:.2f} s",
                   primary_id, c.takeover_after_s);
    }
  }
  takeover_after = Seconds(c.takeover_after_s);
  daemon_id = c.daemon_id;
  status_period = Seconds(c.status_period_s);
  throughput_period = Seconds(c.throughput_log_period_s);
  const auto now = Clock::now();
  next_status = now;
  next_throughput = now + throughput_period;
}

void Gearpathd::Impl::AdoptPending() {
  std::optional<Generation> next;
  {
    std::lock_guard lock(pending_mutex);
    next.swap(pending);
  }
  if (!next) return;
  Adopt(std::move(*next));
  spdlog::info("reload: now running {} machine(s)", machine_ids.size());
}

// Copies every lane's counters for Status and the summary; a new period restarts the
// rejection lines' rate limit.
void Gearpathd::Impl::SnapshotCounters(bool new_period) {
  for (auto& [id, lane] : lanes) {
    std::lock_guard lock(lane->counters_mutex);
    if (new_period) lane->counters.rejection_lines_this_period = 0;
    counters[id] = lane->counters;
  }
}

void Gearpathd::Impl::PublishStatus(gearpath_DaemonState s) {
  SnapshotCounters(false);
  StatusFigures figures;
  figures.daemon_id = daemon_id;
  figures.state = s;
  figures.timestamp_ns = RealtimeNs();
  figures.uptime_s = duration<double>(Clock::now() - started).count();
  FillStatus(figures, machine_ids, counters, *status_sample);
  if (Status st = status_writer.Write(*status_sample); !st) {
    ++publish_failures;
    spdlog::error("Status not published: {}", st.error());
  }
  PublishHealth(s, figures.timestamp_ns);
}

// Reader thread, right after a counter snapshot: one MachineHealth sample per machine.
void Gearpathd::Impl::PublishHealth(gearpath_DaemonState s, std::int64_t timestamp_ns) {
  MachineHealthFigures figures;
  figures.daemon_id = daemon_id;
  figures.state = s;
  figures.timestamp_ns = timestamp_ns;
  figures.machine_count = static_cast<std::uint32_t>(machine_ids.size());
  figures.publishing_results = publishing.load();
  static const MachineCounters kNone;
  std::size_t failed = 0;
  std::string first_error;
  for (std::size_t i = 0; i < machine_ids.size(); ++i) {
    const auto it = counters.find(machine_ids[i]);
    FillMachineHealth(figures, machine_ids[i], static_cast<std::uint32_t>(i),
                      it == counters.end() ? kNone : it->second, *health_sample);
    if (Status st = health_writer.Write(*health_sample); !st) {
      if (failed++ == 0) first_error = st.error();
    }
  }
  if (failed > 0) {  // one line per period, not one per machine
    publish_failures += failed;
    spdlog::error("MachineHealth not published for {} of {} machine(s): {}", failed,
                  machine_ids.size(), first_error);
  }
}

void Gearpathd::Impl::DisposeHealth(const std::string& of_daemon,
                                    std::span<const std::string> ids) {
  for (const std::string& id : ids) {
    CopyTruncated(health_sample->daemon_id, of_daemon);
    CopyTruncated(health_sample->machine_id, id);
    if (Status st = health_writer.Dispose(*health_sample); !st) {
      spdlog::warn("{}: MachineHealth instance not disposed: {}", id, st.error());
    } else {
      spdlog::info("{}: no longer served, its MachineHealth instance disposed", id);
    }
  }
}

void Gearpathd::Impl::LogThroughput() {
  const auto now = Clock::now();
  const double seconds = std::max(1e-9, duration<double>(now - last_summary).count());
  SnapshotCounters(true);
  std::string line;
  for (const auto& id : machine_ids) {
    const MachineCounters& c = counters[id];
    const MachineCounters& before = counters_at_last_summary[id];
    std::string reasons;
    for (const auto& [reason, n] : c.rejected_by_reason) {
      const auto it = before.rejected_by_reason.find(reason);
      const std::uint64_t delta = n - (it == before.rejected_by_reason.end() ? 0 : it->second);
      if (delta > 0) reasons += fmt::format("{}{} {}", reasons.empty() ? "" : ", ", reason, delta);
    }
    line += fmt::format("{}{}: {} processed ({:.2f}/s), {} rejected{}, {} lost, latency last "
                        "{:.1f} ms max {:.1f} ms",
                        line.empty() ? "" : "; ", id, c.processed - before.processed,
                        static_cast<double>(c.processed - before.processed) / seconds,
                        c.rejected - before.rejected,
                        reasons.empty() ? "" : " (" + reasons + ")", c.lost - before.lost,
                        c.latency_last_ms, c.latency_max_ms);
    if (c.rejection_lines_suppressed > before.rejection_lines_suppressed) {
      line += fmt::format(" ({} rejection lines not logged)",
                          c.rejection_lines_suppressed - before.rejection_lines_suppressed);
    }
    if (c.indicators_omitted > before.indicators_omitted) {
      line += fmt::format(", {} condition indicator entries over the IDL bounds left out",
                          c.indicators_omitted - before.indicators_omitted);
    }
  }
  // Dropped by the reader's machine filter, or taken during a reload before the new machine
  // set was adopted.
  const std::uint64_t foreign_now = foreign_blocks + machine_filter.dropped();
  const std::uint64_t foreign = foreign_now - foreign_blocks_at_last_summary;
  spdlog::info("throughput over {:.0f} s: {}{}", seconds, line,
               foreign > 0 ? fmt::format("; {} block(s) of other machines ignored", foreign)
                           : std::string());
  std::uint64_t processed = 0, rejected = 0;
  for (const auto& [id, c] : counters) {
    processed += c.processed;
    rejected += c.rejected;
  }
  NotifySystemd(fmt::format("STATUS=running: {} machine(s), {} block(s) processed, {} "
                            "rejected since start",
                            machine_ids.size(), processed, rejected));
  counters_at_last_summary = counters;
  foreign_blocks_at_last_summary = foreign_now;
  last_summary = now;
}

void Gearpathd::Impl::Housekeeping(bool force_status) {
  const auto now = Clock::now();
  if (force_status || now >= next_status) {
    PublishStatus(static_cast<gearpath_DaemonState>(state.load()));
    next_status += status_period;
    if (next_status <= now) next_status = now + status_period;
  }
  if (now >= next_throughput) {
    LogThroughput();
    next_throughput = now + throughput_period;
  }
  SaveDueMachines(false);
  for (const std::string& id : machine_filter.TakeNewForeignIds()) {
    spdlog::info("ignoring blocks of machine \"{}\": not in this daemon's configuration", id);
  }
  if (!primary_id.empty() && now >= next_primary_check) WatchPrimary();
  heap_trimmer.MaybeTrim(now);
  if (watchdog_period.count() > 0 && now >= next_watchdog) {
    NotifySystemd("WATCHDOG=1");
    next_watchdog = now + watchdog_period / 2;
  }
}

void Gearpathd::Impl::WatchPrimary() {
  if (primary_id.empty()) return;
  const auto now = Clock::now();
  for (;;) {
    auto n = status_reader.Take(status_samples, status_infos);
    if (!n || *n == 0) break;
    for (std::size_t i = 0; i < *n; ++i) {
      if (!status_infos[i].valid_data) continue;
      const gearpath_Status& s = *status_samples[i];
      if (dds::GetString(s.daemon_id) != primary_id) continue;
      // Its arrival on our clock, not its timestamp: the hosts' clocks may disagree.
      primary_last_seen = s.state == gearpath_STOPPING ? Clock::time_point{} : now;
      if (!primary_seen && s.state != gearpath_STOPPING) {
        primary_seen = true;
        spdlog::info("primary \"{}\" seen: standing by", primary_id);
      }
    }
  }
  const bool primary_silent = now - primary_last_seen >= takeover_after;
  if (primary_silent && !publishing) {
    publishing = true;
    spdlog::warn("primary \"{}\" silent for {:.2f} s: publishing results from now on",
                 primary_id, duration<double>(now - primary_last_seen).count());
  } else if (!primary_silent && publishing) {
    publishing = false;
    spdlog::info("primary \"{}\" is back: standing by (results withheld)", primary_id);
  }
  next_primary_check = now + takeover_after / 4;
}

// Worker or reader, with the lane's processor_mutex held.
void Gearpathd::Impl::MarkChanged(MachineLane& lane, FaultState verdict_state) {
  SaveMark& mark = lane.mark;
  if (verdict_state != mark.last_state) {
    // A verdict state that changes (learned, raised, cleared) is saved at once: a restart
    // must resume exactly that judgement.
    mark.last_state = verdict_state;
    SaveMachine(lane);
    return;
  }
  if (!mark.dirty) {
    mark.dirty = true;
    mark.dirty_since = Clock::now();
  }
}

// With the lane's processor_mutex held (its processor is idle).
void Gearpathd::Impl::SaveMachine(MachineLane& lane) {
  SaveMark& mark = lane.mark;
  mark.dirty = false;
  if (!store) return;
  SavedMachine saved;
  saved.machine_id = lane.id;
  saved.saved_at_ns = RealtimeNs();
  saved.learned = lane.runtime->processor.ExportLearnedState();
  {
    std::lock_guard lock(lane.counters_mutex);
    saved.counters = lane.counters;
  }
  if (Status st = store->Save(saved); !st) {
    ++state_save_failures;
    if (!mark.failing) spdlog::error("{}: state not saved: {} (said once until it works)",
                                     lane.id, st.error());
    mark.failing = true;
    return;
  }
  if (mark.failing) spdlog::info("{}: state saved again", lane.id);
  mark.failing = false;
}

// Reader thread. A machine whose worker holds it now is saved at a later round (never waits).
void Gearpathd::Impl::SaveDueMachines(bool all) {
  const auto now = Clock::now();
  for (auto& [id, lane] : lanes) {
    std::unique_lock lock(lane->processor_mutex, std::defer_lock);
    if (all) {
      lock.lock();
    } else if (!lock.try_lock()) {
      continue;
    }
    const SaveMark& mark = lane->mark;
    if (mark.dirty && (all || now - mark.dirty_since >= save_period)) SaveMachine(*lane);
  }
}

// Worker thread, with the lane's processor_mutex held: blocks that found the queue full are
// rejections (reason queue_full) of blocks numbered before this one, so the gap they leave is
// not counted as lost.
void Gearpathd::Impl::CountDrops(MachineLane& lane, std::uint64_t dropped,
                                 std::uint64_t before_sequence) {
  constexpr std::string_view kReason = "queue_full";
  bool log = false;
  {
    std::lock_guard lock(lane.counters_mutex);
    MachineCounters& c = lane.counters;
    c.received += dropped;
    c.rejected += dropped;
    c.rejected_in_gap += dropped;
    auto r = c.rejected_by_reason.find(kReason);
    if (r == c.rejected_by_reason.end()) r = c.rejected_by_reason.emplace(kReason, 0).first;
    r->second += dropped;
    c.last_rejection = fmt::format("{}: {} block(s) arrived while {} were queued", kReason,
                                   dropped, queue_capacity);
    if (c.rejection_lines_this_period < kRejectionLinesPerPeriod) {
      ++c.rejection_lines_this_period;
      log = true;
    } else {
      ++c.rejection_lines_suppressed;
    }
  }
  if (log) {
    spdlog::warn("{}: {} block(s) dropped before block {}: processing fell behind (queue of {} "
                 "blocks full)",
                 lane.id, dropped, before_sequence, queue_capacity);
  }
}

// Worker thread: one block of one machine, start to publish.
void Gearpathd::Impl::HandleBlock(WorkerScratch& ws, MachineLane& lane, QueuedBlock& block) {
  if (!block.info.valid_data) return;
  std::lock_guard processor_lock(lane.processor_mutex);
  MachineRuntime& m = *lane.runtime;
  MachineCounters& c = lane.counters;  // written under counters_mutex: Status reads it
  const AccelBlockView view = block.with_load ? dds::ViewOfWireBlock(*block.sample_v2, ws.channels)
                                              : dds::ViewOfWireBlock(*block.sample, ws.channels);
  if (block.dropped_before > 0) CountDrops(lane, block.dropped_before, view.sequence);
  const ProcessOutcome outcome = m.processor.Process(view, m.result, ws.block);
  if (!outcome.accepted()) {
    const std::string_view reason = ToString(outcome.reason);
    bool log = false;
    {
      std::lock_guard lock(lane.counters_mutex);
      ++c.received;
      ++c.rejected;
      // A rejected block does not advance the sequence tracker, so the next accepted block
      // will see its number as part of a gap; remember it so that it is not counted as lost.
      if (outcome.reason != RejectReason::kDuplicateSequence &&
          outcome.reason != RejectReason::kOutOfOrderSequence) {
        ++c.rejected_in_gap;
      }
      auto r = c.rejected_by_reason.find(reason);
      if (r == c.rejected_by_reason.end()) r = c.rejected_by_reason.emplace(reason, 0).first;
      ++r->second;
      c.last_rejection = fmt::format("{}: {}", reason, outcome.message.view());
      // A peer sending bad blocks must not flood the log: the first kRejectionLinesPerPeriod
      // of each machine per throughput period are logged, the rest counted in the summary.
      if (c.rejection_lines_this_period < kRejectionLinesPerPeriod) {
        ++c.rejection_lines_this_period;
        log = true;
      } else {
        ++c.rejection_lines_suppressed;
      }
    }
    MarkChanged(lane, lane.mark.last_state);  // counters changed
    if (log) {
      spdlog::warn("{}: block {} rejected ({}): {}", m.id, view.sequence, reason,
                   outcome.message.view());
    }
    return;
  }
  const BlockResult& r = m.result;
  std::uint64_t lost = 0;
  bool first_omission = false;
  const OmittedIndicators omitted =
      FillConditionIndicators(m.id, r, m.indicator_names, *ws.condition);
  {
    std::lock_guard lock(lane.counters_mutex);
    ++c.received;
    ++c.processed;
    const std::uint64_t explained = std::min(r.sequence_gap, c.rejected_in_gap);
    c.rejected_in_gap = 0;
    lost = r.sequence_gap - explained;
    c.lost += lost;
    if (omitted.any()) {
      // Counted always, said once per machine: the sample itself carries the counts.
      first_omission = c.indicators_omitted == 0;
      c.indicators_omitted += omitted.sets + omitted.values + omitted.names;
    }
    if (r.score.not_judged != NotJudgedCause::kNone) {
      ++c.not_judged[static_cast<std::size_t>(r.score.not_judged)];
    }
    c.last_alpha = r.regularisation.alpha_median;
    c.last_condition = r.regularisation.condition_max;
    c.last_residual = r.regularisation.relative_residual;
    c.fault_state = r.verdict.state;
    c.last_sequence = r.sequence;
    c.last_t0_ns = r.t0_ns;
    CaptureLatestIndicators(r, c.latest);
  }
  MarkChanged(lane, r.verdict.state);
  if (lost > 0) {
    spdlog::warn("{}: {} block(s) missing before block {}", m.id, lost, r.sequence);
  }
  if (r.sequence_restarted) {
    spdlog::info("{}: sequence restarted at block {} (publisher restart)", m.id, r.sequence);
  }
  if (first_omission) {
    spdlog::warn("{}: block {}: ConditionIndicators exceeds the IDL bounds ({} sets > {}, "
                 "{} values > {} per set, {} names > {} chars): left out and counted "
                 "(sets_omitted, values_omitted); further blocks are counted silently",
                 m.id, r.sequence, omitted.sets, gearpath_MAX_INDICATOR_SETS, omitted.values,
                 gearpath_MAX_INDICATORS_PER_SET, omitted.names, gearpath_INDICATOR_NAME_LENGTH);
  }
  FillDominantPath(m.id, r, *ws.dominant);
  FillSuspectedGear(m.id, r, *ws.gear);
  FillEnvelopeIndicators(m.id, r, *ws.indicators);
  if (publishing.load()) {
    for (Status st : {dominant_writer.Write(*ws.dominant), gear_writer.Write(*ws.gear),
                      indicators_writer.Write(*ws.indicators),
                      condition_writer.Write(*ws.condition)}) {
      if (!st) {
        ++publish_failures;
        spdlog::error("{}: result of block {} not published: {}", m.id, r.sequence, st.error());
      }
    }
  } else {
    ++results_withheld;  // standing by: the primary publishes this block's results
  }
  {
    // The metrics histogram: taken from the reader to results written, on this host's steady
    // clock (no publisher clock in it).
    const double handled_s = duration<double>(Clock::now() - block.taken_at).count();
    std::lock_guard lock(lane.counters_mutex);
    c.latency.Observe(handled_s);
    if (block.info.source_timestamp > 0) {
      // Writer's timestamp to results published: includes the time the block waited in the
      // reader's history and its machine's queue, which is what a late result costs the plant.
      const double latency_ms = std::max(
          0.0, static_cast<double>(RealtimeNs() - block.info.source_timestamp) * 1e-6);
      c.latency_last_ms = latency_ms;
      c.latency_max_ms = std::max(c.latency_max_ms, latency_ms);
    }
  }
  spdlog::debug("{}: block {} -> path {}, {} {}", m.id, r.sequence, r.dominant_path_name,
                ToString(r.verdict.state), r.verdict.gear_name);
}

// Reader thread: hands the taken block to its machine's lane. When the lane is full (the
// machine is a whole queue behind) it waits for room instead of dropping: the reader then
// takes no more blocks, their writers' reliable histories fill and DDS flow control slows them,
// so a burst such as `gearpath replay --fast` loses nothing (docs/topics.md). Only a stop drops
// the block (counted as queue_full). Lanes are detached and the pool paused or stopped by this
// thread only, so none of that can happen during the wait.
void Gearpathd::Impl::Dispatch(bool with_load) {
  const auto it = lanes.find(with_load ? dds::GetString(samples_v2[0]->machine_id)
                                       : dds::GetString(samples[0]->machine_id));
  if (it == lanes.end()) {
    // Let through by the machine filter just before a reload changed the machines: not ours
    // to judge, so not a rejection (the filter logs foreign ids; this only counts them).
    ++foreign_blocks;
    return;
  }
  MachineLane& lane = *it->second;
  offered.with_load = with_load;
  if (with_load) {
    offered.sample_v2 = std::move(samples_v2[0]);
  } else {
    offered.sample = std::move(samples[0]);
  }
  offered.info = with_load ? infos_v2[0] : infos[0];
  offered.dropped_before = lane.pending_drops;
  offered.taken_at = Clock::now();
  bool queued = pool->Offer(lane, offered);
  while (!queued && !stop_requested.load()) {
    if (!pool->WaitForRoom(lane, kRoomWait)) {
      Housekeeping(false);  // Status and the watchdog keep going while the machine catches up
      continue;
    }
    queued = pool->Offer(lane, offered);
  }
  if (queued) {
    lane.pending_drops = 0;
    pool->TakeSpare(offered);  // a handled block's buffers, for the next Take
  } else {
    ++lane.pending_drops;  // counted and logged with the machine's next queued block
  }
  if (with_load) {
    samples_v2[0] = std::move(offered.sample_v2);
  } else {
    samples[0] = std::move(offered.sample);
  }
}

// One block at a time, until neither block topic holds one. With both topics read, each one's
// oldest block is held and the one written first (source timestamp) goes first, so a machine's
// blocks keep their order when they move from one topic to the other.
void Gearpathd::Impl::DrainBlocks() {
  const auto take = [&](bool with_load) {
    auto taken = with_load ? block_v2_reader->Take(samples_v2, infos_v2)
                           : block_reader.Take(samples, infos);
    if (!taken) {
      spdlog::error("taking {} failed: {}", with_load ? "AccelBlockV2s" : "AccelBlocks",
                    taken.error());
      return false;
    }
    return *taken > 0 && (with_load ? infos_v2 : infos)[0].valid_data;
  };
  while (!stop_requested.load()) {
    if (!held_block) held_block = take(false);
    if (block_v2_reader && !held_block_v2) held_block_v2 = take(true);
    if (!held_block && !held_block_v2) return;
    const bool with_load =
        held_block_v2 &&
        (!held_block || infos_v2[0].source_timestamp < infos[0].source_timestamp);
    (with_load ? held_block_v2 : held_block) = false;
    Dispatch(with_load);
    AdoptPending();  // a reload takes effect between two blocks
    Housekeeping(false);
  }
}

void Gearpathd::Impl::Loop() {
  std::array<dds_attach_t, 2> triggered{};
  Housekeeping(true);
  while (!stop_requested.load()) {
    auto wait = next_status - Clock::now();
    if (watchdog_period.count() > 0) wait = std::min(wait, next_watchdog - Clock::now());
    if (!primary_id.empty()) wait = std::min(wait, next_primary_check - Clock::now());
    wait = std::max<Clock::duration>(wait, Clock::duration::zero());
    auto woke = waitset.Wait(triggered, duration_cast<nanoseconds>(wait));
    if (!woke) {
      spdlog::critical("DDS WaitSet failed: {}", woke.error());
      loop_failed = true;
      return;
    }
    (void)guard.TakeTriggered();
    if (stop_requested.load()) break;
    AdoptPending();
    DrainBlocks();
    Housekeeping(false);
  }
  pool->Stop();  // the blocks in hand are finished; queued ones are left
  SaveDueMachines(true);
  LogThroughput();  // the last period's figures, rate-limited lines included
  PublishStatus(gearpath_STOPPING);  // the last word: subscribers see a clean stop
}

void Gearpathd::Impl::Reload() {
  NotifySystemd("RELOADING=1\nSTATUS=reloading the configuration");
  state = gearpath_RELOADING;
  const std::string origin = options.config_path.empty() ? std::string(kEmbeddedOrigin)
                                                         : options.config_path;
  spdlog::info("SIGHUP: reloading {}", origin);
  auto config = options.config_path.empty()
                    ? ParseDaemonConfig(DefaultConfigText(), kEmbeddedOrigin)
                    : LoadDaemonConfigFile(options.config_path);
  std::string failure;
  std::optional<MachineSet> built;
  if (!config) {
    failure = config.error();
  } else if (config->normalized["dds"] != lifecycle_config.normalized["dds"]) {
    failure = "dds: the domain and topic names cannot change on reload (restart the daemon)";
  } else if (ResolveStateDirectory(*config) != ResolveStateDirectory(lifecycle_config)) {
    failure = "state.directory cannot change on reload (restart the daemon)";
  } else if (config->machines.size() > block_instances) {
    failure = fmt::format("machines: {} machines exceed the {} the block reader was sized for "
                          "at start-up (twice the machines then configured, at least {}); "
                          "restart the daemon",
                          config->machines.size(), block_instances,
                          dds::kMaxMachinesPerDomain);
  } else {
    auto machines_built = BuildMachines(*config, frf_registry);
    if (!machines_built) {
      failure = machines_built.error();
    } else if (Status st = ChangeMetrics(config->metrics, lifecycle_config.metrics); !st) {
      failure = st.error();
    } else {
      built.emplace(std::move(machines_built.value()));
    }
  }
  if (!built) {
    spdlog::error("reload failed, still running the previous configuration:\n{}", failure);
    state = gearpath_DEGRADED;
    NotifySystemd("READY=1\nSTATUS=reload failed, running the previous configuration");
    return;
  }
  if (options.log_level_override.empty()) ApplyLogLevel(config->log_level);
  for (const auto& [id, m] : built->machines) spdlog::info("machine {}: {}", id, m->summary);
  lifecycle_config = *config;
  {
    std::lock_guard lock(pending_mutex);
    pending.emplace(Generation{std::move(config.value()), std::move(*built)});
  }
  (void)guard.Trigger();
  state = gearpath_RUNNING;
  NotifySystemd(fmt::format("READY=1\nSTATUS=running: {} machine(s) (reloaded)",
                            lifecycle_config.machines.size()));
}

// Metrics thread: a copy of every machine's counters (under its counters_mutex, as Status
// copies them) and of the daemon's own figures.
DaemonMetrics Gearpathd::Impl::CollectMetrics() {
  DaemonMetrics m;
  m.version = options.version;
  const auto s = static_cast<std::size_t>(state.load());
  m.state = s < std::size(kDaemonStateNames) ? kDaemonStateNames[s] : "unknown";
  m.uptime_s = duration<double>(Clock::now() - started).count();
  m.publishing_results = publishing.load();
  m.foreign_blocks = foreign_blocks.load() + machine_filter.dropped();
  m.publish_failures = publish_failures.load();
  m.results_withheld = results_withheld.load();
  m.state_save_failures = state_save_failures.load();
  std::lock_guard view(metrics_view_mutex);
  m.daemon_id = daemon_id;
  m.machines.reserve(machine_ids.size());
  for (const std::string& id : machine_ids) {
    const auto it = lanes.find(id);
    if (it == lanes.end()) continue;
    MachineMetrics& machine = m.machines.emplace_back();
    machine.id = id;
    if (const MachineRuntime* r = it->second->runtime; r != nullptr) {
      machine.baseline_epoch = r->processor.setup().options.baseline_epoch;
    }
    std::lock_guard lock(it->second->counters_mutex);
    machine.counters = it->second->counters;
  }
  return m;
}

// Lifecycle thread: starts the endpoint `config` asks for (none when disabled).
Status Gearpathd::Impl::StartMetrics(const MetricsConfig& config) {
  metrics_server.reset();
  if (!config.enabled) return {};
  auto server = MetricsServer::Start(config.address, config.port,
                                     [this] { return RenderMetrics(CollectMetrics()); });
  if (!server) return Error{server.error()};
  metrics_server = std::move(server.value());
  spdlog::info("metrics endpoint listening on {}", metrics_server->url());
  if (config.allow_remote) {
    spdlog::warn("metrics endpoint on {} (metrics.allow_remote): no TLS, no authentication; "
                 "anyone who reaches it reads every machine's counters and states",
                 config.address);
  }
  return {};
}

// Lifecycle thread, on reload: a changed `metrics` restarts the endpoint (the old one stops
// first, so the same port can be taken again). If the new one cannot start, the old one is
// started again and the reload fails with the reason.
Status Gearpathd::Impl::ChangeMetrics(const MetricsConfig& next, const MetricsConfig& previous) {
  if (next == previous) return {};
  if (!next.enabled) {
    if (metrics_server) spdlog::info("metrics endpoint stopped (metrics.enabled is false)");
    metrics_server.reset();
    return {};
  }
  // The port the running endpoint has, so that one on port 0 comes back where it was.
  MetricsConfig restore = previous;
  if (metrics_server && restore.port == 0) restore.port = metrics_server->port();
  Status opened = StartMetrics(next);
  if (opened) return {};
  if (Status back = StartMetrics(restore); !back) {
    spdlog::error("{}; the previous metrics endpoint could not be restarted either: {}",
                  opened.error(), back.error());
  }
  return opened;
}

int Gearpathd::Impl::Run(const SignalEvents& signals) {
  watchdog_period = duration_cast<Clock::duration>(SystemdWatchdogPeriod()) / 2;
  next_watchdog = Clock::now();
  state = gearpath_RUNNING;
  std::thread loop([this] { Loop(); });
  NotifySystemd(fmt::format("READY=1\nSTATUS=running: {} machine(s)",
                            lifecycle_config.machines.size()));
  const TopicNames& topics = lifecycle_config.topics;
  spdlog::info("gearpathd \"{}\" running on DDS domain {}: {} machine(s), input topic(s) \"{}\"{}",
               lifecycle_config.daemon_id, lifecycle_config.domain_id,
               lifecycle_config.machines.size(), topics.accel_block,
               topics.accel_block_v2.empty() ? "" : " and \"" + topics.accel_block_v2 + "\"");
  int exit_code = 0;
  for (;;) {
    const SignalEvent event = signals.Wait(milliseconds(200));
    if (event == SignalEvent::kTerminate) {
      spdlog::info("signal {}: stopping", signals.signal_of_last_event());
      break;
    }
    if (event == SignalEvent::kReload) Reload();
    if (loop_failed.load()) {
      exit_code = 1;
      break;
    }
  }
  NotifySystemd("STOPPING=1\nSTATUS=stopping");
  state = gearpath_STOPPING;
  stop_requested = true;
  (void)guard.Trigger();
  loop.join();
  spdlog::info("stopped");
  return exit_code;
}

Gearpathd::Gearpathd(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Gearpathd::~Gearpathd() = default;

Result<std::unique_ptr<Gearpathd>> Gearpathd::Create(DaemonConfig config, MachineSet machines,
                                                     DaemonOptions options) {
  std::optional<MachineStateStore> store;
  if (const std::string dir = ResolveStateDirectory(config); dir.empty()) {
    spdlog::warn("no state directory (state.directory, $STATE_DIRECTORY): learned baselines "
                 "and counters will be forgotten when gearpathd stops");
  } else {
    auto opened = MachineStateStore::Open(dir);
    if (!opened) return Error{opened.error()};
    store.emplace(std::move(opened.value()));
    spdlog::info("machine state kept in {}", dir);
  }
  try {
    const MetricsConfig metrics = config.metrics;
    auto impl = std::make_unique<Impl>(Generation{std::move(config), std::move(machines)},
                                       std::move(options), std::move(store));
    if (Status st = impl->StartMetrics(metrics); !st) return Error{st.error()};
    return std::unique_ptr<Gearpathd>(new Gearpathd(std::move(impl)));
  } catch (const std::exception& e) {
    return Error{fmt::format("DDS set-up failed: {}", e.what())};
  }
}

int Gearpathd::Run(const SignalEvents& signals) { return impl_->Run(signals); }

}  // namespace gearpath::daemon
