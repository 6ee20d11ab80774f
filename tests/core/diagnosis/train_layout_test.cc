#include "core/diagnosis/train_layout.h"

#include <gtest/gtest.h>

#include "core/model/gear_train.h"

namespace gearpath {
namespace {

TEST(TrainLayoutTest, Table1GivesSevenTenthsOfTheInputRateOnBothLaterShafts) {
  const auto ratios = ShaftRateRatios(TrainLayout::Table1());
  ASSERT_TRUE(ratios.ok()) << ratios.error();
  ASSERT_EQ(ratios->size(), 3u);
  EXPECT_DOUBLE_EQ((*ratios)[0], 1.0);
  EXPECT_DOUBLE_EQ((*ratios)[1], 28.0 / 40.0);  // 10 Hz -> 7 Hz (seed Table 6)
  EXPECT_DOUBLE_EQ((*ratios)[2], 28.0 / 40.0 * 34.0 / 34.0);
}

TEST(TrainLayoutTest, RejectsGearWithoutTeethNamingIt) {
  TrainLayout t = TrainLayout::Table1();
  t.gears[2].teeth = 0;
  const auto ratios = ShaftRateRatios(t);
  ASSERT_FALSE(ratios.ok());
  EXPECT_EQ(ratios.error(), "train layout: gear 'G3' has 0 teeth (must be > 0)");
}

TEST(TrainLayoutTest, RejectsShaftUnreachableFromTheInput) {
  TrainLayout t = TrainLayout::Table1();
  t.meshes.pop_back();
  const auto ratios = ShaftRateRatios(t);
  ASSERT_FALSE(ratios.ok());
  EXPECT_EQ(ratios.error(),
            "train layout: shaft 'output' is not connected to the input shaft through any mesh");
}

TEST(TrainLayoutTest, GearTrainTable1GivesTheSameLayoutAsTheBuiltIn) {
  const auto layout = TrainLayoutFromGearTrain(GearTrain::Table1());
  ASSERT_TRUE(layout.ok()) << layout.error();
  const TrainLayout ref = TrainLayout::Table1();
  ASSERT_EQ(layout->gears.size(), ref.gears.size());
  for (std::size_t g = 0; g < ref.gears.size(); ++g) {
    EXPECT_EQ(layout->gears[g].name, ref.gears[g].name);
    EXPECT_EQ(layout->gears[g].teeth, ref.gears[g].teeth);
    EXPECT_EQ(layout->gears[g].shaft, ref.gears[g].shaft);
  }
  ASSERT_EQ(layout->meshes.size(), 2u);
  EXPECT_EQ(layout->meshes[1].gear_a, 2);
  EXPECT_EQ(layout->meshes[1].gear_b, 3);
}

}  // namespace
}  // namespace gearpath
