#include "core/evaluation/evaluation_report.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <nlohmann/json.hpp>

namespace gearpath {
namespace {

std::string Percent(double v) { return fmt::format("{:.1f}%", 100.0 * v); }

// Sort key of a label so that tables read in a natural order.
std::string OrderKey(std::string_view dimension, const std::string& label) {
  if (dimension == "fault") {
    for (std::size_t i = 0; i < std::size(kAllPlantFaultKinds); ++i) {
      if (label == PlantFaultKindName(kAllPlantFaultKinds[i])) return fmt::format("{:02}", i);
    }
  }
  if (dimension == "speed_band") {
    if (label == "below") return "0";
    if (label == "nominal") return "1";
    return "2";
  }
  if (dimension == "speed_rpm" || dimension == "noise") {
    return fmt::format("{:08.2f}", std::atof(label.c_str()));
  }
  return label;
}

PartitionSummary SummarisePartition(const std::string& name,
                                    const std::vector<const ScenarioOutcome*>& outcomes) {
  PartitionSummary p;
  p.name = name;
  p.overall.label = "all";
  for (const ScenarioOutcome* o : outcomes) {
    p.overall.Add(*o);
    const std::string family(PlantFamilyName(o->scenario.family));
    if (std::find(p.families.begin(), p.families.end(), family) == p.families.end()) {
      p.families.push_back(family);
    }
  }
  for (std::string_view dim : kReportDimensions) {
    std::map<std::string, AggregateRow> rows;
    for (const ScenarioOutcome* o : outcomes) {
      const std::string label = DimensionLabel(o->scenario, dim);
      AggregateRow& row = rows[OrderKey(dim, label) + "\x1f" + label];
      row.label = label;
      row.Add(*o);
    }
    AggregateTable table;
    table.dimension = std::string(dim);
    for (auto& [key, row] : rows) table.rows.push_back(std::move(row));
    p.tables.push_back(std::move(table));
  }
  return p;
}

void FormatRow(std::string& out, const AggregateRow& r) {
  const std::string detect = r.faulty > 0 ? Percent(r.detection_rate()) : "-";
  const std::string right = r.faulty > 0 ? Percent(r.right_gear_rate()) : "-";
  const std::string fa = r.healthy_blocks > 0 ? Percent(r.false_alarm_rate()) : "-";
  const std::string first =
      r.first_alarm_count > 0 ? fmt::format("{:.2f}", r.mean_first_alarm()) : "-";
  const std::string flips = r.scored > 0 ? fmt::format("{:.2f}", r.mean_flips()) : "-";
  const std::string learning = r.blocks > 0 ? Percent(r.learning_rate()) : "-";
  const std::string reversals = r.scored > 0 ? fmt::format("{}", r.max_reversals) : "-";
  const std::string regear = r.faulty > 0 ? fmt::format("{:.2f}", r.mean_gear_changes()) : "-";
  out += fmt::format("  {:<22} {:>6} {:>6} {:>8} {:>8} {:>8} {:>6} {:>6} {:>7} {:>5} {:>6}",
                     r.label, r.faulty, r.healthy, detect, right, fa, first, flips, learning,
                     reversals, regear);
  if (r.errors > 0) out += fmt::format("  ({} errors)", r.errors);
  out += "\n";
}

nlohmann::json RowJson(const AggregateRow& r) {
  return {{"label", r.label},
          {"faulty_scenarios", r.faulty},
          {"healthy_scenarios", r.healthy},
          {"detected", r.detected},
          {"right_gear", r.right_gear},
          {"detection_rate", r.detection_rate()},
          {"right_gear_rate", r.right_gear_rate()},
          {"healthy_blocks", r.healthy_blocks},
          {"false_alarm_blocks", r.false_alarm_blocks},
          {"false_alarm_rate_per_block", r.false_alarm_rate()},
          {"mean_first_alarm_block", r.mean_first_alarm()},
          {"mean_flips", r.mean_flips()},
          {"reversals", r.reversals_sum},
          {"max_reversals_per_scenario", r.max_reversals},
          {"gear_changes", r.gear_changes_sum},
          {"mean_gear_changes_per_faulty_scenario", r.mean_gear_changes()},
          {"learning_blocks", r.learning_blocks},
          {"evaluation_blocks", r.blocks},
          {"errors", r.errors}};
}

}  // namespace

void AggregateRow::Add(const ScenarioOutcome& o) {
  if (!o.error.empty()) {
    ++errors;
    return;
  }
  const ScenarioScore& s = o.score;
  ++scored;
  flips_sum += s.flips;
  reversals_sum += s.reversals;
  max_reversals = std::max(max_reversals, s.reversals);
  blocks += s.blocks;
  learning_blocks += s.learning_blocks;
  if (s.faulty) {
    ++faulty;
    gear_changes_sum += s.gear_changes;
    detected += s.detected ? 1 : 0;
    right_gear += s.right_gear ? 1 : 0;
    if (s.first_alarm_block > 0) {
      first_alarm_sum += s.first_alarm_block;
      ++first_alarm_count;
    }
  } else {
    ++healthy;
    healthy_blocks += s.blocks;
    false_alarm_blocks += s.false_alarm_blocks;
  }
}

std::string DimensionLabel(const Scenario& s, std::string_view dimension) {
  if (dimension == "fault") return std::string(PlantFaultKindName(s.fault));
  if (dimension == "gear") return s.gear.empty() ? "healthy" : s.gear;
  if (dimension == "fault_gear") {
    return s.gear.empty() ? "none" : fmt::format("{} {}", PlantFaultKindName(s.fault), s.gear);
  }
  if (dimension == "speed_band") return std::string(SpeedBand(s.input_rpm));
  if (dimension == "speed_rpm") return fmt::format("{}", std::lround(s.input_rpm));
  if (dimension == "noise") return fmt::format("{}%", std::lround(s.noise * 100.0));
  if (dimension == "family") return std::string(PlantFamilyName(s.family));
  if (dimension == "variant") return std::string(TrainVariantName(s.variant));
  if (dimension == "channels") return std::string(ChannelSetName(s.channels));
  if (dimension == "unmodelled") return s.unmodelled ? "on" : "off";
  return "?";
}

std::vector<PartitionSummary> Summarise(const std::vector<ScenarioOutcome>& outcomes) {
  std::vector<const ScenarioOutcome*> tuning, held_out;
  for (const ScenarioOutcome& o : outcomes) {
    (o.scenario.held_out() ? held_out : tuning).push_back(&o);
  }
  std::vector<PartitionSummary> out;
  if (!tuning.empty()) out.push_back(SummarisePartition("tuning", tuning));
  if (!held_out.empty()) out.push_back(SummarisePartition("held_out", held_out));
  return out;
}

std::string FormatSummary(const std::vector<PartitionSummary>& summary) {
  std::string out;
  for (const PartitionSummary& p : summary) {
    std::string families;
    for (const std::string& f : p.families) families += (families.empty() ? "" : ", ") + f;
    out += fmt::format("== {} families: {} ({} scenarios: {} faulty, {} healthy{}) ==\n",
                       p.name == "held_out" ? "HELD-OUT" : "tuning", families,
                       p.overall.scored + p.overall.errors, p.overall.faulty, p.overall.healthy,
                       p.overall.errors > 0 ? fmt::format(", {} errors", p.overall.errors) : "");
    out += fmt::format("  {:<22} {:>6} {:>6} {:>8} {:>8} {:>8} {:>6} {:>6} {:>7} {:>5} {:>6}\n",
                       "group", "faulty", "health", "detect", "right", "FA/blk", "first", "flips",
                       "learn", "rev", "regear");
    FormatRow(out, p.overall);
    for (const AggregateTable& t : p.tables) {
      out += fmt::format("-- by {}\n", t.dimension);
      for (const AggregateRow& r : t.rows) FormatRow(out, r);
    }
    out += "\n";
  }
  return out;
}

std::string ToJson(std::string_view matrix, const std::vector<ScenarioOutcome>& outcomes,
                   const std::vector<PartitionSummary>& summary) {
  nlohmann::json root;
  root["schema"] = "gearpath-evaluation/1";
  root["matrix"] = std::string(matrix);
  root["baseline_blocks"] = kBaselineBlocks;
  root["evaluation_blocks"] = kEvaluationBlocks;
  nlohmann::json partitions = nlohmann::json::object();
  for (const PartitionSummary& p : summary) {
    nlohmann::json part;
    part["families"] = p.families;
    part["overall"] = RowJson(p.overall);
    nlohmann::json tables = nlohmann::json::object();
    for (const AggregateTable& t : p.tables) {
      nlohmann::json rows = nlohmann::json::array();
      for (const AggregateRow& r : t.rows) rows.push_back(RowJson(r));
      tables[t.dimension] = std::move(rows);
    }
    part["by"] = std::move(tables);
    partitions[p.name] = std::move(part);
  }
  root["summary"] = std::move(partitions);
  nlohmann::json scenarios = nlohmann::json::array();
  for (const ScenarioOutcome& o : outcomes) {
    const Scenario& s = o.scenario;
    nlohmann::json j;
    j["index"] = s.index;
    j["key"] = s.Key();
    j["seed"] = s.seed;
    j["family"] = std::string(PlantFamilyName(s.family));
    j["held_out"] = s.held_out();
    j["variant"] = std::string(TrainVariantName(s.variant));
    j["fault"] = std::string(PlantFaultKindName(s.fault));
    j["gear"] = s.gear;
    j["replica"] = s.replica;
    j["input_rpm"] = s.input_rpm;
    j["speed_band"] = std::string(SpeedBand(s.input_rpm));
    j["noise"] = s.noise;
    j["channels"] = std::string(ChannelSetName(s.channels));
    j["unmodelled"] = s.unmodelled;
    j["seconds"] = o.seconds;
    if (s.fault != PlantFaultKind::kNone) {
      j["severity"] = {{"scale", o.severity_scale},
                       {"pulse_depth_m", o.severity.pulse_depth_m},
                       {"am_depth", o.severity.am_depth},
                       {"dip_depth_m", o.severity.dip_depth_m},
                       {"rms_change", o.rms_change}};
    }
    if (!o.error.empty()) {
      j["error"] = o.error;
    } else {
      nlohmann::json verdicts = nlohmann::json::array();
      for (const BlockVerdictRecord& v : o.verdicts) {
        verdicts.push_back({{"state", std::string(ToString(v.state))},
                            {"gear", v.gear},
                            {"candidates", v.candidates},
                            {"shaft", v.shaft}});
      }
      j["verdicts"] = std::move(verdicts);
      const ScenarioScore& sc = o.score;
      j["score"] = {{"faulty", sc.faulty},
                    {"alarmed_blocks", sc.alarmed_blocks},
                    {"learning_blocks", sc.learning_blocks},
                    {"right_gear_blocks", sc.right_gear_blocks},
                    {"detected", sc.detected},
                    {"right_gear", sc.right_gear},
                    {"first_alarm_block", sc.first_alarm_block},
                    {"flips", sc.flips},
                    {"reversals", sc.reversals},
                    {"gear_changes", sc.gear_changes},
                    {"false_alarm_blocks", sc.false_alarm_blocks}};
    }
    scenarios.push_back(std::move(j));
  }
  root["scenarios"] = std::move(scenarios);
  return root.dump(1);
}

}  // namespace gearpath
