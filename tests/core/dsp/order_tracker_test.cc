#include "core/dsp/order_tracker.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstddef>
#include <span>
#include <vector>

#include "core/dsp/synchronous_average.h"
#include "tests/core/dsp/test_signals.h"

namespace gearpath {
namespace {

using dsp_test::kTwoPi;

constexpr double kFs = 8000.0;
constexpr std::size_t kN = 8000;  // 1-s block
constexpr double kShaftHz = 10.0;
constexpr int kTeeth = 30;        // carrier at 300 Hz
constexpr double kDrift = 0.003;  // +/- 0.3 % speed within the block

// Shaft revolutions at time t for speed f0 (1 + a sin(2 pi t / T + phi)), T the block length.
double Revolutions(double t, double a, double phi) {
  const double period = static_cast<double>(kN) / kFs;
  return kShaftHz * t -
         kShaftHz * a * period / kTwoPi * (std::cos(kTwoPi * t / period + phi) - std::cos(phi));
}

// A gear signal: mesh harmonics 1..3 of a rotating shaft, plus a phase modulation of the mesh
// at the shaft rate (a tooth fault's signature) and white noise.
std::vector<double> GearSignal(double drift, double phi, double fault_pm_rad, double noise) {
  std::vector<double> x = dsp_test::WhiteNoise(kN, noise, 7);
  const double amplitude[] = {1.0, 0.5, 0.3};
  for (std::size_t i = 0; i < kN; ++i) {
    const double rev = Revolutions(static_cast<double>(i) / kFs, drift, phi);
    const double pm = fault_pm_rad * std::sin(kTwoPi * rev);
    for (int h = 1; h <= 3; ++h) {
      x[i] += amplitude[h - 1] * std::cos(kTwoPi * h * kTeeth * rev + h * pm);
    }
  }
  return x;
}

// The analytic warp: the sample position where the shaft has turned i f0 / fs revolutions.
std::vector<double> TrueWarp(double drift, double phi) {
  std::vector<double> warp(kN);
  double s = 0.0;
  for (std::size_t i = 0; i < kN; ++i) {
    const double target = kShaftHz * static_cast<double>(i) / kFs;
    for (int it = 0; it < 20; ++it) {  // Newton on the angle
      const double t = s / kFs;
      const double period = static_cast<double>(kN) / kFs;
      const double rate = kShaftHz * (1.0 + drift * std::sin(kTwoPi * t / period + phi));
      s -= (Revolutions(t, drift, phi) - target) / rate * kFs;
    }
    warp[i] = s;
  }
  return warp;
}

// Largest |a - b| over the inner 90 % of the block, a constant offset removed (the angle
// origin does not matter to a synchronous average).
double MaxErrorInside(const std::vector<double>& a, const std::vector<double>& b) {
  const std::size_t lo = kN / 20;
  const std::size_t hi = kN - kN / 20;
  double mean = 0.0;
  for (std::size_t i = lo; i < hi; ++i) mean += a[i] - b[i];
  mean /= static_cast<double>(hi - lo);
  double worst = 0.0;
  for (std::size_t i = lo; i < hi; ++i) worst = std::max(worst, std::abs(a[i] - b[i] - mean));
  return worst;
}

std::vector<double> Identity() {
  std::vector<double> identity(kN);
  for (std::size_t i = 0; i < kN; ++i) identity[i] = static_cast<double>(i);
  return identity;
}

Result<OrderTrackResult> Track(const std::vector<double>& x, std::vector<double>& warp,
                               double carrier_hz = kTeeth * kShaftHz, double half_band = 3.5) {
  auto tracker = OrderTracker::Create(kN, kFs);
  EXPECT_TRUE(tracker.ok()) << tracker.error();
  warp.assign(kN, 0.0);
  return tracker->Track(x, carrier_hz, half_band, warp);
}

// Amplitude of mesh harmonic h in the shaft's synchronous average (with or without a warp).
double MeshHarmonicInAverage(const std::vector<double>& x, int h,
                             const std::vector<double>& warp) {
  auto tsa = SynchronousAverage::Create(kN, kFs, 1024);
  EXPECT_TRUE(tsa.ok());
  SynchronousAverageRecord record = tsa->MakeRecord();
  EXPECT_TRUE(tsa->Process(x, kShaftHz, record, warp).ok());
  return std::abs(record.orders()[static_cast<std::size_t>(h * kTeeth)]);
}

TEST(OrderTrackerTest, FollowsASinusoidalDriftToTheAnalyticWarp) {
  for (double phi : {0.0, 1.3, 4.0}) {
    const std::vector<double> x = GearSignal(kDrift, phi, 0.0, 0.05);
    std::vector<double> warp;
    const auto r = Track(x, warp);
    ASSERT_TRUE(r.ok()) << r.error();
    const std::vector<double> truth = TrueWarp(kDrift, phi);
    // The drift moves the angle by about f0 a T / 2 pi = 0.0048 rev (3.8 samples) each way;
    // tracked, 0.06 samples are left (0.04 rad at the 900 Hz harmonic).
    EXPECT_GT(MaxErrorInside(truth, Identity()), 3.0) << "phi " << phi;
    EXPECT_LT(MaxErrorInside(warp, truth), 0.1) << "phi " << phi;
  }
}

// The phase is taken only where the fit weighs it, four, two and one value at a time
// (PhaseAngles; its own test checks the angles): weighted stretches of every length modulo 4
// track as well as the default one.
TEST(OrderTrackerTest, TracksWhateverTheLengthOfItsWeightedStretch) {
  const std::vector<double> x = GearSignal(kDrift, 1.3, 0.0, 0.05);
  const std::vector<double> truth = TrueWarp(kDrift, 1.3);
  for (const double edge : {0.05, 0.0502, 0.0503, 0.0504}) {  // 7600 .. 7593 weighted samples
    OrderTrackerOptions options;
    options.edge_fraction = edge;
    auto tracker = OrderTracker::Create(kN, kFs, options);
    ASSERT_TRUE(tracker.ok()) << tracker.error();
    std::vector<double> warp(kN);
    const auto r = tracker->Track(x, kTeeth * kShaftHz, 3.5, warp);
    ASSERT_TRUE(r.ok()) << r.error();
    EXPECT_LT(MaxErrorInside(warp, truth), 0.1) << "edge fraction " << edge;
    EXPECT_LT(r->phase_residual_rad, 0.1) << "edge fraction " << edge;
  }
}

TEST(OrderTrackerTest, TrackedAverageKeepsTheMeshHarmonicsThatDriftSmears) {
  const std::vector<double> x = GearSignal(kDrift, 0.7, 0.0, 0.05);
  std::vector<double> warp;
  ASSERT_TRUE(Track(x, warp).ok());
  const double plain = MeshHarmonicInAverage(x, 3, {});
  const double tracked = MeshHarmonicInAverage(x, 3, warp);
  // Third mesh harmonic (900 Hz, amplitude 0.3; cubic interpolation droop < 0.1 % there).
  EXPECT_GT(tracked, 0.3 * 0.98);
  EXPECT_LT(plain, 0.3 * 0.8);
}

TEST(OrderTrackerTest, ConstantSpeedGivesTheIdentityUnderNoise) {
  const std::vector<double> x = GearSignal(0.0, 0.0, 0.0, 0.3);
  std::vector<double> warp;
  const auto r = Track(x, warp);
  ASSERT_TRUE(r.ok()) << r.error();
  // 30 % noise: 0.15 samples (0.1 rad at 900 Hz, a 0.5 % loss of that harmonic's average).
  EXPECT_LT(MaxErrorInside(warp, Identity()), 0.25);
}

TEST(OrderTrackerTest, DoesNotTrackAToothFaultsShaftRateModulation) {
  // 0.5 rad of mesh phase modulation at the shaft rate: tracked as speed it would move the
  // angle by 0.5 / (2 pi 300 Hz) = 2.1 samples.
  // The band is the pipeline's: +/- 3/4 of the shaft rate, the sidebands at +/- 1 x outside.
  const std::vector<double> x = GearSignal(0.0, 0.0, 0.5, 0.05);
  std::vector<double> warp;
  ASSERT_TRUE(Track(x, warp, kTeeth * kShaftHz, 0.75 * kShaftHz).ok());
  EXPECT_LT(MaxErrorInside(warp, Identity()), 0.1);
}

// A foreign line inside the carrier's band (a pump tone 2.5 Hz off the mesh fundamental, as
// strong as it) beats with it and is tracked as speed; the clean second harmonic next door
// tracks the same drift. The phase residual tells them apart, which is how the condition stage
// picks its carrier among the mesh harmonics.
TEST(OrderTrackerTest, AForeignLineInTheBandShowsInThePhaseResidual) {
  std::vector<double> x = GearSignal(kDrift, 1.3, 0.0, 0.05);
  for (std::size_t i = 0; i < kN; ++i) {
    x[i] += std::cos(kTwoPi * 302.5 * static_cast<double>(i) / kFs + 0.4);
  }
  const std::vector<double> truth = TrueWarp(kDrift, 1.3);
  auto tracker = OrderTracker::Create(kN, kFs);
  ASSERT_TRUE(tracker.ok()) << tracker.error();
  std::vector<double> fundamental(kN);
  std::vector<double> second(kN);
  const double band = 0.75 * kShaftHz;
  const auto contaminated = tracker->TryTrack(x, kTeeth * kShaftHz, band, fundamental);
  const auto clean = tracker->TryTrack(x, 2 * kTeeth * kShaftHz, band, second);
  ASSERT_TRUE(clean.has_value());
  // The clean harmonic follows the drift (3.8 samples each way) to 0.02 samples ...
  EXPECT_LT(MaxErrorInside(second, truth), 0.1);
  // ... and its residual is the smaller one: the fundamental is either refused or tracked
  // worse (0.29 rad of residual and 28 samples off, against 0.006 rad).
  if (contaminated.has_value()) {
    EXPECT_LT(clean->phase_residual_rad, contaminated->phase_residual_rad);
    EXPECT_GT(MaxErrorInside(fundamental, truth), 2.0 * MaxErrorInside(second, truth));
  }
  // TryTrack() is Track() without the message.
  std::vector<double> again(kN);
  const auto tracked = tracker->Track(x, 2 * kTeeth * kShaftHz, band, again);
  ASSERT_TRUE(tracked.ok()) << tracked.error();
  EXPECT_EQ(tracked->phase_residual_rad, clean->phase_residual_rad);
  EXPECT_EQ(again, second);
}

// A band narrow enough to keep a fault's shaft-rate sidebands out also cuts off part of a
// drift's FM sidebands (at the 900 Hz harmonic the drift moves the phase by about 2.7 rad at
// one cycle per block; a +/- 2 Hz band keeps its first two sideband pairs). A free fit reads
// what is cut as a mean speed that is off; the block's speed_hz is its mean speed, and the
// tracker keeps it unless told otherwise.
TEST(OrderTrackerTest, KeepsTheNominalMeanSpeedWhereTheBandCutsTheDriftsSidebands) {
  const std::vector<double> x = GearSignal(kDrift, 1.3, 0.0, 0.05);
  const std::vector<double> truth = TrueWarp(kDrift, 1.3);  // ends at kN - 1: mean speed f0
  auto kept = OrderTracker::Create(kN, kFs);
  OrderTrackerOptions free_options;
  free_options.keep_mean_speed = false;
  auto free = OrderTracker::Create(kN, kFs, free_options);
  ASSERT_TRUE(kept.ok() && free.ok());
  std::vector<double> kept_warp(kN);
  std::vector<double> free_warp(kN);
  const double carrier = 3 * kTeeth * kShaftHz;
  const auto with_mean = kept->Track(x, carrier, 2.0, kept_warp);
  const auto without = free->Track(x, carrier, 2.0, free_warp);
  ASSERT_TRUE(with_mean.ok()) << with_mean.error();
  ASSERT_TRUE(without.ok()) << without.error();
  EXPECT_NEAR(kept_warp[kN - 1], static_cast<double>(kN - 1), 1e-6);
  EXPECT_NEAR(with_mean->mean_speed_ratio, 1.0, 1e-9);
  // Free: the block's end about a sample off, 0.23 samples of error inside; kept: 0.10.
  EXPECT_GT(std::abs(free_warp[kN - 1] - static_cast<double>(kN - 1)), 0.5);
  EXPECT_LT(MaxErrorInside(kept_warp, truth), 0.15);
  EXPECT_LT(MaxErrorInside(kept_warp, truth), 0.7 * MaxErrorInside(free_warp, truth));
}

// Three carriers' warps, each the analytic one plus an error of its own: the median follows
// the two that agree at every sample, and increases.
TEST(OrderTrackerTest, TheMedianOfSeveralWarpsFollowsTheOnesThatAgree) {
  const std::vector<double> truth = TrueWarp(kDrift, 0.4);
  std::vector<double> warps(3 * kN);
  for (std::size_t i = 0; i < kN; ++i) {
    const double x = static_cast<double>(i) / static_cast<double>(kN - 1);
    warps[i] = truth[i] + 0.1 * std::sin(kTwoPi * x);       // close
    warps[kN + i] = truth[i] - 0.1 * std::sin(kTwoPi * x);  // close, the other way
    warps[2 * kN + i] = truth[i] + 12.0 * x * (1.0 - x);    // a carrier gone astray
  }
  std::vector<double> median(kN, -1.0);
  MedianOfWarps(warps, 3, median);
  for (std::size_t i = 0; i < kN; ++i) {
    const double a = warps[i];
    const double b = warps[kN + i];
    const double c = warps[2 * kN + i];
    EXPECT_EQ(median[i], std::max(std::min(a, b), std::min(std::max(a, b), c))) << i;
    ASSERT_LE(std::abs(median[i] - truth[i]), 0.1 + 1e-12) << i;
    if (i > 0) {
      ASSERT_GT(median[i], median[i - 1]) << i;
    }
  }
  // Two warps: their mean. Out of range: left as it is.
  MedianOfWarps(std::span<const double>(warps).first(2 * kN), 2, median);
  EXPECT_NEAR(median[kN / 3], truth[kN / 3], 1e-9);
  std::vector<double> untouched(kN, -1.0);
  MedianOfWarps(warps, 0, untouched);
  MedianOfWarps(warps, kMaxMedianWarps + 1, untouched);
  EXPECT_EQ(untouched, std::vector<double>(kN, -1.0));
}

TEST(OrderTrackerTest, RefusesWhatItCannotTrack) {
  std::vector<double> warp;
  const std::vector<double> x = GearSignal(0.0, 0.0, 0.0, 0.05);
  auto outside = Track(x, warp, 3999.0, 3.5);
  ASSERT_FALSE(outside.ok());
  EXPECT_NE(outside.error().find("does not fit"), std::string::npos) << outside.error();
  auto narrow = Track(x, warp, 300.0, 0.6);
  ASSERT_FALSE(narrow.ok());
  EXPECT_NE(narrow.error().find("need at least 3"), std::string::npos) << narrow.error();
  auto silent = Track(std::vector<double>(kN, 0.0), warp);
  ASSERT_FALSE(silent.ok());
  EXPECT_NE(silent.error().find("carrier absent"), std::string::npos) << silent.error();
  for (unsigned seed = 1; seed < 6; ++seed) {
    auto noise = Track(dsp_test::WhiteNoise(kN, 1.0, seed), warp);
    ASSERT_FALSE(noise.ok()) << "seed " << seed;
    EXPECT_NE(noise.error().find("carrier absent"), std::string::npos) << noise.error();
  }
  std::vector<double> bad = x;
  bad[10] = std::nan("");
  auto nan = Track(bad, warp);
  ASSERT_FALSE(nan.ok());
  EXPECT_NE(nan.error().find("non-finite"), std::string::npos) << nan.error();
  EXPECT_FALSE(OrderTracker::Create(32, kFs).ok());
  EXPECT_FALSE(OrderTracker::Create(kN, 0.0).ok());
}

}  // namespace
}  // namespace gearpath
