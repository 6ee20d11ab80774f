// One scenario of the evaluation matrix by its coordinates, seeded as the matrix seeds it
// (ScenarioSeed of its key), so a test runs exactly the scenario `gearpath evaluate` runs.
#pragma once

#include <string>

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

}  // namespace gearpath::testing
