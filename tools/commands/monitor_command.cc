// `gearpath monitor`: subscribes to the daemon's result and status topics and shows them.
//
// On a terminal it redraws one table per machine as results arrive; otherwise (or with --json)
// it prints one line per sample, JSON with --json, so scripts and tests can parse it. In the
// JSON, every field of contract version 2 (idl/gearpath.idl) is named exactly as in the IDL;
// the older ones keep their short names ("machine", "block", "gear", ...). It stops by
// itself after --count verdicts (SuspectedGear samples, one per processed block) or after
// --timeout seconds. Result topics are transient-local, so a monitor started late still gets
// each machine's latest results at once. A daemon whose Status stops arriving (killed, hung)
// is shown NOT RESPONDING (a DaemonSilent line); docs/tools.md lists every JSON key. Each
// machine's counters come from MachineHealth (one sample per daemon and machine per status
// period, every machine however many a daemon serves); from a daemon that publishes no
// MachineHealth (contract version 2) they come from Status, which lists at most 64 machines.
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

#include "idl/dds/domain.h"
#include "idl/dds/gearpath_topics.h"
#include "idl/dds/sequence.h"
#include "idl/dds/topic.h"
#include "idl/dds/waitset.h"
#include "tools/commands/commands.h"
#include "tools/common/cli_checks.h"
#include "tools/common/dds_options.h"

