// The tail guard of RobustBaseline (robust_baseline.h): an indicator that is heavy-tailed when
// healthy gets a scale at which its worst baseline block scores exactly tail_z; a Gaussian one
// keeps its MAD scale.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "core/diagnosis/robust_baseline.h"

namespace gearpath {
namespace {

constexpr int kBlocks = 20;

// Two indicators (no log scale): 0 Gaussian, 1 Gaussian with one burst block at +40 sigma.
RobustBaseline Learn(double tail_z) {
  RobustBaselineOptions o;
  o.blocks = kBlocks;
  o.relative_floor = 0.0;
  o.tail_z = tail_z;
  auto b = RobustBaseline::Create(2, o);
  EXPECT_TRUE(b.ok()) << b.error();
  std::mt19937_64 rng(5);
  std::normal_distribution<double> g(0.0, 1.0);
  for (int i = 0; i < kBlocks; ++i) {
    const double burst = i == 7 ? 40.0 : 0.0;
    EXPECT_TRUE(b->Add(std::vector<double>{g(rng), g(rng) + burst}));
  }
  EXPECT_TRUE(b->learned());
  return std::move(b).value();
}

TEST(RobustBaselineTail, WorstBaselineBlockScoresAtTheGuard) {
  const RobustBaseline off = Learn(0.0);
  const RobustBaseline on = Learn(5.0);
  // The location is the median either way; the Gaussian indicator's scale is untouched.
  EXPECT_DOUBLE_EQ(on.median()[0], off.median()[0]);
  EXPECT_DOUBLE_EQ(on.median()[1], off.median()[1]);
  EXPECT_DOUBLE_EQ(on.scale()[0], off.scale()[0]);
  // Without the guard the burst block scores ~40 sigma on the MAD scale; with it, exactly 5.
  std::vector<double> z(2);
  const std::vector<double> burst{0.0, off.median()[1] + 40.0};
  ASSERT_EQ(off.ZScores(burst, z), 0);
  EXPECT_GT(z[1], 20.0);
  // The worst deviation over the baseline defines the scale: 5 = (40 + noise) / scale.
  EXPECT_GT(on.scale()[1], 39.0 / 5.0);
  EXPECT_LT(on.scale()[1], 44.0 / 5.0);
  // A block 40 above the median scores about 5 (the burst block's own noise moved its
  // deviation by about one sigma).
  ASSERT_EQ(on.ZScores(burst, z), 0);
  EXPECT_NEAR(z[1], 5.0, 0.6);
}

TEST(RobustBaselineTail, ResumedBaselineAppliesTheGuardItIsGiven) {
  RobustBaselineOptions o;
  o.blocks = 4;
  o.relative_floor = 0.0;
  auto b = RobustBaseline::Create(1, o);
  ASSERT_TRUE(b.ok());
  for (double v : {0.0, 1.0, -1.0}) ASSERT_TRUE(b->Add(std::vector<double>{v}));
  auto resumed = RobustBaseline::FromState(b->State());
  ASSERT_TRUE(resumed.ok()) << resumed.error();
  resumed->set_tail_z(2.0);
  ASSERT_TRUE(resumed->Add(std::vector<double>{10.0}));
  // Median of {-1, 0, 1, 10} = 0.5; largest deviation 9.5 -> scale 4.75 (the MAD gives 1.48).
  EXPECT_NEAR(resumed->scale()[0], 9.5 / 2.0, 1e-12);
}

TEST(RobustBaselineTail, RejectsANegativeGuard) {
  RobustBaselineOptions o;
  o.blocks = 5;
  o.tail_z = -1.0;
  const auto b = RobustBaseline::Create(1, o);
  ASSERT_FALSE(b.ok());
  EXPECT_NE(b.error().find("tail_z"), std::string::npos) << b.error();
}

}  // namespace
}  // namespace gearpath
