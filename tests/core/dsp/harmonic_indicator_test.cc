#include "core/dsp/harmonic_indicator.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace gearpath {
namespace {

constexpr double kBin = 0.5;         // Hz
constexpr std::size_t kBins = 8001;  // up to 4000 Hz

// A synthetic SES: a small floor plus lines of the given heights at the given frequencies.
std::vector<double> SesWithLines(const std::vector<std::pair<double, double>>& lines) {
  std::vector<double> ses(kBins, 0.001);
  for (auto [f, a] : lines) ses[static_cast<std::size_t>(std::lround(f / kBin))] = a;
  return ses;
}

TEST(HarmonicIndicator, SumsTheFirstFiveHarmonicsAndReportsEach) {
  const double fc = 10.0;
  const double heights[] = {0.5, 0.3, 0.2, 0.1, 0.05};
  std::vector<std::pair<double, double>> lines;
  for (int h = 1; h <= 5; ++h) lines.emplace_back(h * fc, heights[h - 1]);
  lines.emplace_back(6 * fc, 9.0);  // a sixth harmonic is not part of the indicator
  auto result = ComputeHarmonicIndicator(SesWithLines(lines), kBin, fc).value();
  EXPECT_NEAR(result.sum, 0.5 + 0.3 + 0.2 + 0.1 + 0.05, 1e-15);
  for (int h = 1; h <= 5; ++h) {
    EXPECT_DOUBLE_EQ(result.harmonics[h - 1].frequency_hz, h * fc);
    EXPECT_DOUBLE_EQ(result.harmonics[h - 1].amplitude, heights[h - 1]);
  }
  EXPECT_DOUBLE_EQ(result.characteristic_hz, fc);
}

TEST(HarmonicIndicator, FlatSpectrumGivesFiveTimesTheFloor) {
  auto result = ComputeHarmonicIndicator(SesWithLines({}), kBin, 7.0).value();
  EXPECT_NEAR(result.sum, 5 * 0.001, 1e-15);
}

TEST(HarmonicIndicator, ToleranceFindsALineDriftedWithTheSpeed) {
  // True shaft rate 2 % above nominal: harmonic h sits 0.02 h f_c away.
  const double nominal = 25.0;
  std::vector<std::pair<double, double>> lines;
  for (int h = 1; h <= 5; ++h) lines.emplace_back(h * nominal * 1.02, 1.0);
  const auto ses = SesWithLines(lines);
  auto found = ComputeHarmonicIndicator(ses, kBin, nominal, {0.025}).value();
  EXPECT_NEAR(found.sum, 5.0, 1e-15);
  EXPECT_NEAR(found.harmonics[4].frequency_hz, 5 * nominal * 1.02, kBin);
  auto missed = ComputeHarmonicIndicator(ses, kBin, nominal, {0.005}).value();
  // 0.5 % windows: the first line (0.5 Hz = one bin off) is inside the one-bin minimum, the
  // other four are missed and read the floor.
  EXPECT_NEAR(missed.sum, 1.0 + 4 * 0.001, 1e-15);
}

TEST(HarmonicIndicator, SearchesAtLeastOneBinEitherSide) {
  auto result = ComputeHarmonicIndicator(SesWithLines({{10.5, 1.0}}), kBin, 10.0, {0.0}).value();
  EXPECT_DOUBLE_EQ(result.harmonics[0].frequency_hz, 10.5);
  EXPECT_DOUBLE_EQ(result.harmonics[0].amplitude, 1.0);
}

TEST(HarmonicIndicator, RejectsBadCharacteristicFrequenciesAndSpectra) {
  const auto ses = SesWithLines({});
  for (double fc : {0.0, -3.0, std::numeric_limits<double>::quiet_NaN()}) {
    auto r = ComputeHarmonicIndicator(ses, kBin, fc);
    ASSERT_FALSE(r.ok()) << fc;
    EXPECT_NE(r.error().find("characteristic frequency"), std::string::npos) << r.error();
  }
  auto above = ComputeHarmonicIndicator(ses, kBin, 800.5);  // 5 x 800.5 > 4000 Hz
  ASSERT_FALSE(above.ok());
  EXPECT_NE(above.error().find("Nyquist/5"), std::string::npos) << above.error();
  EXPECT_TRUE(ComputeHarmonicIndicator(ses, kBin, 800.0).ok());  // harmonic 5 at exactly 4000

  auto empty = ComputeHarmonicIndicator({}, kBin, 10.0);
  ASSERT_FALSE(empty.ok());
  EXPECT_NE(empty.error().find("SES is empty"), std::string::npos) << empty.error();
  auto bin = ComputeHarmonicIndicator(ses, 0.0, 10.0);
  ASSERT_FALSE(bin.ok());
  EXPECT_NE(bin.error().find("bin width"), std::string::npos) << bin.error();
  auto tolerance = ComputeHarmonicIndicator(ses, kBin, 10.0, {-0.1});
  ASSERT_FALSE(tolerance.ok());
  EXPECT_NE(tolerance.error().find("relative tolerance"), std::string::npos) << tolerance.error();
  auto bad = ses;
  bad[40] = std::numeric_limits<double>::infinity();
  auto non_finite = ComputeHarmonicIndicator(bad, kBin, 10.0);
  ASSERT_FALSE(non_finite.ok());
  EXPECT_NE(non_finite.error().find("index 40"), std::string::npos) << non_finite.error();
}

TEST(HarmonicIndicator, EnhancementIsReconstructedOverRawInPercent) {
  EXPECT_DOUBLE_EQ(EnhancementPercent(3.0, 1.5).value(), 200.0);
  EXPECT_DOUBLE_EQ(EnhancementPercent(0.0, 1.5).value(), 0.0);
  auto zero_raw = EnhancementPercent(1.0, 0.0);
  ASSERT_FALSE(zero_raw.ok());
  EXPECT_NE(zero_raw.error().find("raw indicator"), std::string::npos) << zero_raw.error();
  auto nan = EnhancementPercent(std::nan(""), 1.0);
  ASSERT_FALSE(nan.ok());
  EXPECT_NE(nan.error().find("reconstructed indicator"), std::string::npos) << nan.error();
}

}  // namespace
}  // namespace gearpath