namespace gearpath::tools {
namespace {

using nlohmann::json;
using dds::GetString;
using dds::View;

struct MonitorOptions {
  int domain_id = 0;
  std::vector<std::string> machines;  // empty = all
  bool json_lines = false;
  int count = 0;           // stop after this many verdicts; 0 = never
  double timeout_s = 0.0;  // stop after this long; 0 = never
  bool status = true;      // also show the Status topic
  DdsOptions dds;
};

const char* StateName(gearpath_FaultState s) {
  switch (s) {
    case gearpath_NO_FAULT: return "no_fault";
    case gearpath_SUSPECTED: return "suspected";
    case gearpath_ALARM: return "alarm";
    case gearpath_LEARNING: return "learning";
  }
  return "unknown";
}

const char* CriterionName(gearpath_DominanceCriterion c) {
  switch (c) {
    case gearpath_CRITERION_BAND_ENERGY: return "band_energy";
    case gearpath_CRITERION_PEAK_AMPLITUDE: return "peak_amplitude";
    case gearpath_CRITERION_OTHER: return "other";
    case gearpath_CRITERION_SIDEBAND_ENERGY: return "sideband_energy";
    case gearpath_CRITERION_INDICATOR: return "indicator";
  }
  return "unknown";
}

const char* SignalSourceName(gearpath_SignalSource s) {
  switch (s) {
    case gearpath_SIGNAL_MEASURED: return "measured";
    case gearpath_SIGNAL_CONTRIBUTION: return "contribution";
    case gearpath_SIGNAL_FORCE: return "force";
  }
  return "unknown";
}

const char* DaemonStateName(gearpath_DaemonState s) {
  switch (s) {
    case gearpath_STARTING: return "starting";
    case gearpath_RUNNING: return "running";
    case gearpath_RELOADING: return "reloading";
    case gearpath_STOPPING: return "stopping";
    case gearpath_DEGRADED: return "degraded";
  }
  return "unknown";
}

const char* SpeedSourceName(gearpath_SpeedSource s) {
  switch (s) {
    case gearpath_SPEED_UNKNOWN: return "unknown";
    case gearpath_SPEED_ACQUISITION_TACHOMETER: return "acquisition";
    case gearpath_SPEED_OTHER: return "other";
  }
  return "unknown";
}

json ToJson(const gearpath_DominantPath& s) {
  json paths = json::array();
  for (const auto& p : View(s.paths)) {
    paths.push_back(
        {{"name", GetString(p.name)}, {"share", p.share}, {"criterion", p.criterion}});
  }
  return {{"topic", "DominantPath"},          {"machine", GetString(s.machine_id)},
          {"block", s.block_sequence},         {"t0_ns", s.block_t0_ns},
          {"path_index", s.path_index},        {"path", GetString(s.path_name)},
          {"band_hz", {s.band_lo_hz, s.band_hi_hz}}, {"criterion", CriterionName(s.criterion)},
          {"paths", paths}};
}

json ToJson(const gearpath_SuspectedGear& s) {
  json candidates = json::array();
  for (const auto& c : View(s.candidates)) candidates.push_back(GetString(c));
  return {{"topic", "SuspectedGear"},   {"machine", GetString(s.machine_id)},
          {"block", s.block_sequence},   {"t0_ns", s.block_t0_ns},
          {"state", StateName(s.state)}, {"gear", GetString(s.gear_name)},
          {"shaft", GetString(s.shaft_name)},
          {"characteristic_hz", s.characteristic_frequency_hz},
          {"confidence", s.confidence},  {"candidates", candidates},
          {"reason", GetString(s.reason)}};
}

json ToJson(const gearpath_EnvelopeIndicators& s) {
  json shafts = json::array();
  for (const auto& sh : View(s.shafts)) {
    shafts.push_back({{"shaft", GetString(sh.shaft_name)},
                      {"characteristic_hz", sh.characteristic_frequency_hz},
                      {"raw", sh.raw_indicator},
                      {"reconstructed", sh.reconstructed_indicator},
                      {"enhancement_percent", sh.enhancement_percent},
                      {"raw_threshold", sh.raw_threshold},
                      {"reconstructed_threshold", sh.reconstructed_threshold}});
  }
  return {{"topic", "EnvelopeIndicators"},
          {"machine", GetString(s.machine_id)},
          {"block", s.block_sequence},
          {"t0_ns", s.block_t0_ns},
          {"band",
           {{"centre_hz", s.band.centre_hz},
            {"width_hz", s.band.width_hz},
            {"level", s.band.level},
            {"kurtosis", s.band.kurtosis},
            {"significant", s.band.significant}}},
          {"speed_hz", s.speed_hz},
          {"speed_source", SpeedSourceName(s.speed_source)},
          {"shafts", shafts}};
}

json ToJson(const gearpath_ConditionIndicators& s) {
  json sets = json::array();
  for (const auto& set : View(s.sets)) {
    json values = json::array();
    for (const auto& v : View(set.values)) {
      values.push_back({{"name", GetString(v.name)}, {"value", v.value}, {"z", v.z}});
    }
    sets.push_back({{"source", SignalSourceName(set.source)},
                    {"signal", GetString(set.signal)},
                    {"shaft", GetString(set.shaft)},
                    {"shaft_hz", set.shaft_hz},
                    {"revolutions", set.revolutions},
                    {"score", set.score},
                    {"values", values}});
  }
  return {{"topic", "ConditionIndicators"},
          {"machine", GetString(s.machine_id)},
          {"block", s.block_sequence},
          {"t0_ns", s.block_t0_ns},
          {"limit_z", s.limit_z},
          {"clear_level", s.clear_level},
          {"score", s.score},
          {"top_indicator", GetString(s.top_indicator)},
          {"top_signal", GetString(s.top_signal)},
          {"top_shaft", GetString(s.top_shaft)},
          {"exceed_count", s.exceed_count},
          {"window", s.window},
          {"baseline_blocks_learned", s.baseline_blocks_learned},
          {"baseline_blocks_needed", s.baseline_blocks_needed},
          {"sets", sets},
          {"sets_omitted", s.sets_omitted},
          {"values_omitted", s.values_omitted}};
}

json ToJson(const gearpath_Status& s) {
  json machines = json::array();
  for (const auto& m : View(s.machines)) {
    machines.push_back({{"machine", GetString(m.machine_id)},
                        {"received", m.blocks_received},
                        {"processed", m.blocks_processed},
                        {"rejected", m.blocks_rejected},
                        {"last_rejection", GetString(m.last_rejection_reason)},
                        {"alpha", m.last_alpha},
                        {"condition_number", m.last_condition_number},
                        {"relative_residual", m.last_relative_residual},
                        {"latency_ms", m.latency_last_ms},
                        {"latency_max_ms", m.latency_max_ms}});
  }
  return {{"topic", "Status"},       {"daemon", GetString(s.daemon_id)},
          {"state", DaemonStateName(s.state)}, {"uptime_s", s.uptime_s},
          {"machines", machines}};
}

// The counters keep the names of a Status machine entry.
json ToJson(const gearpath_MachineHealth& s) {
  return {{"topic", "MachineHealth"},
          {"daemon", GetString(s.daemon_id)},
          {"machine", GetString(s.machine_id)},
          {"daemon_state", DaemonStateName(s.daemon_state)},
          {"timestamp_ns", s.timestamp_ns},
          {"index", s.machine_index},
          {"machine_count", s.machine_count},
          {"state", StateName(s.fault_state)},
          {"publishing_results", s.publishing_results},
          {"block", s.last_block_sequence},
          {"t0_ns", s.last_block_t0_ns},
          {"received", s.blocks_received},
          {"processed", s.blocks_processed},
          {"rejected", s.blocks_rejected},
          {"lost", s.blocks_lost},
          {"last_rejection", GetString(s.last_rejection_reason)},
          {"alpha", s.last_alpha},
          {"condition_number", s.last_condition_number},
          {"relative_residual", s.last_relative_residual},
          {"latency_ms", s.latency_last_ms},
          {"latency_max_ms", s.latency_max_ms}};
}

// The latest of each result topic per machine, for the terminal table.
using Clock = std::chrono::steady_clock;

struct MachineView {
  json dominant, gear, indicators, condition;
  Clock::time_point gear_received{};  // when the latest verdict arrived (its age on screen)
};

// What the monitor knows of one daemon: its latest Status and when Statuses arrive. A daemon
// that dies publishes nothing more, so its silence is the only sign: it is declared silent
// once no Status has arrived for 1.5 of its status periods (at least one period plus 0.25 s, so
// that a Status a little late on a loaded host is not taken for a death), so that a killed
// daemon is reported within two periods (issue 12). The period is the daemon's own: the
// interval between the timestamps of its consecutive Statuses (the median of the last five, so
// one late Status does not move it), 1 s (the daemon's default) until two have arrived. A
// daemon first heard of through MachineHealth (its first Status may arrive later, or never if
// it dies at once) is timed from that sample.
struct DaemonView {
  json status;
  std::map<std::string, json> health;  // latest MachineHealth per machine id (terminal)
  std::string health_state;            // daemon_state of its latest MachineHealth
  Clock::time_point last_seen{};
  std::int64_t last_timestamp_ns = 0;  // of its latest Status
  std::vector<double> intervals_s;     // the last five intervals between its Status timestamps
  bool silent = false;                 // reported silent, not heard since

