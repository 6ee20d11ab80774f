#include "core/dsp/synchronous_average.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstddef>
#include <limits>
#include <numbers>
#include <vector>

#include "tests/core/dsp/test_signals.h"

// The allocation-free claim of Process() is checked with a counting operator new in
// tests/core/diagnosis/gear_condition_indicators_test.cc (this executable already replaces
// operator new in allocation_test.cc, and a second replacement would not link).

namespace gearpath {
namespace {

using dsp_test::kTwoPi;

constexpr double kFs = 10000.0;
constexpr double kShaftHz = 12.3;  // 813.0 samples per revolution: M = 1024, off the sample grid

struct Averaged {
  SynchronousAverageRecord record;
  Status status;
};

Averaged Average(const std::vector<double>& x, double shaft_hz, double fs = kFs,
                 std::size_t max_points = 4096) {
  auto stage = SynchronousAverage::Create(x.size(), fs, max_points);
  EXPECT_TRUE(stage.ok()) << stage.error();
  Averaged a{stage->MakeRecord(), Status::Ok()};
  a.status = stage->Process(x, shaft_hz, a.record);
  return a;
}

// x(t) = a cos(2 pi order f t + phi) sampled at fs.
std::vector<double> OrderTone(std::size_t n, double fs, double shaft_hz, double order, double a,
                              double phi) {
  return dsp_test::Cosine(n, fs, order * shaft_hz, a, phi);
}

double Rms(std::span<const double> x) {
  double s = 0.0;
  for (double v : x) s += v * v;
  return std::sqrt(s / static_cast<double>(x.size()));
}

// Coherent gain of 4-point cubic Lagrange interpolation for a tone of normalised frequency
// nu = f / fs, averaged over uniformly spread fractional positions: the Fourier transform of
// the interpolation kernel at 2 pi nu (midpoint rule, independent of the code under test).
double CubicLagrangeMeanGain(double nu) {
  const int steps = 20000;
  const double w = kTwoPi * nu;
  std::complex<double> sum = 0.0;
  for (int i = 0; i < steps; ++i) {
    const double d = (i + 0.5) / steps;  // fraction past the second stencil node
    const double t = d + 1.0;
    const double l[4] = {-(t - 1) * (t - 2) * (t - 3) / 6, t * (t - 2) * (t - 3) / 2,
                         -t * (t - 1) * (t - 3) / 2, t * (t - 1) * (t - 2) / 6};
    for (int j = 0; j < 4; ++j) sum += l[j] * std::polar(1.0, w * (j - 1 - d));
  }
  return std::abs(sum) / steps;
}

TEST(SynchronousAverage, ReportsThePowerOfTwoPointsPerRevolutionAndTheWholeRevolutions) {
  const std::vector<double> x(16384, 0.0);
  const Averaged a = Average(x, kShaftHz);
  ASSERT_TRUE(a.status.ok()) << a.status.error();
  EXPECT_EQ(a.record.points_per_revolution, 1024u);  // 813 -> 1024
  EXPECT_EQ(a.record.revolutions, 20u);              // 16383 / 813.0 = 20.2
  EXPECT_NEAR(a.record.nyquist_order, kFs / (2 * kShaftHz), 1e-9);
  EXPECT_EQ(a.record.tsa().size(), 1024u);
  EXPECT_EQ(a.record.orders().size(), 513u);

  const Averaged capped = Average(x, kShaftHz, kFs, 512);
  ASSERT_TRUE(capped.status.ok());
  EXPECT_EQ(capped.record.points_per_revolution, 512u);
  const Averaged fast = Average(x, 4000.0);  // 2.5 samples per revolution: the floor of 4
  ASSERT_TRUE(fast.status.ok());
  EXPECT_EQ(fast.record.points_per_revolution, 4u);
}

TEST(SynchronousAverage, CosineAtAShaftOrderKeepsItsAmplitudeAndPhaseWithinOnePercent) {
  // Orders 10..110 span 0.012 fs..0.135 fs, where the cubic droop stays below 1 % (it reaches
  // 1 % at 0.147 fs).
  for (const int k : {10, 34, 68, 102, 110}) {
    const double a = 1.7;
    const double phi = 0.6;
    const Averaged avg = Average(OrderTone(16384, kFs, kShaftHz, k, a, phi), kShaftHz);
    ASSERT_TRUE(avg.status.ok()) << avg.status.error();
    const auto orders = avg.record.orders();
    EXPECT_NEAR(std::abs(orders[k]) / a, 1.0, 0.01) << "order " << k;
    EXPECT_NEAR(std::arg(orders[k]), phi, 0.01) << "order " << k;
    double other = 0.0;
    for (std::size_t j = 0; j < orders.size(); ++j) {
      if (j != static_cast<std::size_t>(k)) other = std::max(other, std::abs(orders[j]));
    }
    EXPECT_LT(other, 0.01 * a) << "order " << k;
    // The TSA is that cosine over one revolution.
    EXPECT_NEAR(*std::max_element(avg.record.tsa().begin(), avg.record.tsa().end()), a, 0.02 * a);
  }
}

TEST(SynchronousAverage, HighOrderDroopIsTheCubicLagrangeKernelGain) {
  // Measured interpolation error at high orders: the amplitude read at order k is the mean
  // coherent gain of the cubic interpolator at k f / fs (0.93 at fs/4, 0.67 at 0.4 fs).
  for (const int k : {163, 203, 244, 325}) {  // 0.20, 0.25, 0.30, 0.40 fs
    const double nu = k * kShaftHz / kFs;
    const Averaged avg = Average(OrderTone(16384, kFs, kShaftHz, k, 1.0, 0.0), kShaftHz);
    ASSERT_TRUE(avg.status.ok());
    const double gain = std::abs(avg.record.orders()[k]);
    const double expected = CubicLagrangeMeanGain(nu);
    EXPECT_NEAR(gain, expected, 0.005) << "order " << k << " at " << nu << " fs";
    RecordProperty("gain_at_" + std::to_string(k), std::to_string(gain));
  }
  EXPECT_NEAR(CubicLagrangeMeanGain(0.25), 0.927, 0.001);
}

TEST(SynchronousAverage, OnTheSampleGridTheTsaIsExactAtEveryOrder) {
  // fs / f = 512 = M: every angle falls on a sample, so nothing is interpolated.
  const double fs = 8192.0;
  const double f = 16.0;
  const int k = 200;  // 0.39 fs
  const Averaged avg = Average(OrderTone(8192, fs, f, k, 2.0, -1.1), f, fs);
  ASSERT_TRUE(avg.status.ok());
  ASSERT_EQ(avg.record.points_per_revolution, 512u);
  EXPECT_NEAR(std::abs(avg.record.orders()[k] - std::polar(2.0, -1.1)), 0.0, 1e-10);
}

TEST(SynchronousAverage, HalfOrderToneFallsToOneOverROfItsAmplitudeForOddR) {
  // A tone at order k + 1/2 averaged over R revolutions: each revolution flips its sign, so the
  // average is a (1/R) sum_r (-1)^r = a / R for odd R (and 0 for even R). Its mean square over
  // the revolution is exactly 1/2 (2 (k + 1/2) is an integer), so RMS(TSA) = a / (R sqrt 2).
  const double a = 3.0;
  for (const std::size_t n : {std::size_t{17500}, std::size_t{16384}}) {  // R = 21, R = 20
    const Averaged avg = Average(OrderTone(n, kFs, kShaftHz, 40.5, a, 0.3), kShaftHz);
    ASSERT_TRUE(avg.status.ok());
    const std::size_t r = avg.record.revolutions;
    const double expected = r % 2 == 1 ? a / (static_cast<double>(r) * std::sqrt(2.0)) : 0.0;
    EXPECT_NEAR(Rms(avg.record.tsa()), expected, 0.01 * a / static_cast<double>(r)) << "R = " << r;
  }
}

TEST(SynchronousAverage, WhiteNoiseFallsLikeOneOverSquareRootOfR) {
  const double sigma = 1.0;
  const std::size_t per_rev = 813;
  const Averaged few = Average(dsp_test::WhiteNoise(4 * per_rev + 10, sigma, 3), kShaftHz);
  const Averaged many = Average(dsp_test::WhiteNoise(36 * per_rev + 40, sigma, 4), kShaftHz);
  ASSERT_TRUE(few.status.ok());
  ASSERT_TRUE(many.status.ok());
  ASSERT_EQ(few.record.revolutions, 4u);
  ASSERT_EQ(many.record.revolutions, 36u);
  // sqrt(36 / 4) = 3, within the scatter of a 1024-point RMS estimate.
  EXPECT_NEAR(Rms(few.record.tsa()) / Rms(many.record.tsa()), 3.0, 0.3);
  EXPECT_LT(Rms(many.record.tsa()), sigma / 6.0 * 1.1);
}

TEST(SynchronousAverage, OncePerRevolutionPulseGivesOnePulseAtItsAngle) {
  // A Gaussian pulse (sigma = 1.5 samples) at 0.3 of every revolution, on top of white noise.
  const std::size_t n = 16384;
  std::vector<double> x = dsp_test::WhiteNoise(n, 0.2, 11);
  const double angle = 0.3;
  for (double t0 = angle / kShaftHz; t0 * kFs < static_cast<double>(n); t0 += 1.0 / kShaftHz) {
    for (std::size_t i = 0; i < n; ++i) {
      const double u = (static_cast<double>(i) - t0 * kFs) / 1.5;
      if (std::abs(u) < 10.0) x[i] += 5.0 * std::exp(-0.5 * u * u);
    }
  }
  const Averaged avg = Average(x, kShaftHz);
  ASSERT_TRUE(avg.status.ok());
  const auto tsa = avg.record.tsa();
  const std::size_t m = tsa.size();
  const auto peak =
      static_cast<std::size_t>(std::max_element(tsa.begin(), tsa.end()) - tsa.begin());
  EXPECT_NEAR(static_cast<double>(peak), angle * static_cast<double>(m), 1.0);
  EXPECT_NEAR(tsa[peak], 5.0, 0.3);
  // One pulse: away from +/- 2 % of a revolution around it, nothing above the averaged noise
  // (0.2 / sqrt(20) = 0.045 RMS).
  for (std::size_t i = 0; i < m; ++i) {
    const double distance = std::abs(static_cast<double>(i) - static_cast<double>(peak));
    if (std::min(distance, static_cast<double>(m) - distance) > 0.02 * static_cast<double>(m)) {
      EXPECT_LT(std::abs(tsa[i]), 0.25) << "point " << i;
    }
  }
}

TEST(SynchronousAverage, OrdersAboveTheNyquistOrderAreZero) {
  std::vector<double> x = dsp_test::WhiteNoise(16384, 1.0, 5);
  const Averaged avg = Average(x, kShaftHz);
  ASSERT_TRUE(avg.status.ok());
  const auto orders = avg.record.orders();
  const auto top = static_cast<std::size_t>(std::floor(avg.record.nyquist_order));  // 406
  EXPECT_GT(std::abs(orders[top]), 0.0);
  for (std::size_t k = top + 1; k < orders.size(); ++k) EXPECT_EQ(std::abs(orders[k]), 0.0);
}

TEST(SynchronousAverage, CreateRejectsBadConfigurationNamingTheArgument) {
  auto bad_points = SynchronousAverage::Create(4096, kFs, 1000);
  ASSERT_FALSE(bad_points.ok());
  EXPECT_NE(bad_points.error().find("max points per revolution"), std::string::npos);
  EXPECT_FALSE(SynchronousAverage::Create(4096, kFs, 2).ok());
  auto bad_rate = SynchronousAverage::Create(4096, 0.0, 1024);
  ASSERT_FALSE(bad_rate.ok());
  EXPECT_NE(bad_rate.error().find("sample rate"), std::string::npos);
  auto short_block = SynchronousAverage::Create(3, kFs, 1024);
  ASSERT_FALSE(short_block.ok());
  EXPECT_NE(short_block.error().find("block length"), std::string::npos);
}

TEST(SynchronousAverage, ProcessRejectsBadInputNamingTheArgument) {
  auto stage = SynchronousAverage::Create(4096, kFs, 1024).value();
  SynchronousAverageRecord out = stage.MakeRecord();
  std::vector<double> x(4096, 0.0);
  for (const double f : {0.0, -5.0, std::numeric_limits<double>::quiet_NaN(),
                         std::numeric_limits<double>::infinity()}) {
    const Status s = stage.Process(x, f, out);
    ASSERT_FALSE(s.ok());
    EXPECT_NE(s.error().find("shaft_hz"), std::string::npos) << s.error();
  }
  const Status slow = stage.Process(x, 2.0, out);  // 5000 samples per revolution > 4096
  ASSERT_FALSE(slow.ok());
  EXPECT_NE(slow.error().find("less than one whole revolution"), std::string::npos);
  std::vector<double> wrong(4095, 0.0);
  const Status length = stage.Process(wrong, 20.0, out);
  ASSERT_FALSE(length.ok());
  EXPECT_NE(length.error().find("signal"), std::string::npos);
  x[77] = std::numeric_limits<double>::quiet_NaN();
  const Status nan = stage.Process(x, 20.0, out);
  ASSERT_FALSE(nan.ok());
  EXPECT_NE(nan.error().find("non-finite value at index 77"), std::string::npos);
  EXPECT_EQ(out.points_per_revolution, 0u);  // untouched
  x[77] = 0.0;
  SynchronousAverageRecord small = SynchronousAverage::Create(4096, kFs, 256)->MakeRecord();
  const Status record = stage.Process(x, 20.0, small);
  ASSERT_FALSE(record.ok());
  EXPECT_NE(record.error().find("record"), std::string::npos);
}

}  // namespace
}  // namespace gearpath

