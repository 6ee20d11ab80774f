// A machine of the evaluation families for the order-tracking tests: the Table-1 lumped plant
// at 600 r/min with 2 % noise, its simulator (optionally with +/- 0.3 % speed drift within
// each block and a fault), and a BlockProcessor given the plant's model FRFs.
#pragma once

#include <gtest/gtest.h>

#include <string>
#include <utility>

#include "core/diagnosis/train_layout.h"
#include "core/evaluation/plant_excitation.h"
#include "core/evaluation/plant_family.h"
#include "core/evaluation/plant_simulator.h"
#include "core/pipeline/block_processor.h"

namespace gearpath::testing {

struct DriftingMachine {
  PlantSimulator sim;
  BlockProcessor processor;
};

// options: the analysis options to run with (sample_rate_hz is set to the simulator's);
// drift_relative: the drift's amplitude when `drift`.
inline DriftingMachine MakeDriftingMachine(bool drift, AnalysisOptions options,
                                           PlantFaultKind fault = PlantFaultKind::kNone,
                                           const std::string& gear = "",
                                           double drift_relative = 0.003) {
  Result<Plant> plant = MakePlant({PlantFamily::kLumpedPerturbed, TrainVariant::kTable1,
                                   ChannelSet::kSeats, 11});
  EXPECT_TRUE(plant.ok()) << plant.error();
  PlantExcitationConfig ex;
  ex.fault = fault;
  ex.faulty_gear = gear;
  ex.seed = 11;
  Result<PlantExcitation> excitation = PlantExcitation::Create(plant->train, ex);
  EXPECT_TRUE(excitation.ok()) << excitation.error();
  PlantSimulatorConfig sc;
  sc.machine_id = "drift";
  sc.input_speed_hz = 10.0;
  sc.noise_relative = 0.02;
  sc.speed_drift = drift;
  sc.drift_relative = drift_relative;
  sc.seed = 11;
  Result<PlantSimulator> sim =
      PlantSimulator::Create(plant->dynamics, plant->channels, std::move(excitation).value(), sc);
  EXPECT_TRUE(sim.ok()) << sim.error();
  MachineSetup setup;
  setup.machine_id = "drift";
  setup.frf_set = plant->model_frf;
  setup.train = TrainLayoutFromGearTrain(plant->train).value();
  setup.options = std::move(options);
  setup.options.sample_rate_hz = sc.sample_rate_hz;
  Result<BlockProcessor> processor = BlockProcessor::Create(std::move(setup));
  EXPECT_TRUE(processor.ok()) << processor.error();
  return {std::move(sim).value(), std::move(processor).value()};
}

}  // namespace gearpath::testing