  double PeriodS() const {
    if (intervals_s.empty()) return 1.0;
    std::vector<double> sorted = intervals_s;
    std::sort(sorted.begin(), sorted.end());
    return sorted[sorted.size() / 2];
  }
  double SilentAfter() const {
    const double p = PeriodS();
    return std::max(1.5 * p, p + 0.25);
  }
  // The state it last said: on its Status, else on its MachineHealth.
  std::string LastState() const {
    return status.is_object() ? status["state"].get<std::string>() : health_state;
  }
  void HeardOfThroughHealth(std::string daemon_state, Clock::time_point now) {
    if (last_seen == Clock::time_point{}) last_seen = now;
    health_state = std::move(daemon_state);
  }
  void Heard(json j, std::int64_t timestamp_ns, Clock::time_point now) {
    // A restarted daemon's clock, or a sample out of order, gives no interval.
    if (last_timestamp_ns > 0 && timestamp_ns > last_timestamp_ns) {
      const double interval = static_cast<double>(timestamp_ns - last_timestamp_ns) * 1e-9;
      if (interval <= 600.0) {
        intervals_s.push_back(interval);
        if (intervals_s.size() > 5) intervals_s.erase(intervals_s.begin());
      }
    }
    last_timestamp_ns = timestamp_ns;
    last_seen = now;
    status = std::move(j);
    silent = false;
  }
};

double SecondsSince(Clock::time_point t, Clock::time_point now) {
  return std::chrono::duration<double>(now - t).count();
}

// ANSI colour for a verdict state on a terminal: alarm red, suspected yellow.
std::string Highlighted(const std::string& state) {
  if (state == "alarm") return "\x1b[1;31mALARM\x1b[0m";
  if (state == "suspected") return "\x1b[1;33msuspected\x1b[0m";
  return state;
}

std::string Fixed(double v, int decimals) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  return buf;
}

// " (baseline 3/20)" from the ConditionIndicators sample of the same block as `verdict`; empty
// when that sample has not arrived (the topics arrive independently).
std::string BaselineProgress(const json& condition, const json& verdict) {
  if (condition.is_null() || condition["block"] != verdict["block"]) return "";
  return " (baseline " + condition["baseline_blocks_learned"].dump() + "/" +
         condition["baseline_blocks_needed"].dump() + ")";
}

// "score 0.42 of limit (z 6.1), 0/5 over the limit, top fm4 on B2x at output"; while learning
// "learning the healthy baseline, 3/20 blocks".
std::string ScoreText(const json& c) {
  const double limit = c["limit_z"].get<double>();
  if (!(limit > 0.0)) {
    return "learning the healthy baseline, " + c["baseline_blocks_learned"].dump() + "/" +
           c["baseline_blocks_needed"].dump() + " blocks";
  }
  std::string s = "score " + Fixed(c["score"].get<double>(), 2) + " of limit (z " +
                  Fixed(limit, 1) + "), " + c["exceed_count"].dump() + "/" +
                  c["window"].dump() + " over the limit";
  if (!c["top_indicator"].get<std::string>().empty()) {
    s += ", top " + c["top_indicator"].get<std::string>() + " on " +
         c["top_signal"].get<std::string>() + " at " + c["top_shaft"].get<std::string>();
  }
  const auto omitted = c["sets_omitted"].get<std::uint64_t>() +
                       c["values_omitted"].get<std::uint64_t>();
  if (omitted > 0) s += " (" + std::to_string(omitted) + " indicators over the IDL bounds)";
  return s;
}

void DrawTable(const std::map<std::string, MachineView>& machines,
               const std::map<std::string, DaemonView>& daemons) {
  const auto now = Clock::now();
  std::string out = "\x1b[H\x1b[2J";  // home + clear: redraw in place
  out += "gearpath monitor  (Ctrl-C to stop)\n\n";
  for (const auto& [id, v] : machines) {
    out += "machine " + id + "\n";
    if (!v.gear.is_null()) {
      out += "  verdict    block " + v.gear["block"].dump() + " (" +
             Fixed(SecondsSince(v.gear_received, now), 0) + " s ago): " +
             Highlighted(v.gear["state"].get<std::string>());
      if (v.gear["state"] == "learning") out += BaselineProgress(v.condition, v.gear);
      if (!v.gear["gear"].get<std::string>().empty()) {
        out += "  gear " + v.gear["gear"].get<std::string>() + " on " +
               v.gear["shaft"].get<std::string>() + " shaft at " +
               Fixed(v.gear["characteristic_hz"].get<double>(), 2) + " Hz, confidence " +
               Fixed(v.gear["confidence"].get<double>(), 2);
      }
      out += "\n  reason     " + v.gear["reason"].get<std::string>() + "\n";
    }
    if (!v.condition.is_null()) out += "  score      " + ScoreText(v.condition) + "\n";
    if (!v.dominant.is_null()) {
      out += "  dominant   " + v.dominant["path"].get<std::string>() + "   shares:";
      for (const auto& p : v.dominant["paths"]) {
        out += " " + p["name"].get<std::string>() + " " +
               Fixed(100.0 * p["share"].get<double>(), 1) + "%";
      }
      out += "\n";
    }
    if (!v.indicators.is_null()) {
      const auto& b = v.indicators["band"];
      out += "  envelope   band " + Fixed(b["centre_hz"].get<double>(), 0) + " Hz +/- " +
             Fixed(b["width_hz"].get<double>() / 2, 0) + " Hz, kurtosis " +
             Fixed(b["kurtosis"].get<double>(), 2) +
             (b["significant"].get<bool>() ? "" : " (not significant)") + "\n";
      out += "  shaft            f [Hz]      raw (thr.)         recon. (thr.)     recon./raw\n";
      for (const auto& s : v.indicators["shafts"]) {
        char line[200];
        std::snprintf(line, sizeof line, "  %-14s %8.2f %8.3f (%7.3f) %8.3f (%7.3f) %8.0f %%\n",
                      s["shaft"].get<std::string>().c_str(),
                      s["characteristic_hz"].get<double>(), s["raw"].get<double>(),
                      s["raw_threshold"].get<double>(), s["reconstructed"].get<double>(),
                      s["reconstructed_threshold"].get<double>(),
                      s["enhancement_percent"].get<double>());
        out += line;
      }
    }
    out += "\n";
  }
  for (const auto& [daemon, d] : daemons) {
    const json& status = d.status;
    const double age = SecondsSince(d.last_seen, now);
    out += "daemon " + daemon + ": ";
    if (d.silent) {
      out += "\x1b[1;31mNOT RESPONDING\x1b[0m (no Status for " + Fixed(age, 0) +
             " s; last said " + d.LastState() + ")\n";
    } else if (!status.is_object()) {
      out += d.LastState() + ", no Status yet\n";
    } else {
      out += status["state"].get<std::string>() + ", up " +
             Fixed(status["uptime_s"].get<double>(), 0) + " s, Status " + Fixed(age, 1) +
             " s ago\n";
    }
    // Every machine from MachineHealth; Status (its first 64) from an older daemon.
    std::vector<const json*> rows;
    for (const auto& [machine, m] : d.health) rows.push_back(&m);
    std::stable_sort(rows.begin(), rows.end(), [](const json* a, const json* b) {
      return (*a)["index"].get<std::uint64_t>() < (*b)["index"].get<std::uint64_t>();
    });
    if (rows.empty() && status.is_object()) {
      for (const auto& m : status["machines"]) rows.push_back(&m);
    }
    for (const json* row : rows) {
      const json& m = *row;
      out += "  " + m["machine"].get<std::string>() + ": ";
      if (m.contains("state")) out += Highlighted(m["state"].get<std::string>()) + ", ";
      out += "received " + m["received"].dump() + ", processed " + m["processed"].dump() +
             ", rejected " + m["rejected"].dump();
      if (m.contains("lost") && m["lost"].get<std::uint64_t>() > 0) {
        out += ", lost " + m["lost"].dump();
      }
      if (!m["last_rejection"].get<std::string>().empty()) {
        out += " (last: " + m["last_rejection"].get<std::string>() + ")";
      }
      out += ", latency " + Fixed(m["latency_ms"].get<double>(), 1) + " ms\n";
    }
  }
  std::fputs(out.c_str(), stdout);
  std::fflush(stdout);
}

// Plain one-line summary of a sample for non-terminal output without --json. `condition` is
// the machine's latest ConditionIndicators (null if none yet), for the baseline progress.
std::string PlainLine(const json& j, const json& condition) {
  const std::string topic = j["topic"];
  if (topic == "ConditionIndicators") {
    return "score     " + j["machine"].get<std::string>() + " block " + j["block"].dump() +
           ": " + ScoreText(j);
  }
  if (topic == "SuspectedGear") {
    std::string s = "verdict   " + j["machine"].get<std::string>() + " block " +
                    j["block"].dump() + ": " + j["state"].get<std::string>();
    if (j["state"] == "learning") s += BaselineProgress(condition, j);
    if (!j["gear"].get<std::string>().empty()) {
      s += " " + j["gear"].get<std::string>() + " (" + j["shaft"].get<std::string>() + ", " +
           Fixed(j["characteristic_hz"].get<double>(), 2) + " Hz, confidence " +
           Fixed(j["confidence"].get<double>(), 2) + ")";
    }
    return s + " - " + j["reason"].get<std::string>();
  }
  if (topic == "DominantPath") {
    return "dominant  " + j["machine"].get<std::string>() + " block " + j["block"].dump() +
           ": " + j["path"].get<std::string>();
  }
  if (topic == "EnvelopeIndicators") {
    std::string s = "envelope  " + j["machine"].get<std::string>() + " block " +
                    j["block"].dump() + ":";
    for (const auto& sh : j["shafts"]) {
      s += " " + sh["shaft"].get<std::string>() + " raw " + Fixed(sh["raw"].get<double>(), 3) +
           " recon " + Fixed(sh["reconstructed"].get<double>(), 3) + " (" +
           Fixed(sh["enhancement_percent"].get<double>(), 0) + " %)";
    }
    return s;
  }
  if (topic == "MachineHealth") {
    std::string s = "health    " + j["machine"].get<std::string>() + " (daemon " +
                    j["daemon"].get<std::string>() + ", " +
                    j["daemon_state"].get<std::string>() + "): " +
                    j["state"].get<std::string>() + ", received " + j["received"].dump() +
                    ", processed " + j["processed"].dump() + ", rejected " +
                    j["rejected"].dump() + ", lost " + j["lost"].dump() + ", latency " +
                    Fixed(j["latency_ms"].get<double>(), 1) + " ms";
    if (!j["last_rejection"].get<std::string>().empty()) {
      s += " (last rejection: " + j["last_rejection"].get<std::string>() + ")";
    }
    return s;
  }
  return "status    " + j.dump();
}

template <typename T>
struct Subscription {
  Subscription(const dds::Participant& participant, dds::WaitSet& waitset, dds_attach_t token,
               std::size_t batch = 16)
      : topic(participant), reader(topic), condition(reader), samples(batch), infos(batch) {
    waitset.Attach(condition, token);
  }
  dds::Topic<T> topic;
  dds::Reader<T> reader;
  dds::ReadCondition condition;
  std::vector<dds::Owned<T>> samples;
  std::vector<dds::SampleInfo> infos;
};

int RunMonitor(const MonitorOptions& opt) {
  const std::set<std::string> wanted(opt.machines.begin(), opt.machines.end());
  const bool terminal = !opt.json_lines && isatty(STDOUT_FILENO);

  dds::Domain domain(opt.domain_id, ToolDomainConfig(opt.dds));
  dds::Participant participant(domain, ToolSecurityFiles(opt.dds));
  dds::WaitSet waitset(participant);
  Subscription<gearpath_DominantPath> dominant(participant, waitset, 1);
  Subscription<gearpath_SuspectedGear> gear(participant, waitset, 2);
  Subscription<gearpath_EnvelopeIndicators> indicators(participant, waitset, 3);
  Subscription<gearpath_Status> status(participant, waitset, 4);
  Subscription<gearpath_ConditionIndicators> condition(participant, waitset, 5);
  // One sample per machine per status period: taken in larger batches.
  Subscription<gearpath_MachineHealth> health(participant, waitset, 6, 128);

  std::map<std::string, MachineView> table;
  std::map<std::string, DaemonView> daemons;
  int verdicts = 0;
  const auto start = std::chrono::steady_clock::now();

  auto emit = [&](json j, const std::string& machine, json MachineView::*slot) {
    if (!wanted.empty() && !machine.empty() && !wanted.count(machine)) return;
    if (terminal) {
      if (slot == &MachineView::gear) table[machine].gear_received = Clock::now();
      if (slot != nullptr) table[machine].*slot = std::move(j);
      DrawTable(table, daemons);
    } else {
      static const json kNone;
      const json& latest = machine.empty() ? kNone : table[machine].condition;
      std::puts(opt.json_lines ? j.dump().c_str() : PlainLine(j, latest).c_str());
      std::fflush(stdout);
      // Plain lines keep only the latest scores (for the baseline progress of verdicts).
      if (slot == &MachineView::condition) table[machine].condition = std::move(j);
    }
  };
  auto drain = [&](auto& sub, auto on_sample) -> bool {
    auto taken = sub.reader.Take(sub.samples, sub.infos);
    if (!taken) {
      std::fprintf(stderr, "gearpath monitor: %s\n", taken.error().c_str());
      return false;
    }
    for (std::size_t i = 0; i < *taken; ++i) {
      if (sub.infos[i].valid_data) on_sample(*sub.samples[i]);
    }
    return true;
  };

  std::vector<dds_attach_t> triggered(8);
  for (;;) {
    std::chrono::nanoseconds wait = std::chrono::milliseconds(500);
    // Awake when a daemon's silence becomes due, not up to half a second later.
    const auto now = Clock::now();
    for (const auto& [id, d] : daemons) {
      if (d.last_seen == Clock::time_point{} || d.silent) continue;
      const auto due = d.last_seen + std::chrono::duration_cast<Clock::duration>(
                                         std::chrono::duration<double>(d.SilentAfter()));
      wait = std::clamp(std::chrono::duration_cast<std::chrono::nanoseconds>(due - now),
                        std::chrono::nanoseconds(std::chrono::milliseconds(1)), wait);
    }
    if (opt.timeout_s > 0) {
      const auto left = start + std::chrono::duration<double>(opt.timeout_s) -
                        std::chrono::steady_clock::now();
      if (left <= std::chrono::nanoseconds::zero()) {
        if (opt.count > 0) {
          std::fprintf(stderr, "gearpath monitor: timed out after %.1f s with %d of %d verdicts\n",
                       opt.timeout_s, verdicts, opt.count);
          return kExitFailure;
        }
        return kExitOk;
      }
      wait = std::min(wait, std::chrono::duration_cast<std::chrono::nanoseconds>(left));
    }
    auto woke = waitset.Wait(triggered, wait);
    if (!woke) {
      std::fprintf(stderr, "gearpath monitor: %s\n", woke.error().c_str());
      return kExitFailure;
    }
    bool ok = drain(dominant, [&](const auto& s) {
      emit(ToJson(s), std::string(GetString(s.machine_id)), &MachineView::dominant);
    });
    ok = ok && drain(indicators, [&](const auto& s) {
      emit(ToJson(s), std::string(GetString(s.machine_id)), &MachineView::indicators);
    });
    // Before the verdicts, so that a verdict line can show the same block's baseline progress.
    ok = ok && drain(condition, [&](const auto& s) {
      emit(ToJson(s), std::string(GetString(s.machine_id)), &MachineView::condition);
    });
    ok = ok && drain(gear, [&](const auto& s) {
      const std::string machine(GetString(s.machine_id));
      if (!wanted.empty() && !wanted.count(machine)) return;
      emit(ToJson(s), machine, &MachineView::gear);
      ++verdicts;
    });
    ok = ok && drain(status, [&](const auto& s) {
      if (!opt.status) return;
      json j = ToJson(s);
      daemons[std::string(GetString(s.daemon_id))].Heard(j, s.timestamp_ns, Clock::now());
      emit(std::move(j), "", nullptr);
    });
    // MachineHealth: kept per daemon for the table (drawn once per round, not per sample:
    // a daemon sends one per machine per period), printed as lines otherwise.
    // A disposed instance (the daemon no longer serves that machine) leaves the table.
    bool health_changed = false;
    if (ok) {
      auto taken = health.reader.Take(health.samples, health.infos);
      if (!taken) {
        std::fprintf(stderr, "gearpath monitor: %s\n", taken.error().c_str());
        return kExitFailure;
      }
      for (std::size_t i = 0; i < *taken && opt.status; ++i) {
        const gearpath_MachineHealth& s = *health.samples[i];
        const std::string machine(GetString(s.machine_id));
        const std::string daemon(GetString(s.daemon_id));
        // Disposed: on an invalid sample carrying the key, or on the last sample if unread.
        const bool disposed =
            health.infos[i].instance_state == DDS_NOT_ALIVE_DISPOSED_INSTANCE_STATE;
        if (disposed && terminal && daemons.count(daemon) > 0) {
          health_changed = daemons[daemon].health.erase(machine) > 0 || health_changed;
        }
        if (!health.infos[i].valid_data) continue;
        // Whichever machine it is about, the sample says the daemon is alive (as Status does).
        daemons[daemon].HeardOfThroughHealth(DaemonStateName(s.daemon_state), Clock::now());
        if (!wanted.empty() && !wanted.count(machine)) continue;
        json j = ToJson(s);
        if (terminal) {
          if (!disposed) daemons[daemon].health[machine] = std::move(j);
          health_changed = true;
        } else {
          std::puts(opt.json_lines ? j.dump().c_str() : PlainLine(j, json()).c_str());
          std::fflush(stdout);
        }
      }
    }
    if (!ok) return kExitFailure;
    if (health_changed) DrawTable(table, daemons);
    // A daemon that stopped talking without saying STOPPING: killed, hung or cut off.
    for (auto& [id, d] : daemons) {
      if (d.last_seen == Clock::time_point{}) continue;
      const double age = SecondsSince(d.last_seen, Clock::now());
      const std::string last_state = d.LastState();
      if (d.silent || last_state == "stopping" || age < d.SilentAfter()) continue;
      d.silent = true;
      json j = {{"topic", "DaemonSilent"},
                {"daemon", id},
                {"silent_s", age},
                {"last_state", last_state}};
      if (terminal) {
        DrawTable(table, daemons);
      } else {
        std::puts(opt.json_lines ? j.dump().c_str()
                                 : ("status    daemon " + id + " NOT RESPONDING: no Status for " +
                                    Fixed(age, 1) + " s (last said " + last_state + ")")
                                       .c_str());
        std::fflush(stdout);
      }
    }
    if (opt.count > 0 && verdicts >= opt.count) return kExitOk;
  }
}

}  // namespace

