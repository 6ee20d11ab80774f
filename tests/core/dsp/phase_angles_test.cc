#include "core/dsp/phase_angles.h"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <cstddef>
#include <limits>
#include <numbers>
#include <random>
#include <vector>

namespace gearpath {
namespace {

// Units in the last place between a and b (same sign, finite).
double Ulps(double a, double b) {
  const double spacing =
      std::nextafter(std::abs(b), std::numeric_limits<double>::infinity()) - std::abs(b);
  return std::abs(a - b) / spacing;
}

// Every count from 0 to 13 takes each path (four, two and one value per call) in each
// position; the values cover the four quadrants, both axes, tiny and huge magnitudes.
TEST(PhaseAngles, AgreeWithArgWithinFourUlpsForEveryCount) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> angle(-std::numbers::pi, std::numbers::pi);
  std::uniform_real_distribution<double> exponent(-300.0, 300.0);
  std::vector<std::complex<double>> z;
  for (int k = 0; k < 400; ++k) z.push_back(std::polar(std::pow(10.0, exponent(rng)), angle(rng)));
  for (const std::complex<double> axis : {std::complex<double>(1.0, 0.0), {0.0, 2.0}, {-3.0, 0.0},
                                          {0.0, -4.0}, {-1.0, 1e-300}, {-1.0, -1e-300}}) {
    z.push_back(axis);
  }
  for (std::size_t count = 0; count <= 13; ++count) {
    for (std::size_t first = 0; first + count <= z.size(); first += 7) {
      std::vector<double> out(count + 1, 99.0);  // one more: nothing past count is written
      PhaseAngles(std::span<const std::complex<double>>(z).subspan(first, count),
                  std::span<double>(out).first(count));
      for (std::size_t i = 0; i < count; ++i) {
        const double expected = std::arg(z[first + i]);
        ASSERT_LE(Ulps(out[i], expected), 4.0)
            << "count " << count << " value " << first + i << ": " << out[i] << " against "
            << expected;
      }
      EXPECT_EQ(out[count], 99.0) << "count " << count;
    }
  }
}

TEST(PhaseAngles, ZeroHasAngleZeroAndAShortOutputBoundsTheCount) {
  const std::vector<std::complex<double>> z = {{0.0, 0.0}, {1.0, 1.0}, {-1.0, -1.0}};
  std::vector<double> out(2, 7.0);
  PhaseAngles(z, out);
  EXPECT_EQ(out[0], 0.0);
  EXPECT_NEAR(out[1], std::numbers::pi / 4.0, 1e-15);
}

}  // namespace
}  // namespace gearpath
