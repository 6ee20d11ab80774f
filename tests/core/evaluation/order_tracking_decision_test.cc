// The per-machine order-tracking decision (condition_indicator_stage.h) on a plant of the
// evaluation families: a machine whose speed drifts within each block is tracked, one at
// constant speed is not, the decision is kept in the learned state, and a machine with order
// tracking off never decides; localisation tracking alone decides the same way.
#include <gtest/gtest.h>

#include <utility>

#include "core/diagnosis/train_layout.h"
#include "core/evaluation/plant_excitation.h"
#include "core/evaluation/plant_family.h"
#include "core/evaluation/plant_simulator.h"
#include "core/pipeline/block_processor.h"

namespace gearpath {
namespace {

struct Machine {
  PlantSimulator sim;
  BlockProcessor processor;
};

// A healthy Table-1 lumped plant at 600 r/min, 2 % noise, with or without +/- 0.3 % drift.
Machine MakeMachine(bool drift, bool order_tracking, bool localisation_tracking = false) {
  Result<Plant> plant = MakePlant({PlantFamily::kLumpedPerturbed, TrainVariant::kTable1,
                                   ChannelSet::kSeats, 11});
  EXPECT_TRUE(plant.ok()) << plant.error();
  PlantExcitationConfig ex;
  ex.seed = 11;
  Result<PlantExcitation> excitation = PlantExcitation::Create(plant->train, ex);
  EXPECT_TRUE(excitation.ok()) << excitation.error();
  PlantSimulatorConfig sc;
  sc.machine_id = "drift";
  sc.input_speed_hz = 10.0;
  sc.noise_relative = 0.02;
  sc.speed_drift = drift;
  sc.seed = 11;
  Result<PlantSimulator> sim =
      PlantSimulator::Create(plant->dynamics, plant->channels, std::move(excitation).value(), sc);
  EXPECT_TRUE(sim.ok()) << sim.error();
  MachineSetup setup;
  setup.machine_id = "drift";
  setup.frf_set = plant->model_frf;
  setup.train = TrainLayoutFromGearTrain(plant->train).value();
  setup.options.sample_rate_hz = sc.sample_rate_hz;
  setup.options.order_tracking = order_tracking;
  setup.options.localisation_tracking = localisation_tracking;
  Result<BlockProcessor> processor = BlockProcessor::Create(std::move(setup));
  EXPECT_TRUE(processor.ok()) << processor.error();
  return {std::move(sim).value(), std::move(processor).value()};
}

int ModeAfterBlocks(Machine& m, int blocks) {
  AccelBlock block;
  BlockResult result;
  for (int b = 0; b < blocks; ++b) {
    m.sim.NextBlock(false, block);
    EXPECT_TRUE(m.processor.Process(block.view(), result).accepted());
  }
  return m.processor.ExportLearnedState().order_tracking_mode;
}

TEST(OrderTrackingDecision, ADriftingMachineIsTrackedAndKeepsIt) {
  Machine m = MakeMachine(/*drift=*/true, /*order_tracking=*/true);
  EXPECT_EQ(ModeAfterBlocks(m, 1), 1);
  EXPECT_EQ(ModeAfterBlocks(m, 2), 1);
  // A restart resumes the decision with the baseline.
  Machine again = MakeMachine(true, true);
  ASSERT_TRUE(again.processor.ImportLearnedState(m.processor.ExportLearnedState()).ok());
  EXPECT_EQ(again.processor.ExportLearnedState().order_tracking_mode, 1);
  // A re-baseline decides again.
  m.processor.ResetBaseline();
  EXPECT_EQ(m.processor.ExportLearnedState().order_tracking_mode, -1);
}

TEST(OrderTrackingDecision, AConstantSpeedMachineIsNotTracked) {
  Machine m = MakeMachine(/*drift=*/false, /*order_tracking=*/true);
  EXPECT_EQ(ModeAfterBlocks(m, 3), 0);
}

TEST(OrderTrackingDecision, TrackingOffNeverDecides) {
  Machine m = MakeMachine(/*drift=*/true, /*order_tracking=*/false);
  EXPECT_EQ(ModeAfterBlocks(m, 2), -1);
}

// Localisation tracking alone (the default) takes the same per-machine decision.
TEST(OrderTrackingDecision, LocalisationTrackingDecidesLikeOrderTracking) {
  Machine drifting = MakeMachine(/*drift=*/true, /*order_tracking=*/false, true);
  EXPECT_EQ(ModeAfterBlocks(drifting, 2), 1);
  Machine steady = MakeMachine(/*drift=*/false, /*order_tracking=*/false, true);
  EXPECT_EQ(ModeAfterBlocks(steady, 2), 0);
}

}  // namespace
}  // namespace gearpath