void AddMonitorCommand(CLI::App& app, int& exit_code) {
  auto opt = std::make_shared<MonitorOptions>();
  CLI::App* cmd = app.add_subcommand(
      "monitor", "Show the daemon's fault topics (dominant path, suspected gear, envelope "
                 "and condition indicators with the block score) and its status, live; "
                 "loopback DDS unless --dds-config or CYCLONEDDS_URI says otherwise");
  cmd->add_option("--domain", opt->domain_id, "DDS domain id")->capture_default_str()
      ->check(CLI::Range(0, 232));
  cmd->add_option("--machine", opt->machines, "Only these machine ids (repeatable)");
  cmd->add_flag("--json", opt->json_lines, "One JSON object per line (for scripts)");
  cmd->add_option("--count", opt->count,
                  "Stop after this many verdicts (SuspectedGear samples); 0 = never")
      ->check(NonNegative());
  cmd->add_option("--timeout", opt->timeout_s,
                  "Stop after this many seconds; with --count, exit 1 if it was not reached")
      ->check(NonNegative());
  cmd->add_flag("!--no-status", opt->status, "Do not show the Status topic");
  AddDdsOptions(cmd, &opt->dds);
  cmd->callback([opt, &exit_code] {
    try {
      exit_code = RunMonitor(*opt);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "gearpath monitor: %s\n", e.what());
      exit_code = kExitFailure;
    }
  });
}

}  // namespace gearpath::tools
