#include "core/dsp/band_pass.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "tests/core/dsp/test_signals.h"

namespace gearpath {
namespace {

using dsp_test::Cosine;

constexpr double kFs = 8000.0;
constexpr std::size_t kN = 4096;
constexpr double kBin = kFs / kN;  // 1.953125 Hz

std::vector<double> OnBin(std::size_t k, double amplitude = 1.0, double phase = 0.3) {
  return Cosine(kN, kFs, static_cast<double>(k) * kBin, amplitude, phase);
}

std::vector<double> Filter(const std::vector<double>& x, double low, double high,
                           double transition = 50.0) {
  auto band_pass = BandPass::Create(kN, kFs, transition).value();
  std::vector<double> y(kN);
  EXPECT_TRUE(band_pass.Process(x, low, high, y).ok());
  return y;
}

double MaxAbsDifference(const std::vector<double>& a, const std::vector<double>& b) {
  double d = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) d = std::max(d, std::abs(a[i] - b[i]));
  return d;
}

TEST(BandPass, ToneInsideTheBandPassesWithUnitGainAndNoPhaseShift) {
  const auto x = OnBin(512, 2.0, 0.9);  // 1000 Hz
  EXPECT_LT(MaxAbsDifference(Filter(x, 800.0, 1200.0), x), 1e-12);
}

TEST(BandPass, ToneOutsideTheBandAndItsTransitionsIsRemoved) {
  const auto x = OnBin(1024);  // 2000 Hz
  const auto y = Filter(x, 800.0, 1200.0);
  EXPECT_LT(MaxAbsDifference(y, std::vector<double>(kN, 0.0)), 1e-12);
}

TEST(BandPass, ToneHalfwayThroughTheTransitionGetsHalfGain) {
  // Raised cosine: gain 0.5 (1 + cos(pi/2)) = 0.5 halfway.
  const std::size_t k = 640;  // 1250 Hz, 50 Hz above the 1200 Hz edge with a 100 Hz roll-off
  const auto y = Filter(OnBin(k), 800.0, 1200.0, 100.0);
  const auto half = OnBin(k, 0.5);
  EXPECT_LT(MaxAbsDifference(y, half), 1e-12);
}

TEST(BandPass, BandFromZeroHzKeepsTheMeanAndLowTones) {
  std::vector<double> low = OnBin(51);  // ~100 Hz
  for (double& v : low) v += 1.5;
  std::vector<double> x = low;
  const auto high = OnBin(512);
  for (std::size_t i = 0; i < kN; ++i) x[i] += high[i];
  EXPECT_LT(MaxAbsDifference(Filter(x, 0.0, 200.0), low), 1e-12);
}

TEST(BandPass, BandUpToNyquistKeepsTheNyquistTone) {
  std::vector<double> nyquist(kN);
  for (std::size_t i = 0; i < kN; ++i) nyquist[i] = i % 2 == 0 ? 0.7 : -0.7;
  std::vector<double> x = nyquist;
  const auto low = OnBin(512);
  for (std::size_t i = 0; i < kN; ++i) x[i] += low[i];
  EXPECT_LT(MaxAbsDifference(Filter(x, 3500.0, 4000.0), nyquist), 1e-12);
}

TEST(BandPass, ImpulseResponseIsSymmetricSoTheFilterIsZeroPhase) {
  std::vector<double> delta(kN, 0.0);
  delta[0] = 1.0;
  const auto h = Filter(delta, 1000.0, 1500.0, 80.0);
  for (std::size_t i = 1; i < kN; ++i) EXPECT_NEAR(h[i], h[kN - i], 1e-15) << i;
}

TEST(BandPass, GainIsOneInsideRaisedCosineOutsideAndZeroBeyond) {
  auto band_pass = BandPass::Create(kN, kFs, 100.0).value();
  EXPECT_EQ(band_pass.Gain(1000.0, 1000.0, 2000.0), 1.0);
  EXPECT_EQ(band_pass.Gain(2000.0, 1000.0, 2000.0), 1.0);
  EXPECT_NEAR(band_pass.Gain(975.0, 1000.0, 2000.0), 0.5 * (1.0 + std::cos(std::numbers::pi / 4.0)),
              1e-15);
  EXPECT_EQ(band_pass.Gain(2100.0, 1000.0, 2000.0), 0.0);
  EXPECT_EQ(band_pass.Gain(500.0, 1000.0, 2000.0), 0.0);
}

TEST(BandPass, RejectsBadConfigurationNamingTheArgument) {
  auto transition = BandPass::Create(kN, kFs, -1.0);
  ASSERT_FALSE(transition.ok());
  EXPECT_NE(transition.error().find("transition_hz"), std::string::npos) << transition.error();
  auto length = BandPass::Create(1, kFs, 10.0);
  ASSERT_FALSE(length.ok());
  EXPECT_NE(length.error().find("block length 1"), std::string::npos) << length.error();
  auto rate = BandPass::Create(kN, 0.0, 10.0);
  ASSERT_FALSE(rate.ok());
  EXPECT_NE(rate.error().find("sample rate"), std::string::npos) << rate.error();
}

TEST(BandPass, RejectsBandsOutsideZeroToNyquistAndBadBlocks) {
  auto band_pass = BandPass::Create(kN, kFs, 10.0).value();
  std::vector<double> x(kN, 0.0);
  std::vector<double> y(kN);
  for (auto [low, high] :
       {std::pair{-1.0, 100.0}, std::pair{100.0, 4001.0}, std::pair{500.0, 500.0},
        std::pair{600.0, 500.0}, std::pair{std::nan(""), 500.0}}) {
    Status s = band_pass.Process(x, low, high, y);
    ASSERT_FALSE(s.ok()) << low << " " << high;
    EXPECT_NE(s.error().find("0 <= low < high <= fs/2"), std::string::npos) << s.error();
  }
  Status empty = band_pass.Process({}, 10.0, 20.0, y);
  ASSERT_FALSE(empty.ok());
  EXPECT_NE(empty.error().find("input block is empty"), std::string::npos) << empty.error();
  std::vector<double> short_block(kN - 1, 0.0);
  Status mismatched = band_pass.Process(short_block, 10.0, 20.0, y);
  ASSERT_FALSE(mismatched.ok());
  EXPECT_NE(mismatched.error().find("configured for 4096"), std::string::npos);
  x[7] = std::numeric_limits<double>::infinity();
  Status inf = band_pass.Process(x, 10.0, 20.0, y);
  ASSERT_FALSE(inf.ok());
  EXPECT_NE(inf.error().find("index 7"), std::string::npos) << inf.error();
}

}  // namespace
}  // namespace gearpath