namespace gearpath {
namespace {

// One plan, many signals: Process(signal, plan) gives bit for bit what the one-step Process
// gives, with and without a warp, and a failed or foreign plan is refused.
TEST(SynchronousAveragePlan, SharedGridIsBitIdenticalToTheOneStepAverage) {
  constexpr std::size_t kN = 4096;
  auto stage = SynchronousAverage::Create(kN, kFs, 4096);
  ASSERT_TRUE(stage.ok());
  std::vector<double> warp(kN);
  for (std::size_t i = 0; i < kN; ++i) {
    warp[i] = static_cast<double>(i) +
              2.0 * std::sin(dsp_test::kTwoPi * static_cast<double>(i) / static_cast<double>(kN));
  }
  for (const bool warped : {false, true}) {
    const std::span<const double> wspan =
        warped ? std::span<const double>(warp) : std::span<const double>();
    SynchronousAveragePlan plan = stage->MakePlan();
    ASSERT_TRUE(stage->Plan(kShaftHz, plan, wspan).ok());
    for (unsigned seed : {1u, 2u, 3u}) {
      const std::vector<double> x = dsp_test::WhiteNoise(kN, 1.0, seed);
      SynchronousAverageRecord one = stage->MakeRecord();
      SynchronousAverageRecord two = stage->MakeRecord();
      ASSERT_TRUE(stage->Process(x, kShaftHz, one, wspan).ok());
      ASSERT_TRUE(stage->Process(x, plan, two).ok());
      ASSERT_EQ(one.revolutions, two.revolutions);
      ASSERT_EQ(one.points_per_revolution, two.points_per_revolution);
      for (std::size_t m = 0; m < one.tsa().size(); ++m) ASSERT_EQ(one.tsa()[m], two.tsa()[m]);
    }
  }
  SynchronousAveragePlan failed = stage->MakePlan();
  EXPECT_FALSE(stage->Plan(0.5, failed).ok());  // under one revolution in the block
  SynchronousAverageRecord out = stage->MakeRecord();
  const Status refused = stage->Process(dsp_test::WhiteNoise(kN, 1.0, 4), failed, out);
  ASSERT_FALSE(refused.ok());
  EXPECT_NE(refused.error().find("plan holds no grid"), std::string::npos) << refused.error();
  SynchronousAveragePlan foreign;  // not made by MakePlan()
  EXPECT_FALSE(stage->Plan(kShaftHz, foreign).ok());
}

// RevolutionSpread: a line locked to the shaft lands in `locked` at its amplitude squared (the
// Hann window's coherent gain is compensated; within the interpolation droop) with no spread.
TEST(SynchronousAverageRevolutionSpread, LockedLineHasItsPowerAndNoSpread) {
  const std::size_t n = 8000;
  const std::vector<double> x = OrderTone(n, kFs, kShaftHz, 5.0, 0.8, 0.4);
  auto stage = SynchronousAverage::Create(n, kFs, 4096).value();
  SynchronousAveragePlan plan = stage.MakePlan();
  ASSERT_TRUE(stage.Plan(kShaftHz, plan).ok());
  ASSERT_EQ(plan.points_per_revolution, 1024u);
  std::vector<double> locked(20), spread(20);
  const Status s = stage.RevolutionSpread(x, plan, locked, spread);
  ASSERT_TRUE(s.ok()) << s.error();
  EXPECT_NEAR(locked[5], 0.64, 0.64 * 1e-3);
  EXPECT_LT(spread[5], 1e-8);
  // The Hann window spreads the line over k +/- 1 at half amplitude, and nowhere else.
  EXPECT_NEAR(locked[4], 0.16, 0.16 * 1e-3);
  EXPECT_NEAR(locked[6], 0.16, 0.16 * 1e-3);
  EXPECT_LT(locked[8], 1e-8);
}

// Content in one revolution only (a burst) adds |B|^2 / R^2 to the mean and |B|^2 (R - 1) / R^2
// to the spread: locked = spread / (R - 1) at every order, exactly, whatever its spectrum.
TEST(SynchronousAverageRevolutionSpread, ABurstInOneRevolutionIsLockedOnlyAsMuchAsNoise) {
  const std::size_t n = 8000;
  std::vector<double> x(n, 0.0);
  for (std::size_t i = 200; i < 500; ++i) {
    const double t = static_cast<double>(i - 200);
    x[i] = std::exp(-t / 60.0) * std::sin(kTwoPi * 0.07 * t);
  }
  auto stage = SynchronousAverage::Create(n, kFs, 4096).value();
  SynchronousAveragePlan plan = stage.MakePlan();
  ASSERT_TRUE(stage.Plan(kShaftHz, plan).ok());
  const auto r = static_cast<double>(plan.revolutions);
  ASSERT_GE(r, 5.0);
  std::vector<double> locked(513), spread(513);
  ASSERT_TRUE(stage.RevolutionSpread(x, plan, locked, spread).ok());
  double total = 0.0;
  for (std::size_t k = 0; k < locked.size(); ++k) {
    EXPECT_NEAR(locked[k] * (r - 1.0), spread[k], 1e-9 * spread[k] + 1e-18) << "order " << k;
    total += spread[k];
  }
  EXPECT_GT(total, 1e-4);  // the burst is there
}

// ProcessWithSpread resamples each revolution once for both results: the TSA, its orders and
// the spread must be the bits of the two separate calls, on a constant-speed grid and a warped
// one, and what either call refuses it refuses.
TEST(SynchronousAverageRevolutionSpread, ProcessWithSpreadIsBitIdenticalToTheTwoCalls) {
  constexpr std::size_t kN = 8000;
  auto stage = SynchronousAverage::Create(kN, kFs, 4096).value();
  std::vector<double> warp(kN);
  for (std::size_t i = 0; i < kN; ++i) {
    warp[i] = static_cast<double>(i) +
              3.0 * std::sin(dsp_test::kTwoPi * static_cast<double>(i) / static_cast<double>(kN));
  }
  for (const bool warped : {false, true}) {
    SynchronousAveragePlan plan = stage.MakePlan();
    ASSERT_TRUE(stage.Plan(kShaftHz, plan, warped ? warp : std::span<const double>()).ok());
    ASSERT_GE(plan.revolutions, 5u);
    const std::size_t orders = plan.points_per_revolution / 2 + 1;
    const std::vector<double> x = dsp_test::WhiteNoise(kN, 1.0, warped ? 7u : 8u);
    SynchronousAverageRecord apart = stage.MakeRecord();
    SynchronousAverageRecord fused = stage.MakeRecord();
    std::vector<double> locked(orders), spread(orders), fused_locked(orders), fused_spread(orders);
    ASSERT_TRUE(stage.Process(x, plan, apart).ok());
    ASSERT_TRUE(stage.RevolutionSpread(x, plan, locked, spread).ok());
    const Status s = stage.ProcessWithSpread(x, plan, fused, fused_locked, fused_spread);
    ASSERT_TRUE(s.ok()) << s.error();
    ASSERT_EQ(fused.revolutions, apart.revolutions);
    ASSERT_EQ(fused.points_per_revolution, apart.points_per_revolution);
    for (std::size_t m = 0; m < apart.tsa().size(); ++m) ASSERT_EQ(fused.tsa()[m], apart.tsa()[m]);
    for (std::size_t k = 0; k < orders; ++k) {
      ASSERT_EQ(fused.orders()[k], apart.orders()[k]) << "order " << k;
      ASSERT_EQ(fused_locked[k], locked[k]) << "order " << k;
      ASSERT_EQ(fused_spread[k], spread[k]) << "order " << k;
    }
  }
  SynchronousAveragePlan none = stage.MakePlan();
  SynchronousAverageRecord out = stage.MakeRecord();
  std::vector<double> a(10), b(10), c(9);
  const Status no_grid = stage.ProcessWithSpread(std::vector<double>(kN, 1.0), none, out, a, b);
  ASSERT_FALSE(no_grid.ok());
  EXPECT_NE(no_grid.error().find("plan holds no grid"), std::string::npos) << no_grid.error();
  ASSERT_TRUE(stage.Plan(kShaftHz, none).ok());
  const Status unequal = stage.ProcessWithSpread(std::vector<double>(kN, 1.0), none, out, a, c);
  ASSERT_FALSE(unequal.ok());
  EXPECT_NE(unequal.error().find("equal counts"), std::string::npos) << unequal.error();
}

TEST(SynchronousAverageRevolutionSpread, RejectsSpansOfWrongSizesAndPlansWithoutAGrid) {
  const std::size_t n = 8000;
  const std::vector<double> x(n, 1.0);
  auto stage = SynchronousAverage::Create(n, kFs, 4096).value();
  SynchronousAveragePlan plan = stage.MakePlan();
  std::vector<double> a(10), b(10), c(9), big(514), big2(514);
  EXPECT_FALSE(stage.RevolutionSpread(x, plan, a, b).ok());  // no grid yet
  ASSERT_TRUE(stage.Plan(kShaftHz, plan).ok());
  const Status unequal = stage.RevolutionSpread(x, plan, a, c);
  ASSERT_FALSE(unequal.ok());
  EXPECT_NE(unequal.error().find("equal counts"), std::string::npos) << unequal.error();
  EXPECT_FALSE(stage.RevolutionSpread(x, plan, big, big2).ok());  // M/2 + 1 = 513
  std::vector<double> nan = x;
  nan[7] = std::nan("");
  EXPECT_FALSE(stage.RevolutionSpread(nan, plan, a, b).ok());
  EXPECT_TRUE(stage.RevolutionSpread(x, plan, a, b).ok());
}

// A plan whose revolutions were changed after Plan() (more than its grid holds, or none) is
// refused by every call that reads it, instead of reading past the grid.
TEST(SynchronousAveragePlan, PlansWhoseRevolutionsDoNotFitTheirGridAreRefused) {
  const std::size_t n = 8000;
  const std::vector<double> x(n, 1.0);
  auto stage = SynchronousAverage::Create(n, kFs, 4096).value();
  SynchronousAveragePlan plan = stage.MakePlan();
  ASSERT_TRUE(stage.Plan(kShaftHz, plan).ok());
  const Result<CheckedSignal> checked = stage.Check(x);
  ASSERT_TRUE(checked.ok());
  SynchronousAverageRecord record = stage.MakeRecord();
  std::vector<double> median(plan.points_per_revolution);
  ASSERT_TRUE(stage.Process(x, plan, record).ok());
  ASSERT_TRUE(stage.RevolutionMedian(checked.value(), plan, median).ok());
  for (const std::size_t revolutions :
       {std::size_t{0}, plan.grid.size() / plan.points_per_revolution + 1}) {
    SCOPED_TRACE(revolutions);
    SynchronousAveragePlan bad = plan;
    bad.revolutions = revolutions;
    const Status s = stage.Process(x, bad, record);
    ASSERT_FALSE(s.ok());
    EXPECT_NE(s.error().find("do not fit its grid"), std::string::npos) << s.error();
    EXPECT_FALSE(stage.RevolutionMedian(checked.value(), bad, median).ok());
  }
}

// A signal checked once serves every rate: the checked overloads give the bits of the span ones,
// and what Check() refuses (a wrong length, a non-finite sample) is named as Process() names it.
TEST(SynchronousAverageCheckedSignal, ServesEveryRateWithTheBitsOfTheSpanCalls) {
  constexpr std::size_t kN = 8000;
  auto stage = SynchronousAverage::Create(kN, kFs, 4096).value();
  const std::vector<double> x = dsp_test::WhiteNoise(kN, 1.0, 21);
  const Result<CheckedSignal> checked = stage.Check(x);
  ASSERT_TRUE(checked.ok()) << checked.error();
  for (const double shaft_hz : {kShaftHz, 0.61 * kShaftHz, 2.3 * kShaftHz}) {
    SynchronousAveragePlan plan = stage.MakePlan();
    ASSERT_TRUE(stage.Plan(shaft_hz, plan).ok());
    const std::size_t orders = plan.points_per_revolution / 2 + 1;
    SynchronousAverageRecord by_span = stage.MakeRecord();
    SynchronousAverageRecord by_check = stage.MakeRecord();
    ASSERT_TRUE(stage.Process(x, plan, by_span).ok());
    ASSERT_TRUE(stage.Process(checked.value(), plan, by_check).ok());
    for (std::size_t m = 0; m < by_span.tsa().size(); ++m) {
      ASSERT_EQ(by_check.tsa()[m], by_span.tsa()[m]) << shaft_hz << " Hz, point " << m;
    }
    std::vector<double> locked(orders), spread(orders), checked_locked(orders),
        checked_spread(orders);
    ASSERT_TRUE(stage.ProcessWithSpread(x, plan, by_span, locked, spread).ok());
    ASSERT_TRUE(
        stage.ProcessWithSpread(checked.value(), plan, by_check, checked_locked, checked_spread)
            .ok());
    for (std::size_t k = 0; k < orders; ++k) {
      ASSERT_EQ(by_check.orders()[k], by_span.orders()[k]) << shaft_hz << " Hz, order " << k;
      ASSERT_EQ(checked_locked[k], locked[k]) << shaft_hz << " Hz, order " << k;
      ASSERT_EQ(checked_spread[k], spread[k]) << shaft_hz << " Hz, order " << k;
    }
  }
  std::vector<double> nan = x;
  nan[4321] = std::numeric_limits<double>::infinity();
  const Result<CheckedSignal> refused = stage.Check(nan);
  ASSERT_FALSE(refused.ok());
  EXPECT_NE(refused.error().find("4321"), std::string::npos) << refused.error();
  EXPECT_FALSE(stage.Check(std::vector<double>(kN - 1, 0.0)).ok());
  // The plan and the record are still checked on a checked signal.
  SynchronousAveragePlan none = stage.MakePlan();
  SynchronousAverageRecord out = stage.MakeRecord();
  const Status no_grid = stage.Process(checked.value(), none, out);
  ASSERT_FALSE(no_grid.ok());
  EXPECT_NE(no_grid.error().find("plan holds no grid"), std::string::npos) << no_grid.error();
}

}  // namespace
}  // namespace gearpath
