#include "core/dsp/kurtogram.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "tests/core/dsp/test_signals.h"

namespace gearpath {
namespace {

using dsp_test::AddResonanceImpulses;
using dsp_test::Cosine;
using dsp_test::WhiteNoise;

constexpr double kFs = 8000.0;
constexpr std::size_t kN = 16384;
constexpr double kResonanceHz = 2500.0;

KurtogramOptions Options(KurtogramWhitening whitening) {
  KurtogramOptions options;
  options.depth = 6;
  options.whitening = whitening;
  return options;
}

// Unit white noise plus a 10 Hz train of impulses ringing a 2500 Hz, 2 % damped resonance.
std::vector<double> ImpulsesInNoise(unsigned seed) {
  std::vector<double> x = WhiteNoise(kN, 1.0, seed);
  AddResonanceImpulses(x, kFs, 10.0, 0.013, kResonanceHz, 0.02, 3.0);
  return x;
}

// Twelve harmonics of a ~280 Hz mesh, 26 dB and more above the noise, scattered phases.
void AddMeshTones(std::vector<double>& x) {
  const double mesh_hz = 280.0;
  for (int h = 1; h <= 12; ++h) {
    const auto tone = Cosine(x.size(), kFs, mesh_hz * h, 20.0 / std::sqrt(h), 1.7 * h * h);
    for (std::size_t i = 0; i < x.size(); ++i) x[i] += tone[i];
  }
}

TEST(Kurtogram, RejectsOptionsOutsideTheirRangeNamingThem) {
  KurtogramOptions deep;
  deep.depth = 13;
  auto r1 = Kurtogram::Create(kN, kFs, deep);
  ASSERT_FALSE(r1.ok());
  EXPECT_NE(r1.error().find("depth 13"), std::string::npos) << r1.error();

  KurtogramOptions wide;
  wide.min_bandwidth_hz = 5000.0;
  auto r2 = Kurtogram::Create(kN, kFs, wide);
  ASSERT_FALSE(r2.ok());
  EXPECT_NE(r2.error().find("min_bandwidth_hz"), std::string::npos) << r2.error();

  KurtogramOptions order;
  order.ar_order = 0;
  auto r3 = Kurtogram::Create(kN, kFs, order);
  ASSERT_FALSE(r3.ok());
  EXPECT_NE(r3.error().find("ar_order 0"), std::string::npos) << r3.error();

  KurtogramOptions taper;
  taper.taper_fraction = 1.5;
  auto r4 = Kurtogram::Create(kN, kFs, taper);
  ASSERT_FALSE(r4.ok());
  EXPECT_NE(r4.error().find("taper_fraction"), std::string::npos) << r4.error();

  auto r5 = Kurtogram::Create(8, kFs, Options(KurtogramWhitening::kNone));
  ASSERT_FALSE(r5.ok());
  EXPECT_NE(r5.error().find("block length 8"), std::string::npos) << r5.error();

  auto r6 = Kurtogram::Create(kN, -1.0, KurtogramOptions{});
  ASSERT_FALSE(r6.ok());
  EXPECT_NE(r6.error().find("sample rate"), std::string::npos) << r6.error();
}

TEST(Kurtogram, RejectsEmptyMismatchedAndNonFiniteBlocks) {
  auto kurtogram = Kurtogram::Create(1024, kFs, KurtogramOptions{}).value();
  auto empty = kurtogram.Process({});
  ASSERT_FALSE(empty.ok());
  EXPECT_NE(empty.error().find("block is empty"), std::string::npos) << empty.error();
  std::vector<double> x(1000, 0.0);
  auto mismatched = kurtogram.Process(x);
  ASSERT_FALSE(mismatched.ok());
  EXPECT_NE(mismatched.error().find("1000 values, configured for 1024"), std::string::npos)
      << mismatched.error();
  x.assign(1024, 0.0);
  x[5] = std::numeric_limits<double>::quiet_NaN();
  auto nan = kurtogram.Process(x);
  ASSERT_FALSE(nan.ok());
  EXPECT_NE(nan.error().find("non-finite value at index 5"), std::string::npos) << nan.error();
}

TEST(Kurtogram, RowsFollowTheOneThirdBinaryTree) {
  KurtogramOptions options;
  options.depth = 3;
  auto kurtogram = Kurtogram::Create(kN, kFs, options).value();
  const int expected_levels[] = {0, 1, 1, 2, 2, 3};
  const bool expected_ternary[] = {false, false, true, false, true, false};
  const std::size_t expected_bands[] = {1, 2, 3, 4, 6, 8};
  ASSERT_EQ(kurtogram.row_count(), 6u);
  for (std::size_t r = 0; r < 6; ++r) {
    EXPECT_EQ(kurtogram.row_node(r).level, expected_levels[r]) << r;
    EXPECT_EQ(kurtogram.row_node(r).ternary, expected_ternary[r]) << r;
    EXPECT_EQ(kurtogram.map_row(r).size(), expected_bands[r]) << r;
    EXPECT_DOUBLE_EQ(kurtogram.row_bandwidth_hz(r),
                     kFs / 2.0 / static_cast<double>(expected_bands[r]));
  }
  EXPECT_NEAR(kurtogram.row_node(2).DisplayLevel(), 1.585, 1e-3);
}

TEST(Kurtogram, MinimumBandwidthCapsTheDepth) {
  // Bandwidths 4000, 2000, 1333, 1000, 667, 500, 333 | 250: a 300 Hz minimum stops at 3.6.
  KurtogramOptions options;
  options.depth = 6;
  options.min_bandwidth_hz = 300.0;
  auto kurtogram = Kurtogram::Create(kN, kFs, options).value();
  ASSERT_EQ(kurtogram.row_count(), 7u);
  EXPECT_EQ(kurtogram.row_node(6).level, 3);
  EXPECT_TRUE(kurtogram.row_node(6).ternary);
  auto best = kurtogram.Process(ImpulsesInNoise(1)).value();
  EXPECT_GE(best.bandwidth_hz, 300.0);
}

TEST(Kurtogram, SilentBlockScoresZeroAndIsNotSignificant) {
  for (KurtogramWhitening w : {KurtogramWhitening::kNone, KurtogramWhitening::kAutoregressive}) {
    auto kurtogram = Kurtogram::Create(kN, kFs, Options(w)).value();
    auto best = kurtogram.Process(std::vector<double>(kN, 3.0)).value();
    EXPECT_EQ(best.kurtosis, 0.0);
    EXPECT_FALSE(best.significant);
  }
}

TEST(Kurtogram, SigmaIsTwoOverRootOfTheBandsBinCount) {
  auto kurtogram = Kurtogram::Create(kN, kFs, Options(KurtogramWhitening::kNone)).value();
  // Level 0 holds bins 1..N/2; level 2 band 1 holds bins N/8..N/4-1.
  EXPECT_DOUBLE_EQ(kurtogram.Band({0, false, 0}).sigma, 2.0 / std::sqrt(kN / 2.0));
  EXPECT_DOUBLE_EQ(kurtogram.Band({2, false, 1}).sigma, 2.0 / std::sqrt(kN / 8.0));
}

class KurtogramWhitenings : public ::testing::TestWithParam<KurtogramWhitening> {};

TEST_P(KurtogramWhitenings, FindsTheResonanceOfAnImpulseTrainInNoise) {
  auto kurtogram = Kurtogram::Create(kN, kFs, Options(GetParam())).value();
  for (unsigned seed : {1u, 2u, 3u}) {
    auto best = kurtogram.Process(ImpulsesInNoise(seed)).value();
    EXPECT_LE(std::abs(best.centre_hz - kResonanceHz), best.bandwidth_hz) << "seed " << seed;
    EXPECT_TRUE(best.significant) << "seed " << seed << " SK " << best.kurtosis;
    EXPECT_GE(best.low_hz, 0.0);
    EXPECT_DOUBLE_EQ(best.high_hz - best.low_hz, best.bandwidth_hz);
  }
}

TEST_P(KurtogramWhitenings, WhiteNoiseScoresAboutZeroAndIsNotSignificant) {
  auto kurtogram = Kurtogram::Create(kN, kFs, Options(GetParam())).value();
  for (unsigned seed : {11u, 12u, 13u, 14u}) {
    auto best = kurtogram.Process(WhiteNoise(kN, 2.0, seed)).value();
    EXPECT_FALSE(best.significant) << "seed " << seed << " SK " << best.kurtosis;
    // Every cell is within a few of its own sigma of the Gaussian value 0 (the map maximum is
    // the largest of ~250 draws, hence 5 and not 3).
    for (std::size_t r = 0; r < kurtogram.row_count(); ++r) {
      const KurtogramNode row = kurtogram.row_node(r);
      const double sigma = kurtogram.Band({row.level, row.ternary, 0}).sigma;
      for (double sk : kurtogram.map_row(r)) EXPECT_LT(std::abs(sk), 5.0 * sigma) << r;
    }
  }
}

TEST_P(KurtogramWhitenings, KurtosisDoesNotDependOnTheSignalsScale) {
  auto kurtogram = Kurtogram::Create(4096, kFs, Options(GetParam())).value();
  std::vector<double> x = WhiteNoise(4096, 1.0, 5);
  AddResonanceImpulses(x, kFs, 25.0, 0.01, 1500.0, 0.03, 4.0);
  (void)kurtogram.Process(x).value();
  std::vector<std::vector<double>> map;
  for (std::size_t r = 0; r < kurtogram.row_count(); ++r) {
    map.emplace_back(kurtogram.map_row(r).begin(), kurtogram.map_row(r).end());
  }
  for (double& v : x) v *= 1e-3;
  (void)kurtogram.Process(x).value();
  for (std::size_t r = 0; r < kurtogram.row_count(); ++r) {
    for (std::size_t b = 0; b < map[r].size(); ++b) {
      EXPECT_NEAR(kurtogram.map_row(r)[b], map[r][b], 1e-9);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(NoneAndAutoregressive, KurtogramWhitenings,
                         ::testing::Values(KurtogramWhitening::kNone,
                                           KurtogramWhitening::kAutoregressive));

TEST(Kurtogram, PureToneGivesMinusOneInTheBandThatHoldsIt) {
  // A constant-envelope band has |c|^4 / (|c|^2)^2 = 1, SK = -1: the tone trap.
  const std::size_t k0 = 2300;  // 1123 Hz, on a bin, away from the band edges of rows 0..3
  const auto x = Cosine(kN, kFs, static_cast<double>(k0) * kFs / kN, 1.0, 0.4);
  auto kurtogram = Kurtogram::Create(kN, kFs, Options(KurtogramWhitening::kNone)).value();
  (void)kurtogram.Process(x).value();
  const double f0 = static_cast<double>(k0) * kFs / kN;
  for (std::size_t r = 0; r < 6; ++r) {
    const KurtogramNode row = kurtogram.row_node(r);
    const int band = static_cast<int>(f0 / kurtogram.row_bandwidth_hz(r));
    EXPECT_NEAR(kurtogram.map_row(r)[static_cast<std::size_t>(band)], -1.0, 0.02)
        << "level " << row.level << (row.ternary ? ".6" : "");
  }
}

TEST(Kurtogram, MeshTonesHideTheResonanceAndWhiteningRevealsIt) {
  std::vector<double> x = ImpulsesInNoise(2);
  AddMeshTones(x);
  auto plain = Kurtogram::Create(kN, kFs, Options(KurtogramWhitening::kNone)).value();
  (void)plain.Process(x).value();
  // The trap: the mesh harmonic at 2520 Hz dominates the resonance band, whose SK goes negative.
  EXPECT_LT(plain.Band({3, true, 7}).kurtosis, 0.0);  // 2333..2667 Hz

  auto whitened = Kurtogram::Create(kN, kFs, Options(KurtogramWhitening::kAutoregressive)).value();
  for (unsigned seed : {1u, 2u, 3u}) {
    std::vector<double> y = ImpulsesInNoise(seed);
    AddMeshTones(y);
    auto best = whitened.Process(y).value();
    EXPECT_LE(std::abs(best.centre_hz - kResonanceHz), best.bandwidth_hz) << "seed " << seed;
    EXPECT_TRUE(best.significant) << "seed " << seed << " SK " << best.kurtosis;
  }
}

}  // namespace
}  // namespace gearpath
