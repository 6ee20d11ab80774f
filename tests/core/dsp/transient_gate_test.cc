#include "core/dsp/transient_gate.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/dsp/order_tracker.h"
#include "core/dsp/synchronous_average.h"
#include "tests/core/dsp/test_signals.h"

namespace gearpath {
namespace {

using dsp_test::kTwoPi;

constexpr double kFs = 8000.0;
constexpr std::size_t kN = 16000;

// A shaft's signal as a function of its angle in revolutions: harmonics 1..40 with fixed
// amplitudes and phases.
double ShaftSignal(double revolutions) {
  double v = 0.0;
  for (int k = 1; k <= 40; ++k) v += (1.0 / k) * std::cos(kTwoPi * k * revolutions + 0.37 * k * k);
  return v;
}

// A decaying burst e^{-t / tau} sin(2 pi f t) added from sample `at`; returns it alone.
std::vector<double> AddBurst(std::vector<double>& x, std::size_t at, double peak, double f,
                             double tau) {
  std::vector<double> burst(x.size(), 0.0);
  for (std::size_t i = at; i < x.size(); ++i) {
    const double t = static_cast<double>(i - at) / kFs;
    if (t > 12.0 * tau) break;
    burst[i] = peak * std::exp(-t / tau) * std::sin(kTwoPi * f * t);
    x[i] += burst[i];
  }
  return burst;
}

double Energy(const std::vector<double>& x, std::size_t from, std::size_t to) {
  double e = 0.0;
  for (std::size_t i = from; i < to; ++i) e += x[i] * x[i];
  return e;
}

TransientGate MakeGate() {
  auto gate = TransientGate::Create(kN, kFs);
  EXPECT_TRUE(gate.ok()) << gate.error();
  return std::move(gate).value();
}

// What the gate is for: on a residual of noise and another machine's tones, it returns the
// bursts (most of their energy, nothing away from them) and leaves the tones.
TEST(TransientGate, EstimatesTheBurstsAmongNoiseAndTonesAndNothingElse) {
  TransientGate gate = MakeGate();
  EXPECT_EQ(gate.window(), 16u);  // 2 ms
  std::vector<double> x = dsp_test::WhiteNoise(kN, 0.05, 21);
  for (double f : {331.0, 597.5, 1204.0}) {  // a pump's tones, ten times the noise's RMS
    const std::vector<double> tone = dsp_test::Cosine(kN, kFs, f, 0.7, 0.3 * f);
    for (std::size_t i = 0; i < kN; ++i) x[i] += tone[i];
  }
  std::vector<double> transient(kN);
  EXPECT_EQ(gate.Estimate(x, transient), 0u) << "noise and tones alone";
  EXPECT_EQ(Energy(transient, 0, kN), 0.0);

  std::vector<double> bursts(kN, 0.0);
  const std::vector<double> a = AddBurst(x, 4001, 1.5, 1800.0, 4e-3);
  const std::vector<double> b = AddBurst(x, 9517, 1.0, 900.0, 6e-3);
  for (std::size_t i = 0; i < kN; ++i) bursts[i] = a[i] + b[i];
  const std::size_t marked = gate.Estimate(x, transient);
  EXPECT_GT(marked, 0u);
  EXPECT_LT(marked, 4000u) << "a quarter of the block";
  // Nothing is taken before a burst's window (4000..4015) and the guard window before it...
  EXPECT_EQ(Energy(transient, 0, 3984), 0.0);
  // ... the bursts are: over each one's first five time constants, what is left of it is under
  // 10 % of its energy ...
  std::vector<double> left(kN);
  for (std::size_t i = 0; i < kN; ++i) left[i] = bursts[i] - transient[i];
  EXPECT_LT(Energy(left, 4001, 4161), 0.1 * Energy(bursts, 4001, 4161));
  EXPECT_LT(Energy(left, 9517, 9757), 0.1 * Energy(bursts, 9517, 9757));
  // ... and after them, where a stretch runs on until the broadband part has a quiet window,
  // what is taken is the noise, not the tones: per sample, about the noise's variance, against
  // 0.74 for the three tones together.
  double beyond = 0.0;
  std::size_t samples = 0;
  for (std::size_t i = 0; i < kN; ++i) {
    if (transient[i] == 0.0 || (i >= 4001 && i < 4161) || (i >= 9517 && i < 9757)) continue;
    beyond += transient[i] * transient[i];
    ++samples;
  }
  if (samples > 0) {
    EXPECT_LT(beyond / static_cast<double>(samples), 3.0 * 0.05 * 0.05);
  }
}

// The gate is scale-free (whitening, ratios to medians) over its domain: a residual at the top
// of the float range (a block of float samples can hold no larger) gives the same marks and an
// estimate as many times larger.
TEST(TransientGate, MarksTheSameSamplesAtTheTopOfTheFloatRange) {
  TransientGate gate = MakeGate();
  std::vector<double> x = dsp_test::WhiteNoise(kN, 0.05, 23);
  (void)AddBurst(x, 6007, 1.2, 1500.0, 5e-3);
  std::vector<double> transient(kN);
  const std::size_t marked = gate.Estimate(x, transient);
  ASSERT_GT(marked, 0u);
  constexpr double kScale = 1e38;
  std::vector<double> huge(kN);
  for (std::size_t i = 0; i < kN; ++i) huge[i] = kScale * x[i];
  std::vector<double> huge_transient(kN);
  EXPECT_EQ(gate.Estimate(huge, huge_transient), marked);
  for (std::size_t i = 0; i < kN; ++i) {
    ASSERT_TRUE(std::isfinite(huge_transient[i])) << i;
    EXPECT_NEAR(huge_transient[i] / kScale, transient[i], 1e-9) << i;
  }
}

TEST(TransientGate, RefusesSpansOfAnotherLengthAndTooShortBlocks) {
  TransientGate gate = MakeGate();
  std::vector<double> x = dsp_test::WhiteNoise(kN, 0.05, 22);
  AddBurst(x, 4001, 1.5, 1800.0, 4e-3);
  std::vector<double> transient(kN - 1, 1.0);
  EXPECT_EQ(gate.Estimate(x, transient), 0u);
  EXPECT_FALSE(TransientGate::Create(63, kFs).ok());
  EXPECT_FALSE(TransientGate::Create(kN, std::nan("")).ok());
}

TEST(InvertWarp, ReturnsTheUniformPositionOfEverySample) {
  // warp(s) = s + 40 sin(2 pi s / N): increasing (slope >= 1 - 80 pi / N > 0).
  std::vector<double> warp(kN), nominal(kN);
  for (std::size_t s = 0; s < kN; ++s) {
    warp[s] = static_cast<double>(s) + 40.0 * std::sin(kTwoPi * static_cast<double>(s) / kN);
  }
  InvertWarp(warp, nominal);
  for (std::size_t i = 0; i < kN; i += 97) {
    const double u = nominal[i];
    ASSERT_GE(u, 0.0);
    ASSERT_LE(u, static_cast<double>(kN - 1));
    const auto k = std::min(static_cast<std::size_t>(u), kN - 2);
    const double at = warp[k] + (u - static_cast<double>(k)) * (warp[k + 1] - warp[k]);
    EXPECT_NEAR(at, static_cast<double>(i), 1e-9) << i;
  }
}

// A shaft's signal on a drifting shaft less its revolution median (on the warp that describes
// the drift) leaves almost nothing; a burst in one revolution is left almost whole, since the
// median does not hold it (the mean would hold 1/R of it and subtract it from every revolution).
TEST(SubtractPeriodicPart, RemovesTheShaftAndKeepsTheBurstWhole) {
  const double shaft_hz = 7.0;  // 13 revolutions
  const double drift = 0.003;
  std::vector<double> warp(kN), nominal(kN), x(kN);
  for (std::size_t s = 0; s < kN; ++s) {
    const double u = static_cast<double>(s);
    warp[s] = u - drift * kN / kTwoPi * std::sin(kTwoPi * u / kN);
  }
  InvertWarp(warp, nominal);
  for (std::size_t i = 0; i < kN; ++i) x[i] = ShaftSignal(shaft_hz * nominal[i] / kFs);
  std::vector<double> with_burst = x;
  const std::vector<double> burst = AddBurst(with_burst, 6001, 2.0, 900.0, 5e-3);

  auto tsa = SynchronousAverage::Create(kN, kFs, 4096);
  ASSERT_TRUE(tsa.ok()) << tsa.error();
  SynchronousAveragePlan plan = tsa->MakePlan();
  ASSERT_TRUE(tsa->Plan(shaft_hz, plan, warp).ok());
  ASSERT_EQ(plan.revolutions, 13u);
  std::vector<double> median(plan.points_per_revolution);
  PeriodicReadPlan read = MakePeriodicReadPlan(kN);
  ASSERT_TRUE(PlanPeriodicRead(plan.points_per_revolution, shaft_hz / kFs, nominal, read));
  std::vector<double> scratch(plan.points_per_revolution + 3);

  const Result<CheckedSignal> clean = tsa->Check(x);
  ASSERT_TRUE(clean.ok());
  ASSERT_TRUE(tsa->RevolutionMedian(clean.value(), plan, median).ok());
  std::vector<double> residual = x;
  SubtractPeriodicPart(residual, median, read, scratch);
  // Away from the block's ends (where the warp is extrapolated), the shaft is gone to the
  // interpolation's accuracy: under 1 % of the signal's RMS anywhere.
  double worst = 0.0;
  for (std::size_t i = 100; i + 100 < kN; ++i) worst = std::max(worst, std::abs(residual[i]));
  EXPECT_LT(worst, 0.01 * dsp_test::Rms(x));

  const Result<CheckedSignal> hit = tsa->Check(with_burst);
  ASSERT_TRUE(hit.ok());
  ASSERT_TRUE(tsa->RevolutionMedian(hit.value(), plan, median).ok());
  residual = with_burst;
  SubtractPeriodicPart(residual, median, read, scratch);
  std::vector<double> error(kN);
  for (std::size_t i = 0; i < kN; ++i) error[i] = residual[i] - burst[i];
  EXPECT_LT(Energy(error, 100, kN - 100), 1e-3 * Energy(burst, 0, kN));

  // A median span of another size is refused.
  std::vector<double> wrong(plan.points_per_revolution + 1);
  EXPECT_FALSE(tsa->RevolutionMedian(hit.value(), plan, wrong).ok());
}

// On a grid that falls on the samples (64 samples per revolution: M = 64, every stencil reads
// one sample), the revolution median is the median of the samples at each angle, for an odd
// and an even number of revolutions and any order of the values.
TEST(SynchronousAverageRevolutionMedian, IsTheMedianOfTheRevolutionsAtEveryPoint) {
  for (const std::size_t revolutions : {1u, 2u, 5u, 8u, 13u, 20u}) {
    SCOPED_TRACE(revolutions);
    const std::size_t n = 64 * revolutions + 1;
    const std::vector<double> x =
        dsp_test::WhiteNoise(n, 1.0, static_cast<unsigned>(30 + revolutions));
    auto tsa = SynchronousAverage::Create(n, kFs, 4096);
    ASSERT_TRUE(tsa.ok()) << tsa.error();
    SynchronousAveragePlan plan = tsa->MakePlan();
    ASSERT_TRUE(tsa->Plan(kFs / 64.0, plan).ok());
    ASSERT_EQ(plan.points_per_revolution, 64u);
    ASSERT_EQ(plan.revolutions, revolutions);
    const Result<CheckedSignal> checked = tsa->Check(x);
    ASSERT_TRUE(checked.ok());
    std::vector<double> median(64);
    ASSERT_TRUE(tsa->RevolutionMedian(checked.value(), plan, median).ok());
    for (std::size_t m = 0; m < 64; ++m) {
      std::vector<double> column;
      for (std::size_t r = 0; r < revolutions; ++r) column.push_back(x[r * 64 + m]);
      std::sort(column.begin(), column.end());
      const std::size_t half = revolutions / 2;
      const double expected =
          revolutions % 2 == 1 ? column[half] : 0.5 * (column[half] + column[half - 1]);
      ASSERT_EQ(median[m], expected) << m;
    }
  }
}

}  // namespace
}  // namespace gearpath
