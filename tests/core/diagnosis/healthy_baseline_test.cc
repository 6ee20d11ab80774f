#include "core/diagnosis/healthy_baseline.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace gearpath {
namespace {

TEST(HealthyBaselineTest, RejectsTooFewBlocksNamingTheOption) {
  BaselineOptions o;
  o.blocks = 1;
  const auto b = HealthyBaseline::Create(2, o);
  ASSERT_FALSE(b.ok());
  EXPECT_EQ(b.error(), "healthy baseline: blocks must be >= 2 to estimate a spread, got 1");
}

TEST(HealthyBaselineTest, RejectsNonPositiveConfiguredThreshold) {
  const std::vector<double> t = {1.0, 0.0};
  const auto b = HealthyBaseline::Configured(t);
  ASSERT_FALSE(b.ok());
  EXPECT_EQ(b.error(), "healthy baseline: threshold 1 must be finite and > 0, got 0.000000");
}

TEST(HealthyBaselineTest, LearnsMeanPlusKSigmaOverTheBaselineBlocks) {
  BaselineOptions o;
  o.blocks = 4;
  o.k_sigma = 3.0;
  o.min_margin = 0.0;
  auto b = HealthyBaseline::Create(1, o);
  ASSERT_TRUE(b.ok());
  for (double v : {1.0, 2.0, 3.0}) {
    b->Add(std::vector<double>{v});
    EXPECT_FALSE(b->learned());
  }
  b->Add(std::vector<double>{4.0});
  ASSERT_TRUE(b->learned());
  // mean 2.5, sample variance 5/3.
  EXPECT_NEAR(b->thresholds()[0], 2.5 + 3.0 * std::sqrt(5.0 / 3.0), 1e-12);
  b->Add(std::vector<double>{100.0});  // after learning, nothing changes
  EXPECT_NEAR(b->thresholds()[0], 2.5 + 3.0 * std::sqrt(5.0 / 3.0), 1e-12);
}

TEST(HealthyBaselineTest, ConstantIndicatorGetsTheRelativeMarginNotItsOwnLevel) {
  BaselineOptions o;
  o.blocks = 3;
  o.min_margin = 0.5;
  auto b = HealthyBaseline::Create(1, o);
  ASSERT_TRUE(b.ok());
  for (int i = 0; i < 3; ++i) b->Add(std::vector<double>{2.0});
  EXPECT_DOUBLE_EQ(b->thresholds()[0], 3.0);
}

TEST(HealthyBaselineTest, SkipsNonFiniteBlocksAndRelearnsAfterReset) {
  BaselineOptions o;
  o.blocks = 2;
  o.min_margin = 0.0;
  o.k_sigma = 0.0;
  auto b = HealthyBaseline::Create(1, o);
  ASSERT_TRUE(b.ok());
  b->Add(std::vector<double>{NAN});
  EXPECT_EQ(b->blocks_seen(), 0);
  b->Add(std::vector<double>{1.0});
  b->Add(std::vector<double>{3.0});
  EXPECT_DOUBLE_EQ(b->thresholds()[0], 2.0);
  b->Reset();
  EXPECT_FALSE(b->learned());
  EXPECT_EQ(b->blocks_seen(), 0);
}

}  // namespace
}  // namespace gearpath
