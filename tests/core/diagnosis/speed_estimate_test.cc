#include "core/diagnosis/speed_estimate.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace gearpath {
namespace {

// Amplitude spectrum of unit tones at the mesh harmonics of input speed f (Table 1 orders 28
// and 23.8), linearly spread over the two nearest bins, plus a flat floor.
std::vector<double> MeshSpectrum(double f, double bin_hz, std::size_t bins) {
  std::vector<double> a(bins, 0.01);
  for (double o : {28.0, 23.8}) {
    for (int h = 1; h <= 3; ++h) {
      const double b = h * o * f / bin_hz;
      const auto k = static_cast<std::size_t>(b);
      const double t = b - static_cast<double>(k);
      a[k] += 1.0 - t;
      a[k + 1] += t;
    }
  }
  return a;
}

TEST(SpeedEstimateTest, FindsTheInputSpeedFromTheMeshLines) {
  const double bin = 8000.0 / 8192.0;
  const std::vector<double> orders = {28.0, 23.8};
  for (double truth : {8.0, 9.37, 10.0, 11.2}) {
    const auto a = MeshSpectrum(truth, bin, 4097);
    SpeedSearch s;
    s.lo_hz = 7.5;
    s.hi_hz = 12.5;
    const SpeedEstimate e = EstimateSpeedFromMeshes(a, bin, orders, s);
    EXPECT_TRUE(e.found);
    // A line moves h * o bins per Hz of input speed; a quarter of the finest line step.
    EXPECT_NEAR(e.speed_hz, truth, bin / (28.0 * 3.0)) << truth;
    EXPECT_GT(e.prominence, 3.0);
  }
}

TEST(SpeedEstimateTest, AFlatSpectrumHasNoSpeedToTrack) {
  const std::vector<double> a(4097, 1.0);
  const std::vector<double> orders = {28.0};
  SpeedSearch s;
  s.lo_hz = 5.0;
  s.hi_hz = 15.0;
  const SpeedEstimate e = EstimateSpeedFromMeshes(a, 1.0, orders, s);
  EXPECT_FALSE(e.found);
  EXPECT_NEAR(e.prominence, 1.0, 1e-9);
}

TEST(SpeedEstimateTest, InvalidSearchRangeFindsNothing) {
  const std::vector<double> a(100, 1.0);
  const std::vector<double> orders = {28.0};
  SpeedSearch s;
  s.lo_hz = 10.0;
  s.hi_hz = 5.0;
  EXPECT_FALSE(EstimateSpeedFromMeshes(a, 1.0, orders, s).found);
}

}  // namespace
}  // namespace gearpath
