// One scenario of the evaluation matrix by its coordinates, seeded as the matrix seeds it
// (ScenarioSeed of its key), so a test runs exactly the scenario `gearpath evaluate` runs.
#pragma once

#include <gtest/gtest.h>

#include <string>

#include "core/evaluation/evaluation_runner.h"
#include "core/evaluation/scenario_matrix.h"

namespace gearpath::testing {

inline Scenario ScenarioOf(PlantFamily family, TrainVariant variant, PlantFaultKind fault,
                           const std::string& gear, double input_rpm, double noise,
                           ChannelSet channels, bool unmodelled) {
  Scenario s;
  s.family = family;
  s.variant = variant;
  s.fault = fault;
  s.gear = gear;
  s.input_rpm = input_rpm;
  s.noise = noise;
  s.channels = channels;
  s.unmodelled = unmodelled;
  s.seed = ScenarioSeed(s.Key());
  return s;
}

// Runs a faulty scenario that must be detected; its gear is the caller's to check.
inline ScenarioOutcome RunExpectingDetection(const Scenario& s,
                                             const RunnerOptions& options = {}) {
  ScenarioOutcome out = RunScenario(s, options);
  EXPECT_TRUE(out.error.empty()) << out.error;
  EXPECT_TRUE(out.score.detected);
  return out;
}

// Runs a faulty scenario that must be detected and put on its gear.
inline ScenarioOutcome RunExpectingRightGear(const Scenario& s,
                                             const RunnerOptions& options = {}) {
  ScenarioOutcome out = RunExpectingDetection(s, options);
  EXPECT_TRUE(out.score.right_gear);
  return out;
}

// How many blocks of `out` are alarmed (suspected or alarm), and how many of those name `shaft`.
struct NamedShaftBlocks {
  int alarmed = 0;
  int naming = 0;
};
inline NamedShaftBlocks CountNamedShaft(const ScenarioOutcome& out, const std::string& shaft) {
  NamedShaftBlocks n;
  for (const BlockVerdictRecord& v : out.verdicts) {
    if (v.state != FaultState::kSuspected && v.state != FaultState::kAlarm) continue;
    ++n.alarmed;
    n.naming += v.shaft == shaft ? 1 : 0;
  }
  return n;
}

}  // namespace gearpath::testing
