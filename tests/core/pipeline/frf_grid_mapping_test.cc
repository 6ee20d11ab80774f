#include "core/pipeline/frf_grid_mapping.h"

#include <gtest/gtest.h>

#include <complex>

namespace gearpath {
namespace {

// H(f) = (a + j b) f + (c + j d), entry-wise different: linear in f, so linear interpolation
// in real and imaginary parts must reproduce it exactly.
FrfMatrix LinearFrf(const Eigen::VectorXd& f) {
  FrfMatrix m;
  m.frequency_hz = f;
  for (Eigen::Index k = 0; k < f.size(); ++k) {
    Eigen::MatrixXcd h(2, 3);
    for (Eigen::Index r = 0; r < 2; ++r) {
      for (Eigen::Index c = 0; c < 3; ++c) {
        const auto rd = static_cast<double>(r);
        const auto cd = static_cast<double>(c);
        h(r, c) = Complex(1.0 + rd, -0.5 * cd) * f[k] + Complex(rd - cd, 2.0);
      }
    }
    m.at.push_back(h);
  }
  return m;
}

TEST(FrfGridMappingTest, ReproducesAnFrfLinearInFrequencyExactly) {
  Eigen::VectorXd f = Eigen::VectorXd::LinSpaced(41, 10.0, 410.0);  // 10 Hz step
  const FrfMatrix frf = LinearFrf(f);
  const auto map = MapFrfToBlockGrid(frf, 1000, 1000.0);  // 1 Hz bins, 0..500 Hz
  ASSERT_TRUE(map.ok()) << map.error();
  EXPECT_EQ(map->block_bins, 501u);
  EXPECT_EQ(map->first_bin, 10u);
  EXPECT_EQ(map->frf.bins(), 401);
  EXPECT_EQ(map->bins_outside, 501u - 401u);
  const FrfMatrix truth = LinearFrf(map->in_range->frequency_hz);
  for (Eigen::Index k = 0; k < map->frf.bins(); ++k) {
    EXPECT_LT((map->frf.at[k] - truth.at[k]).norm(), 1e-9 * truth.at[k].norm());
  }
}

TEST(FrfGridMappingTest, CopiesWhenTheGridsCoincide) {
  Eigen::VectorXd f = Eigen::VectorXd::LinSpaced(100, 1.0, 100.0);
  FrfMatrix frf = LinearFrf(f);
  frf.at[5](0, 0) = Complex(123.0, -7.0);  // not linear any more at one point
  const auto map = MapFrfToBlockGrid(frf, 256, 256.0);
  ASSERT_TRUE(map.ok()) << map.error();
  EXPECT_EQ(map->first_bin, 1u);
  EXPECT_EQ(map->frf.at[5](0, 0), Complex(123.0, -7.0));
}

TEST(FrfGridMappingTest, MarksBinsOutsideTheFrfRangeWithoutExtrapolating) {
  Eigen::VectorXd f = Eigen::VectorXd::LinSpaced(11, 100.0, 200.0);
  const auto map = MapFrfToBlockGrid(LinearFrf(f), 1000, 1000.0);
  ASSERT_TRUE(map.ok()) << map.error();
  EXPECT_FALSE(map->InRange(99));
  EXPECT_TRUE(map->InRange(100));
  EXPECT_TRUE(map->InRange(200));
  EXPECT_FALSE(map->InRange(201));
  EXPECT_EQ(map->bins_outside, 501u - 101u);
}

TEST(FrfGridMappingTest, RejectsAnFrfThatNoBlockBinReaches) {
  Eigen::VectorXd f(2);
  f << 600.0, 700.0;
  const auto map = MapFrfToBlockGrid(LinearFrf(f), 1000, 1000.0);
  ASSERT_FALSE(map.ok());
  EXPECT_EQ(map.error(),
            "FRF grid mapping: no bin of a 1000-sample block at 1000 Hz (0..500 Hz, step 1 Hz) "
            "lies in the FRF range 600..700 Hz");
}

TEST(FrfGridMappingTest, RejectsNonIncreasingFrequencies) {
  Eigen::VectorXd f(3);
  f << 1.0, 3.0, 3.0;
  const auto map = MapFrfToBlockGrid(LinearFrf(f), 64, 64.0);
  ASSERT_FALSE(map.ok());
  EXPECT_EQ(map.error(), "FRF grid mapping: frequencies not strictly increasing at 3 Hz");
}

TEST(FrfGridMappingTest, RejectsAnEmptyFrf) {
  const auto map = MapFrfToBlockGrid(FrfMatrix{}, 64, 64.0);
  ASSERT_FALSE(map.ok());
  EXPECT_EQ(map.error(), "FRF grid mapping: the FRF matrix is empty");
}

}  // namespace
}  // namespace gearpath
