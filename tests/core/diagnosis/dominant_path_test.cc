#include "core/diagnosis/dominant_path.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace gearpath {
namespace {

TEST(DominantPathTest, SidebandMaskMarksMeshPlusMinusShaftLinesButNotTheMeshLine) {
  // 1 Hz bins; mesh at 100 Hz between shafts of 10 and 7 Hz; 2 orders; no tolerance.
  std::vector<std::uint8_t> mask(301);
  const std::vector<MeshLines> meshes = {{100.0, {10.0, 7.0}}};
  BuildSidebandMask(1.0, meshes, 2, 0.0, 150.0, 0.0, mask);
  std::vector<int> expected;
  for (int h : {1}) {
    for (double f : {10.0, 20.0, 7.0, 14.0}) {
      expected.push_back(static_cast<int>(h * 100 - f));
      expected.push_back(static_cast<int>(h * 100 + f));
    }
  }
  for (std::size_t k = 0; k < mask.size(); ++k) {
    const bool want =
        std::find(expected.begin(), expected.end(), static_cast<int>(k)) != expected.end();
    EXPECT_EQ(mask[k] != 0, want) << k;  // 2nd harmonic (200 +/- ...) is outside 0..150 Hz
  }
}

TEST(DominantPathTest, MeshHarmonicMaskCoversEveryHarmonicWithItsTolerance) {
  std::vector<std::uint8_t> mask(101);
  const std::vector<MeshLines> meshes = {{30.0, {3.0, 2.0}}};
  BuildMeshHarmonicMask(1.0, meshes, 1.0, mask);
  for (std::size_t k = 0; k < mask.size(); ++k) {
    const bool want = (k >= 29 && k <= 31) || (k >= 59 && k <= 61) || (k >= 89 && k <= 91);
    EXPECT_EQ(mask[k] != 0, want) << k;
  }
}

TEST(DominantPathTest, SelectsTheLargestCriterionAndNoneWhenAllAreZero) {
  EXPECT_EQ(SelectDominantPath(std::vector<double>{1.0, 3.0, 2.0}), 1);
  EXPECT_EQ(SelectDominantPath(std::vector<double>{0.0, 0.0}), -1);
  EXPECT_EQ(SelectDominantPath(std::vector<double>{}), -1);
  EXPECT_EQ(SelectDominantPath(std::vector<double>{NAN, 0.5}), 1);
}

TEST(DominantPathTest, SharesSumToOne) {
  const std::vector<double> e = {1.0, 3.0, 4.0};
  std::vector<double> s(3);
  EnergyShares(e, s);
  EXPECT_DOUBLE_EQ(s[0] + s[1] + s[2], 1.0);
  EXPECT_DOUBLE_EQ(s[2], 0.5);
  const std::vector<double> zero = {0.0, 0.0, 0.0};
  EnergyShares(zero, s);
  EXPECT_EQ(s[0] + s[1] + s[2], 0.0);
}

}  // namespace
}  // namespace gearpath
