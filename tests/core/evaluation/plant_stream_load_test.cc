// PlantStreamConfig::load_factor (plant_stream.h), the evaluation's load step: on a linear
// plant the healthy response is linear in the transmission errors it scales, so the noise-free
// block scales by exactly the factor; on the parametric plant the load torque deflects the
// meshes, whose stiffness variation then excites the housing in proportion, so the response
// grows with the load (not exactly: the contact is not linear); a factor that is not a finite
// positive number is refused.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <string>

#include "core/evaluation/plant_family.h"
#include "core/evaluation/plant_stream.h"
#include "core/common/accel_block.h"
#include "core/evaluation/scenario_matrix.h"
#include "tests/core/evaluation/scenario_of.h"

namespace gearpath {
namespace {

// Noise-free, without the unmodelled sources: the blocks are the plant's response alone.
Scenario Healthy(PlantFamily family) {
  return testing::ScenarioOf(family, TrainVariant::kTable1, PlantFaultKind::kNone, "", 450.0,
                             0.0, ChannelSet::kSeats, /*unmodelled=*/false);
}

// The stream's third block (past the start-up) at `load_factor`.
AccelBlock BlockAtLoad(const Plant& plant, const Scenario& s, double load_factor) {
  PlantStreamConfig config;
  config.load_factor = load_factor;
  Result<std::unique_ptr<PlantStream>> stream = MakePlantStream(plant, s, config);
  EXPECT_TRUE(stream.ok()) << stream.error();
  AccelBlock block;
  if (!stream.ok()) return block;
  for (int b = 0; b < 3; ++b) (*stream)->NextBlock(false, block);
  return block;
}

double Rms(const AccelBlock& block) {
  double sum = 0.0;
  for (float v : block.samples) sum += static_cast<double>(v) * v;
  return std::sqrt(sum / static_cast<double>(block.samples.size()));
}

TEST(PlantStreamLoad, ALinearPlantsHealthyResponseScalesWithItsLoad) {
  const Scenario s = Healthy(PlantFamily::kLumpedPerturbed);
  Result<Plant> plant = MakePlant({s.family, s.variant, s.channels, s.seed});
  ASSERT_TRUE(plant.ok()) << plant.error();
  const AccelBlock nominal = BlockAtLoad(*plant, s, 1.0);
  const AccelBlock loaded = BlockAtLoad(*plant, s, 1.5);
  ASSERT_EQ(nominal.samples.size(), loaded.samples.size());
  ASSERT_GT(Rms(nominal), 0.0);
  double worst = 0.0;
  for (std::size_t i = 0; i < nominal.samples.size(); ++i) {
    worst = std::max(worst, std::fabs(loaded.samples[i] - 1.5 * nominal.samples[i]));
  }
  EXPECT_LT(worst, 1e-5 * Rms(nominal));  // float samples
}

TEST(PlantStreamLoad, TheParametricPlantRespondsMoreUnderMoreLoad) {
  const Scenario s = Healthy(PlantFamily::kParametricPlate);
  Result<Plant> plant = MakePlant({s.family, s.variant, s.channels, s.seed});
  ASSERT_TRUE(plant.ok()) << plant.error();
  const double nominal = Rms(BlockAtLoad(*plant, s, 1.0));
  const double loaded = Rms(BlockAtLoad(*plant, s, 1.3));
  ASSERT_GT(nominal, 0.0);
  EXPECT_GT(loaded / nominal, 1.15);
  EXPECT_LT(loaded / nominal, 1.45);
}

TEST(PlantStreamLoad, AFactorThatIsNotPositiveIsRefused) {
  for (PlantFamily family : {PlantFamily::kLumpedPerturbed, PlantFamily::kParametricPlate}) {
    const Scenario s = Healthy(family);
    Result<Plant> plant = MakePlant({s.family, s.variant, s.channels, s.seed});
    ASSERT_TRUE(plant.ok()) << plant.error();
    for (double bad : {0.0, -1.0, std::numeric_limits<double>::quiet_NaN()}) {
      PlantStreamConfig config;
      config.load_factor = bad;
      Result<std::unique_ptr<PlantStream>> stream = MakePlantStream(*plant, s, config);
      ASSERT_FALSE(stream.ok());
      EXPECT_NE(stream.error().find("load_factor"), std::string::npos) << stream.error();
    }
  }
}

}  // namespace
}  // namespace gearpath
