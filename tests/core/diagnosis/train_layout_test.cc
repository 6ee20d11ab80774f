#include "core/diagnosis/train_layout.h"

#include <gtest/gtest.h>

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

}  // namespace
}  // namespace gearpath
