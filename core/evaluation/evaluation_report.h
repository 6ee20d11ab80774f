// Evaluation report: scenario outcomes aggregated per dimension (fault kind, gear, speed band,
// noise, family, train variant, channel set, disturbances), as text tables and as JSON.
//
// Two partitions are always kept apart: the TUNING families and the HELD-OUT families
// (parametric_plate; plant_family.h). Rates per group:
//   detection  = detected faulty scenarios / faulty scenarios,
//   right gear = faulty scenarios whose gear is right / faulty scenarios (not conditional on
//                detection: a missed fault has no right gear),
//   false alarms per healthy block = alarmed evaluation blocks of healthy scenarios / all
//                evaluation blocks of healthy scenarios,
//   first alarm = mean 1-based index of the first alarmed evaluation block, over the faulty
//                scenarios that alarmed at all,
//   flips = mean number of state changes within the evaluation blocks, over all scenarios,
//   learning = evaluation blocks still learning / all evaluation blocks (should be 0),
//   rev = the most reversals (changes to a less severe state) of any one scenario: the
//                diagnosis issue's "no verdict flips more than once in 5 blocks" bar,
//   regear = mean number of changes of the named gears (gear and candidates) from one
//                alarmed evaluation block to the next alarmed one, over faulty scenarios.
// Scenarios that failed to run are counted as errors and excluded from every rate.
// JSON schema: docs/evaluation.md.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "core/evaluation/evaluation_runner.h"

namespace gearpath {

struct AggregateRow {
  std::string label;
  int faulty = 0;
  int detected = 0;
  int right_gear = 0;
  int healthy = 0;
  int healthy_blocks = 0;
  int false_alarm_blocks = 0;
  int first_alarm_sum = 0;
  int first_alarm_count = 0;
  int flips_sum = 0;
  int reversals_sum = 0;
  int max_reversals = 0;  // the most reversals of any one scenario
  int gear_changes_sum = 0;  // faulty scenarios only
  int learning_blocks = 0;
  int blocks = 0;
  int scored = 0;
  int errors = 0;

  void Add(const ScenarioOutcome& outcome);
  double detection_rate() const {
    return faulty > 0 ? static_cast<double>(detected) / faulty : 0.0;
  }
  double right_gear_rate() const {
    return faulty > 0 ? static_cast<double>(right_gear) / faulty : 0.0;
  }
  double false_alarm_rate() const {
    return healthy_blocks > 0 ? static_cast<double>(false_alarm_blocks) / healthy_blocks : 0.0;
  }
  double mean_first_alarm() const {
    return first_alarm_count > 0 ? static_cast<double>(first_alarm_sum) / first_alarm_count : 0.0;
  }
  double mean_flips() const { return scored > 0 ? static_cast<double>(flips_sum) / scored : 0.0; }
  double mean_gear_changes() const {
    return faulty > 0 ? static_cast<double>(gear_changes_sum) / faulty : 0.0;
  }
  double learning_rate() const {
    return blocks > 0 ? static_cast<double>(learning_blocks) / blocks : 0.0;
  }
};

struct AggregateTable {
  std::string dimension;  // "fault", "gear", "speed_band", ...
  std::vector<AggregateRow> rows;
};

struct PartitionSummary {
  std::string name;  // "tuning" or "held_out"
  std::vector<std::string> families;
  AggregateRow overall;
  std::vector<AggregateTable> tables;
};

// Dimensions tabulated, in print order.
inline constexpr std::string_view kReportDimensions[] = {
    "fault", "gear",   "fault_gear", "speed_band", "speed_rpm",
    "noise", "family", "variant",    "channels",   "unmodelled"};

// The label of an outcome along a dimension (e.g. "te_pulse", "G3", "nominal", "5%").
std::string DimensionLabel(const Scenario& scenario, std::string_view dimension);

// Partitions (tuning, held_out) that have at least one scenario.
std::vector<PartitionSummary> Summarise(const std::vector<ScenarioOutcome>& outcomes);

std::string FormatSummary(const std::vector<PartitionSummary>& summary);

// The whole run as JSON (per-scenario outcomes with every verdict, plus the summary).
std::string ToJson(std::string_view matrix, const std::vector<ScenarioOutcome>& outcomes,
                   const std::vector<PartitionSummary>& summary);

}  // namespace gearpath
