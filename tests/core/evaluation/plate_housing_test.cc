// PlateHousing against independent truth: the simply supported plate's frequencies and FRFs
// written out here from the textbook formulas, the static limit against Navier's double-series
// solution for a point load, mode enumeration, rejection of bad input.
#include "core/evaluation/plate_housing.h"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <numbers>

namespace gearpath {
namespace {

constexpr double kPi = std::numbers::pi;

PlateGeometry SteelPlate() {
  PlateGeometry g;
  g.length_m = 0.6;
  g.width_m = 0.42;
  g.thickness_m = 0.015;
  return g;
}

TEST(PlateHousing, ModeFrequenciesAreLeissasFormula) {
  const PlateGeometry g = SteelPlate();
  // D = E h^3 / (12 (1 - nu^2)) = 2.1e11 * 3.375e-6 / 10.92 = 64904 N m; rho h = 117.75 kg/m^2.
  EXPECT_NEAR(g.BendingStiffness(), 2.1e11 * 0.015 * 0.015 * 0.015 / (12.0 * 0.91), 1e-6);
  const double c = std::sqrt(g.BendingStiffness() / (7850.0 * 0.015));
  for (auto [m, n] : {std::pair{1, 1}, std::pair{2, 1}, std::pair{1, 3}, std::pair{4, 5}}) {
    const double w = kPi * kPi * c * (m * m / 0.36 + n * n / (0.42 * 0.42));
    EXPECT_NEAR(g.ModeFrequencyHz(m, n), w / (2.0 * kPi), 1e-9 * w) << m << "," << n;
  }
  // f_11 of this plate: 311.5 Hz.
  EXPECT_NEAR(g.ModeFrequencyHz(1, 1), 311.5, 0.1);
}

TEST(PlateHousing, EnumeratesEveryModeBelowTheCutoffInOrder) {
  const PlateGeometry g = SteelPlate();
  const std::vector<PlateMode> modes = EnumeratePlateModes(g, 4000.0);
  ASSERT_FALSE(modes.empty());
  std::size_t count = 0;
  for (int m = 1; m < 50; ++m) {
    for (int n = 1; n < 50; ++n) count += g.ModeFrequencyHz(m, n) <= 4000.0 ? 1 : 0;
  }
  EXPECT_EQ(modes.size(), count);
  for (std::size_t r = 1; r < modes.size(); ++r) {
    EXPECT_LE(modes[r - 1].frequency_hz, modes[r].frequency_hz);
  }
  EXPECT_EQ(modes.front().m, 1);
  EXPECT_EQ(modes.front().n, 1);
  EXPECT_LE(modes.back().frequency_hz, 4000.0);
}

TEST(PlateHousing, PointAndTransferAccelerancesAreTheModalSum) {
  const PlateGeometry g = SteelPlate();
  std::vector<PlateMode> modes = EnumeratePlateModes(g, 5000.0);
  for (std::size_t r = 0; r < modes.size(); ++r) {
    modes[r].damping_ratio = 0.01 + 0.001 * static_cast<double>(r);
  }
  const std::vector<PlatePoint> points = {{0.15, 0.2}, {0.33, 0.11}, {0.47, 0.31}};
  Result<PlateHousing> plate = PlateHousing::Create(g, modes, points);
  ASSERT_TRUE(plate.ok()) << plate.error();
  const double rho_h = 7850.0 * 0.015;
  for (double f : {120.0, 777.0, 2345.0, 3999.0}) {
    const Eigen::MatrixXcd h = plate->Accelerance(f, {0, 1, 2}, {0, 1, 2});
    const double w = 2.0 * kPi * f;
    for (int p = 0; p < 3; ++p) {
      for (int q = 0; q < 3; ++q) {
        std::complex<double> sum = 0.0;
        for (const PlateMode& m : modes) {
          const double wr = 2.0 * kPi * g.ModeFrequencyHz(m.m, m.n);
          const double phi_p = 2.0 / std::sqrt(rho_h * 0.6 * 0.42) *
                               std::sin(m.m * kPi * points[p].x_m / 0.6) *
                               std::sin(m.n * kPi * points[p].y_m / 0.42);
          const double phi_q = 2.0 / std::sqrt(rho_h * 0.6 * 0.42) *
                               std::sin(m.m * kPi * points[q].x_m / 0.6) *
                               std::sin(m.n * kPi * points[q].y_m / 0.42);
          sum += phi_p * phi_q * (-w * w) /
                 std::complex<double>(wr * wr - w * w, 2.0 * m.damping_ratio * wr * w);
        }
        EXPECT_LT(std::abs(h(p, q) - sum), 1e-12 * std::abs(sum)) << f << " " << p << q;
      }
    }
    // Reciprocity.
    EXPECT_LT(std::abs(h(0, 2) - h(2, 0)), 1e-14 * std::abs(h(0, 2)));
  }
}

// The receptance H / (-w^2) at w -> 0 is sum phi(P) phi(Q) / w_mn^2, which must equal Navier's
// static deflection of a simply supported plate under a unit point load at Q (Timoshenko &
// Woinowsky-Krieger, Theory of Plates and Shells, section 30):
//   w(P) = 4 / (a b D pi^4) sum_mn sin(m pi xQ / a) sin(n pi yQ / b) sin(m pi xP / a)
//          sin(n pi yP / b) / ((m / a)^2 + (n / b)^2)^2.
// A transfer point pair (the series converges fast there), all modes up to 2 MHz.
TEST(PlateHousing, StaticLimitIsNaviersSolution) {
  const PlateGeometry g = SteelPlate();
  const std::vector<PlatePoint> points = {{0.17, 0.13}, {0.41, 0.29}};
  Result<PlateHousing> plate = PlateHousing::Create(g, EnumeratePlateModes(g, 2e6), points);
  ASSERT_TRUE(plate.ok()) << plate.error();
  const Eigen::MatrixXcd h = plate->Accelerance(0.01, {0}, {1});
  const double w = 2.0 * kPi * 0.01;
  const double receptance = (h(0, 0) / (-w * w)).real();
  double navier = 0.0;
  for (int m = 1; m < 400; ++m) {
    for (int n = 1; n < 400; ++n) {
      const double k = m * m / (0.6 * 0.6) + n * n / (0.42 * 0.42);
      navier += std::sin(m * kPi * 0.41 / 0.6) * std::sin(n * kPi * 0.29 / 0.42) *
                std::sin(m * kPi * 0.17 / 0.6) * std::sin(n * kPi * 0.13 / 0.42) / (k * k);
    }
  }
  navier *= 4.0 / (0.6 * 0.42 * g.BendingStiffness() * std::pow(kPi, 4));
  EXPECT_GT(navier, 0.0);
  EXPECT_NEAR(receptance / navier, 1.0, 1e-3) << receptance << " vs " << navier;
}

TEST(PlateHousing, RejectsBadInputByName) {
  PlateGeometry g = SteelPlate();
  std::vector<PlateMode> modes = EnumeratePlateModes(g, 1000.0);
  Result<PlateHousing> outside = PlateHousing::Create(g, modes, {{0.7, 0.1}});
  ASSERT_FALSE(outside.ok());
  EXPECT_NE(outside.error().find("points[0]"), std::string::npos) << outside.error();
  modes[1].damping_ratio = -0.1;
  Result<PlateHousing> damping = PlateHousing::Create(g, modes, {{0.3, 0.1}});
  ASSERT_FALSE(damping.ok());
  EXPECT_NE(damping.error().find("modes[1]"), std::string::npos) << damping.error();
  g.thickness_m = 0.0;
  EXPECT_FALSE(PlateHousing::Create(g, EnumeratePlateModes(SteelPlate(), 1000.0), {}).ok());
  EXPECT_FALSE(PlateHousing::Create(SteelPlate(), {}, {}).ok());
}

}  // namespace
}  // namespace gearpath
