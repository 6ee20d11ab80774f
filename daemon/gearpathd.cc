#include "daemon/gearpathd.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <array>
#include <atomic>
#include <chrono>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <thread>

#include "daemon/dds_bridge.h"
#include "daemon/dds_setup.h"
#include "idl/dds/accel_block_wire.h"
#include "daemon/machine_id_filter.h"
#include "daemon/machine_runtime.h"
#include "daemon/machine_state_store.h"
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
constexpr std::uint64_t kRejectionLinesPerPeriod = 10;

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

// The block topic with the machine filter set, ready for the block reader.
const dds::Topic<gearpath_AccelBlock>& FilteredByMachine(dds::Topic<gearpath_AccelBlock>& topic,
                                                         MachineIdFilter& filter) {
  topic.SetSampleFilter(&MachineIdFilter::Accept, &filter);
  return topic;
}

struct Gearpathd::Impl {
  Impl(Generation first, DaemonOptions opts, std::optional<MachineStateStore> state_store)
      : options(std::move(opts)),
        store(std::move(state_store)),
        lifecycle_config(first.config),
        domain(first.config.domain_id, DaemonDomainConfig(first.config)),
        participant(domain, DaemonSecurityFiles(first.config)),
        block_topic(participant, first.config.topics.accel_block),
        dominant_topic(participant, first.config.topics.dominant_path),
        gear_topic(participant, first.config.topics.suspected_gear),
        indicators_topic(participant, first.config.topics.envelope_indicators),
        condition_topic(participant, first.config.topics.condition_indicators),
        status_topic(participant, first.config.topics.status),
        block_reader(FilteredByMachine(block_topic, machine_filter)),
        status_reader(status_topic),
        dominant_writer(dominant_topic),
        gear_writer(gear_topic),
        indicators_writer(indicators_topic),
        condition_writer(condition_topic),
        status_writer(status_topic),
        blocks_ready(block_reader),
        guard(participant),
        waitset(participant) {
    waitset.Attach(blocks_ready, kBlocksToken);
    waitset.Attach(guard, kGuardToken);
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
  void HandleBlock(const gearpath_AccelBlock& sample, const dds::SampleInfo& info);
  void Housekeeping(bool force_status);
  void PublishStatus(gearpath_DaemonState state);
  void LogThroughput();
  void Resume(MachineRuntime& machine, MachineSet& previous);
  void MarkChanged(const MachineRuntime& machine, FaultState verdict_state);
  void SaveMachine(const MachineRuntime& machine);
  void SaveDueMachines(bool all);
  void WatchPrimary();

  DaemonOptions options;
  std::optional<MachineStateStore> store;  // none: nothing is kept across restarts
  MachineIdFilter machine_filter;  // before the block reader, which it filters
  DaemonConfig lifecycle_config;  // the configuration in force, as the lifecycle thread knows it
  const Clock::time_point started = Clock::now();

  dds::Domain domain;
  dds::Participant participant;
  dds::Topic<gearpath_AccelBlock> block_topic;
  dds::Topic<gearpath_DominantPath> dominant_topic;
  dds::Topic<gearpath_SuspectedGear> gear_topic;
  dds::Topic<gearpath_EnvelopeIndicators> indicators_topic;
  dds::Topic<gearpath_ConditionIndicators> condition_topic;
  dds::Topic<gearpath_Status> status_topic;
  dds::Reader<gearpath_AccelBlock> block_reader;
  dds::Reader<gearpath_Status> status_reader;  // a standby watches its primary's Status
  dds::Writer<gearpath_DominantPath> dominant_writer;
  dds::Writer<gearpath_SuspectedGear> gear_writer;
  dds::Writer<gearpath_EnvelopeIndicators> indicators_writer;
  dds::Writer<gearpath_ConditionIndicators> condition_writer;
  dds::Writer<gearpath_Status> status_writer;
  dds::ReadCondition blocks_ready;
  dds::GuardCondition guard;
  dds::WaitSet waitset;

  // Shared between the threads.
  std::atomic<bool> stop_requested{false};
  std::atomic<bool> loop_failed{false};
  std::atomic<int> state{gearpath_STARTING};
  std::mutex pending_mutex;
  std::optional<Generation> pending;

  // Processing thread only (after construction).
  MachineSet machines;
  std::vector<std::string> machine_ids;  // configuration order, for Status
  std::string daemon_id;
  Clock::duration status_period{};
  Clock::duration throughput_period{};
  Clock::duration watchdog_period{};  // half of systemd's WatchdogSec; zero: no watchdog
  std::map<std::string, MachineCounters, std::less<>> counters;
  std::map<std::string, MachineCounters, std::less<>> counters_at_last_summary;
  std::map<std::string, SaveMark, std::less<>> save_marks;
  Clock::duration save_period{};
  std::uint64_t state_save_failures = 0;
  // Hot standby: results are published only while `publishing`; a primary always publishes.
  std::string primary_id;
  Clock::duration takeover_after{};
  bool publishing = true;
  Clock::time_point primary_last_seen{};
  Clock::time_point next_primary_check{};
  bool primary_seen = false;  // its Status has arrived at least once (logged once)
  std::uint64_t results_withheld = 0;
  std::vector<dds::Owned<gearpath_Status>> status_samples;
  std::vector<dds::SampleInfo> status_infos;
  std::uint64_t foreign_blocks = 0;
  std::uint64_t foreign_blocks_at_last_summary = 0;
  std::uint64_t publish_failures = 0;
  Clock::time_point next_status{};
  Clock::time_point next_throughput{};
  Clock::time_point next_watchdog{};
  Clock::time_point last_summary = Clock::now();
  std::vector<dds::Owned<gearpath_AccelBlock>> samples;
  std::vector<dds::SampleInfo> infos;
  std::vector<ChannelInfo> channel_scratch;
  dds::Owned<gearpath_DominantPath> dominant_sample;
  dds::Owned<gearpath_SuspectedGear> gear_sample;
  dds::Owned<gearpath_EnvelopeIndicators> indicators_sample;
  dds::Owned<gearpath_ConditionIndicators> condition_sample;
  dds::Owned<gearpath_Status> status_sample;
};

// A machine of a new generation takes over what its predecessor learned (reload) or what was
// saved (start-up, or a machine added by a reload); else it learns.
void Gearpathd::Impl::Resume(MachineRuntime& m, MachineSet& previous) {
  if (auto old = previous.machines.find(m.id); old != previous.machines.end()) {
    Status st = m.processor.ImportLearnedState(old->second->processor.ExportLearnedState());
    if (!st) {
      spdlog::warn("{}: the reloaded configuration changes what the baseline measures ({}); "
                   "learning a new baseline",
                   m.id, st.error());
      save_marks[m.id] = SaveMark{FaultState::kLearning, true, Clock::now(), false};
    }
    return;  // counters and save marks carry over as they are
  }
  counters[m.id] = MachineCounters{};
  save_marks[m.id] = SaveMark{};
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
  counters[m.id] = std::move(s.counters);
  const double age_s = static_cast<double>(RealtimeNs() - s.saved_at_ns) * 1e-9;
  if (Status st = m.processor.ImportLearnedState(s.learned); !st) {
    spdlog::warn("{}: saved state not used ({}); learning a new baseline (counters kept)", m.id,
                 st.error());
    return;
  }
  save_marks[m.id].last_state = s.learned.alarm.state;
  spdlog::info("{}: resumed from {} (saved {:.0f} s ago): baseline {} of {} blocks, verdict "
               "state {}",
               m.id, store->PathOf(m.id), age_s, m.processor.baseline_blocks_learned(),
               m.processor.baseline_blocks_needed(), ToString(s.learned.alarm.state));
}

void Gearpathd::Impl::Adopt(Generation generation) {
  const DaemonConfig& c = generation.config;
  MachineSet previous = std::move(machines);
  machines = std::move(generation.machines);
  machine_ids.clear();
  for (const auto& m : c.machines) machine_ids.push_back(m.id);
  machine_filter.Admit(machine_ids);
  for (auto& [id, m] : machines.machines) Resume(*m, previous);
  // Counters and save marks of machines no longer configured go.
  std::erase_if(counters, [&](const auto& e) { return !machines.machines.contains(e.first); });
  std::erase_if(save_marks, [&](const auto& e) { return !machines.machines.contains(e.first); });
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

void Gearpathd::Impl::PublishStatus(gearpath_DaemonState s) {
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
}

void Gearpathd::Impl::LogThroughput() {
  const auto now = Clock::now();
  const double seconds = std::max(1e-9, duration<double>(now - last_summary).count());
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
  for (auto& [id, c] : counters) c.rejection_lines_this_period = 0;
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

void Gearpathd::Impl::MarkChanged(const MachineRuntime& m, FaultState verdict_state) {
  SaveMark& mark = save_marks[m.id];
  if (verdict_state != mark.last_state) {
    // A verdict state that changes (learned, raised, cleared) is saved at once: a restart
    // must resume exactly that judgement.
    mark.last_state = verdict_state;
    SaveMachine(m);
    return;
  }
  if (!mark.dirty) {
    mark.dirty = true;
    mark.dirty_since = Clock::now();
  }
}

void Gearpathd::Impl::SaveMachine(const MachineRuntime& m) {
  SaveMark& mark = save_marks[m.id];
  mark.dirty = false;
  if (!store) return;
  SavedMachine saved;
  saved.machine_id = m.id;
  saved.saved_at_ns = RealtimeNs();
  saved.learned = m.processor.ExportLearnedState();
  saved.counters = counters[m.id];
  if (Status st = store->Save(saved); !st) {
    ++state_save_failures;
    if (!mark.failing) spdlog::error("{}: state not saved: {} (said once until it works)", m.id,
                                     st.error());
    mark.failing = true;
    return;
  }
  if (mark.failing) spdlog::info("{}: state saved again", m.id);
  mark.failing = false;
}

void Gearpathd::Impl::SaveDueMachines(bool all) {
  const auto now = Clock::now();
  for (auto& [id, m] : machines.machines) {
    const SaveMark& mark = save_marks[id];
    if (mark.dirty && (all || now - mark.dirty_since >= save_period)) SaveMachine(*m);
  }
}

void Gearpathd::Impl::HandleBlock(const gearpath_AccelBlock& sample,
                                  const dds::SampleInfo& info) {
  const std::string_view id = dds::GetString(sample.machine_id);
  const auto it = machines.machines.find(id);
  if (it == machines.machines.end()) {
    // Let through by the machine filter just before a reload changed the machines: not ours
    // to judge, so not a rejection (the filter logs foreign ids; this only counts them).
    ++foreign_blocks;
    return;
  }
  MachineRuntime& m = *it->second;
  MachineCounters& c = counters[m.id];
  ++c.received;
  const AccelBlockView view = dds::ViewOfWireBlock(sample, channel_scratch);
  const ProcessOutcome outcome = m.processor.Process(view, m.result);
  if (!outcome.accepted()) {
    const std::string_view reason = ToString(outcome.reason);
    ++c.rejected;
    // A rejected block does not advance the sequence tracker, so the next accepted block will
    // see its number as part of a gap; remember it so that it is not counted as lost too.
    if (outcome.reason != RejectReason::kDuplicateSequence &&
        outcome.reason != RejectReason::kOutOfOrderSequence) {
      ++c.rejected_in_gap;
    }
    auto r = c.rejected_by_reason.find(reason);
    if (r == c.rejected_by_reason.end()) r = c.rejected_by_reason.emplace(reason, 0).first;
    ++r->second;
    c.last_rejection = fmt::format("{}: {}", reason, outcome.message.view());
    MarkChanged(m, save_marks[m.id].last_state);  // counters changed
    // A peer sending bad blocks must not flood the log: the first kRejectionLinesPerPeriod
    // of each machine per throughput period are logged, the rest counted in the summary.
    if (c.rejection_lines_this_period < kRejectionLinesPerPeriod) {
      ++c.rejection_lines_this_period;
      spdlog::warn("{}: block {} rejected ({}): {}", m.id, view.sequence, reason,
                   outcome.message.view());
    } else {
      ++c.rejection_lines_suppressed;
    }
    return;
  }
  const BlockResult& r = m.result;
  ++c.processed;
  MarkChanged(m, r.verdict.state);
  const std::uint64_t explained = std::min(r.sequence_gap, c.rejected_in_gap);
  c.rejected_in_gap = 0;
  if (r.sequence_gap > explained) {
    c.lost += r.sequence_gap - explained;
    spdlog::warn("{}: {} block(s) missing before block {}", m.id, r.sequence_gap - explained,
                 r.sequence);
  }
  if (r.sequence_restarted) {
    spdlog::info("{}: sequence restarted at block {} (publisher restart)", m.id, r.sequence);
  }
  FillDominantPath(m.id, r, *dominant_sample);
  FillSuspectedGear(m.id, r, *gear_sample);
  FillEnvelopeIndicators(m.id, r, *indicators_sample);
  const OmittedIndicators omitted =
      FillConditionIndicators(m.id, r, m.indicator_names, *condition_sample);
  if (omitted.any()) {
    // Counted always, said once per machine: the sample itself carries the counts.
    if (c.indicators_omitted == 0) {
      spdlog::warn("{}: block {}: ConditionIndicators exceeds the IDL bounds ({} sets > {}, "
                   "{} values > {} per set, {} names > {} chars): left out and counted "
                   "(sets_omitted, values_omitted); further blocks are counted silently",
                   m.id, r.sequence, omitted.sets, gearpath_MAX_INDICATOR_SETS, omitted.values,
                   gearpath_MAX_INDICATORS_PER_SET, omitted.names,
                   gearpath_INDICATOR_NAME_LENGTH);
    }
    c.indicators_omitted += omitted.sets + omitted.values + omitted.names;
  }
  if (publishing) {
    for (Status st : {dominant_writer.Write(*dominant_sample), gear_writer.Write(*gear_sample),
                      indicators_writer.Write(*indicators_sample),
                      condition_writer.Write(*condition_sample)}) {
      if (!st) {
        ++publish_failures;
        spdlog::error("{}: result of block {} not published: {}", m.id, r.sequence, st.error());
      }
    }
  } else {
    ++results_withheld;  // standing by: the primary publishes this block's results
  }
  c.last_alpha = r.regularisation.alpha_median;
  c.last_condition = r.regularisation.condition_max;
  c.last_residual = r.regularisation.relative_residual;
  if (info.source_timestamp > 0) {
    // Writer's timestamp to results published: includes the time the block waited in the
    // reader's history, which is what a late result costs the plant.
    c.latency_last_ms = std::max(0.0, static_cast<double>(RealtimeNs() - info.source_timestamp) *
                                          1e-6);
    c.latency_max_ms = std::max(c.latency_max_ms, c.latency_last_ms);
  }
  spdlog::debug("{}: block {} -> path {}, {} {}", m.id, r.sequence, r.dominant_path_name,
                ToString(r.verdict.state), r.verdict.gear_name);
}

void Gearpathd::Impl::DrainBlocks() {
  while (!stop_requested.load()) {
    auto taken = block_reader.Take(samples, infos);
    if (!taken) {
      spdlog::error("taking AccelBlocks failed: {}", taken.error());
      return;
    }
    if (*taken == 0) return;
    if (infos[0].valid_data) HandleBlock(*samples[0], infos[0]);
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
  } else {
    auto machines_built = BuildMachines(*config);
    if (!machines_built) {
      failure = machines_built.error();
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

int Gearpathd::Impl::Run(const SignalEvents& signals) {
  watchdog_period = duration_cast<Clock::duration>(SystemdWatchdogPeriod()) / 2;
  next_watchdog = Clock::now();
  state = gearpath_RUNNING;
  std::thread loop([this] { Loop(); });
  NotifySystemd(fmt::format("READY=1\nSTATUS=running: {} machine(s)",
                            lifecycle_config.machines.size()));
  spdlog::info("gearpathd \"{}\" running on DDS domain {}: {} machine(s), input topic \"{}\"",
               lifecycle_config.daemon_id, lifecycle_config.domain_id,
               lifecycle_config.machines.size(), lifecycle_config.topics.accel_block);
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
    auto impl = std::make_unique<Impl>(Generation{std::move(config), std::move(machines)},
                                       std::move(options), std::move(store));
    return std::unique_ptr<Gearpathd>(new Gearpathd(std::move(impl)));
  } catch (const std::exception& e) {
    return Error{fmt::format("DDS set-up failed: {}", e.what())};
  }
}

int Gearpathd::Run(const SignalEvents& signals) { return impl_->Run(signals); }

}  // namespace gearpath::daemon
