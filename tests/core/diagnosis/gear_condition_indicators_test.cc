// Gear condition indicators against analytical truth: TSAs built from known order lines, so
// every expected value below is computed by hand from the signal's definition.
//
// This file also proves that SynchronousAverage::Process (core/dsp) and
// GearConditionIndicators::Compute allocate nothing, with test_diagnosis' one counting
// operator new (robust_baseline_test.cc); CountingAllocatorIsTheOneInUse guards against a
// vacuous pass.
#include "core/diagnosis/gear_condition_indicators.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdlib>
#include <limits>
#include <new>
#include <numbers>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "core/dsp/spectrum.h"
#include "core/dsp/synchronous_average.h"

// The counting operator new of this executable lives in robust_baseline_test.cc.
namespace diagnosis_alloc {
extern bool counting;
extern long allocations;
}  // namespace diagnosis_alloc

namespace gearpath {
namespace {

using CI = ConditionIndicator;
constexpr double kTwoPi = 2.0 * std::numbers::pi;

class CountAllocations {
 public:
  CountAllocations() {
    diagnosis_alloc::allocations = 0;
    diagnosis_alloc::counting = true;
  }
  ~CountAllocations() { diagnosis_alloc::counting = false; }
  long count() const { return diagnosis_alloc::allocations; }
};

// One revolution of M points and its amplitude-scaled order spectrum (Spectrum at fs = M, so
// bin k is order k).
struct Tsa {
  std::vector<double> x;
  std::vector<std::complex<double>> orders;
};

Tsa MakeTsa(std::vector<double> x) {
  auto spectrum = Spectrum::Create(x.size(), 1, static_cast<double>(x.size())).value();
  Tsa t{std::move(x), std::vector<std::complex<double>>(spectrum.bin_count())};
  EXPECT_TRUE(spectrum.Process(t.x, t.orders).ok());
  return t;
}

// sum of a_i cos(k_i theta + phi_i) over one revolution of m points.
struct Line {
  double order;
  double amplitude;
  double phase = 0.0;
};
std::vector<double> Lines(std::size_t m, std::initializer_list<Line> lines) {
  std::vector<double> x(m, 0.0);
  for (std::size_t i = 0; i < m; ++i) {
    const double theta = kTwoPi * static_cast<double>(i) / static_cast<double>(m);
    for (const Line& l : lines) x[i] += l.amplitude * std::cos(l.order * theta + l.phase);
  }
  return x;
}

void AddNoise(std::vector<double>& x, double sigma, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal(0.0, sigma);
  for (double& v : x) v += normal(rng);
}

// A Gaussian pulse of `height` and width `sigma` points centred on point `at` (wrapped).
void AddPulse(std::vector<double>& x, double at, double height, double sigma) {
  const auto m = static_cast<double>(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) {
    double d = std::abs(static_cast<double>(i) - at);
    d = std::min(d, m - d);
    x[i] += height * std::exp(-0.5 * d * d / (sigma * sigma));
  }
}

ConditionIndicatorValues Compute(const Tsa& t, std::vector<int> meshes, double na4_ref = 0.0,
                                 const IndicatorOptions& options = {}) {
  auto stage = GearConditionIndicators::Create(4096, options);
  EXPECT_TRUE(stage.ok()) << stage.error();
  ConditionIndicatorValues v;
  const Status s = stage->Compute(t.x, t.orders, meshes, na4_ref, v);
  EXPECT_TRUE(s.ok()) << s.error();
  return v;
}

TEST(GearConditionIndicators, EveryIndicatorHasASnakeCaseNameADescriptionAndAUnit) {
  std::set<std::string> names;
  for (std::size_t i = 0; i < kConditionIndicatorCount; ++i) {
    const auto id = static_cast<ConditionIndicator>(i);
    const std::string name(ConditionIndicatorName(id));
    EXPECT_NE(name, "unknown");
    EXPECT_TRUE(std::all_of(name.begin(), name.end(), [](char c) {
      return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_';
    })) << name;
    EXPECT_TRUE(names.insert(name).second) << "duplicate " << name;
    EXPECT_FALSE(ConditionIndicatorDescription(id).empty());
    EXPECT_TRUE(ConditionIndicatorUnit(id) == "1" || ConditionIndicatorUnit(id) == "signal");
  }
  EXPECT_LE(kConditionIndicatorCount, 16u);
  EXPECT_EQ(ConditionIndicatorName(CI::kFm4), "fm4");
  EXPECT_EQ(ConditionIndicatorName(CI::kCount), "unknown");
}

TEST(GearConditionIndicators, PureMeshHarmonicTsaHasNoResidualAndFm0IsPeakToPeakOverTheSum) {
  // cos(32 t) + 0.25 cos(64 t): with c = cos(32 t) it is 0.5 c^2 + c - 0.25, from -0.75 (c = -1)
  // to 1.25 (c = 1), both on the 1024-point grid. p2p = 2, harmonic sum = 1.25, FM0 = 1.6.
  const Tsa t = MakeTsa(Lines(1024, {{32, 1.0}, {64, 0.25}}));
  const ConditionIndicatorValues v = Compute(t, {32});
  EXPECT_NEAR(v[CI::kFm0], 2.0 / 1.25, 1e-12);
  EXPECT_NEAR(v[CI::kMeshHarmonics], 1.25, 1e-12);
  EXPECT_LT(v[CI::kResidualRms], 1e-12);
  EXPECT_LT(v.residual_variance, 1e-24);
  EXPECT_EQ(v[CI::kEnergyRatio], 0.0);
  EXPECT_EQ(v[CI::kFm4], 0.0);  // the difference signal is zero: its moments are reported 0
  EXPECT_LT(v[CI::kSidebandLevel], 1e-12);
  EXPECT_NEAR(v[CI::kTsaRms], std::sqrt((1.0 + 0.0625) / 2.0), 1e-12);
  EXPECT_NEAR(v.mesh_energy[0], (1.0 + 0.0625) / 2.0, 1e-12);
  EXPECT_LT(v.sideband_energy[0], 1e-24);
}

TEST(GearConditionIndicators, OffsetAndLowShaftOrdersBelongToNoResidual) {
  // DC, unbalance (order 1) and misalignment (order 2) are regular or dropped, not residual.
  const Tsa t = MakeTsa(Lines(1024, {{0, 0.7}, {1, 0.5, 0.3}, {2, 0.2, 1.0}, {34, 1.0}}));
  const ConditionIndicatorValues v = Compute(t, {34});
  EXPECT_LT(v[CI::kResidualRms], 1e-12);
  EXPECT_LT(v[CI::kResidualLowOrders], 1e-24);
  EXPECT_NEAR(v[CI::kMeshHarmonics], 1.0, 1e-12);
  // With L = 0 the shaft orders are residual: their energy, over the TSA's (DC excluded).
  IndicatorOptions no_shaft_orders;
  no_shaft_orders.low_shaft_orders = 0;
  const ConditionIndicatorValues w = Compute(t, {34}, 0.0, no_shaft_orders);
  const double shaft = (0.25 + 0.04) / 2.0;
  EXPECT_NEAR(w[CI::kResidualLowOrders], shaft / (shaft + 0.5), 1e-12);
}

TEST(GearConditionIndicators, Fm4OfAGaussianDifferenceSignalIsNearThree) {
  // Mesh harmonics plus white Gaussian noise: the difference signal is Gaussian noise (a subset
  // of its lines), kurtosis 3, 6th standardised moment 15, 8th 105. Sampling scatter with 4096
  // points: about 0.08, 1.6 and 22.
  std::vector<double> x = Lines(4096, {{34, 1.0}, {68, 0.4}, {102, 0.2}});
  AddNoise(x, 0.1, 7);
  const ConditionIndicatorValues v = Compute(MakeTsa(x), {34});
  EXPECT_NEAR(v[CI::kFm4], 3.0, 0.3);
  EXPECT_NEAR(v[CI::kM6a], 15.0, 5.0);
  EXPECT_NEAR(v[CI::kM8a], 105.0, 60.0);
  EXPECT_NEAR(v[CI::kNa4], 3.0, 0.3);  // no reference: the residual's own kurtosis
  // Residual variance: the noise's, less the few lines (1 + 2 + 120 mesh lines of 2048) removed.
  EXPECT_NEAR(v.residual_variance, 0.01, 0.001);
}

TEST(GearConditionIndicators, Na4AgainstTheHealthyVarianceGrowsWithTheResidualWhereFm4DoesNot) {
  std::vector<double> noise(2048, 0.0);
  AddNoise(noise, 0.05, 21);
  const std::vector<double> mesh = Lines(2048, {{40, 1.0}});
  std::vector<double> healthy(2048);
  std::vector<double> worse(2048);
  for (std::size_t i = 0; i < 2048; ++i) {
    healthy[i] = mesh[i] + noise[i];
    worse[i] = mesh[i] + 2.0 * noise[i];
  }
  const ConditionIndicatorValues h = Compute(MakeTsa(healthy), {40});
  const double reference = h.residual_variance;
  const ConditionIndicatorValues hr = Compute(MakeTsa(healthy), {40}, reference);
  const ConditionIndicatorValues w = Compute(MakeTsa(worse), {40}, reference);
  EXPECT_NEAR(hr[CI::kNa4], h[CI::kNa4], 1e-9);         // own variance = the reference
  EXPECT_NEAR(w[CI::kNa4] / hr[CI::kNa4], 16.0, 1e-6);  // residual x2: 4th moment x16
  EXPECT_NEAR(w[CI::kFm4], h[CI::kFm4], 1e-9);          // kurtosis is scale-free
  EXPECT_NEAR(w.residual_variance, 4.0 * reference, 1e-12);
}

TEST(GearConditionIndicators, OncePerRevolutionImpulseRaisesFm4WellAboveThreeAndTheResidual) {
  std::vector<double> healthy = Lines(1024, {{34, 1.0}, {68, 0.3}});
  AddNoise(healthy, 0.05, 3);
  std::vector<double> damaged = healthy;
  AddPulse(damaged, 0.0, 1.0, 1.5);  // on the TSA's crest
  const ConditionIndicatorValues h = Compute(MakeTsa(healthy), {34});
  const ConditionIndicatorValues d = Compute(MakeTsa(damaged), {34}, h.residual_variance);
  EXPECT_NEAR(h[CI::kFm4], 3.0, 0.6);
  EXPECT_GT(d[CI::kFm4], 10.0);
  EXPECT_GT(d[CI::kM6a], 10.0 * h[CI::kM6a]);
  EXPECT_GT(d[CI::kM8a], 10.0 * h[CI::kM8a]);
  EXPECT_GT(d[CI::kNa4], 5.0 * h[CI::kNa4]);
  // The pulse's mean square (1.5 sqrt(pi) / 1024 = 0.0026) about doubles the residual's (0.0025).
  EXPECT_GT(d[CI::kResidualRms], 1.3 * h[CI::kResidualRms]);
  EXPECT_GT(d[CI::kEnergyRatio], 1.3 * h[CI::kEnergyRatio]);
  EXPECT_GT(d[CI::kCrestFactor], h[CI::kCrestFactor]);
}

TEST(GearConditionIndicators, ShaftRateAmOfOneMeshGivesTheAnalyticalSlfAndOnlyItsSidebands) {
  // Meshes at orders 34 (amplitude A) and 40 (B) on one shaft; mesh 34 amplitude-modulated at
  // the shaft rate with depth m: A (1 + m cos t) cos 34 t = A cos 34 t + (A m / 2)(cos 33 t +
  // cos 35 t). SLF = (A m/2 + A m/2) / RMS, RMS^2 = A^2/2 + 2 (A m/2)^2/2 + B^2/2.
  const double a = 1.0;
  const double b = 0.6;
  const double m = 0.4;
  std::vector<double> healthy = Lines(1024, {{34, a}, {40, b}});
  std::vector<double> modulated(1024);
  for (std::size_t i = 0; i < 1024; ++i) {
    const double t = kTwoPi * static_cast<double>(i) / 1024.0;
    modulated[i] = a * (1.0 + m * std::cos(t)) * std::cos(34 * t) + b * std::cos(40 * t);
  }
  const Tsa am = MakeTsa(modulated);
  EXPECT_NEAR(std::abs(am.orders[33]), a * m / 2, 1e-12);
  EXPECT_NEAR(std::abs(am.orders[35]), a * m / 2, 1e-12);
  const ConditionIndicatorValues v = Compute(am, {34, 40});
  const double rms = std::sqrt(a * a / 2 + a * a * m * m / 4 + b * b / 2);
  EXPECT_NEAR(v[CI::kSidebandLevel], a * m / rms, 1e-12);
  ASSERT_EQ(v.mesh_count, 2u);
  EXPECT_NEAR(v.sideband_energy[0], a * a * m * m / 4, 1e-12);
  EXPECT_NEAR(v.sideband_ratio[0], m * m / 2, 1e-12);
  EXPECT_LT(v.sideband_energy[1], 1e-24);

  // The same with noise, against the same noise without the modulation.
  AddNoise(healthy, 0.02, 5);
  for (std::size_t i = 0; i < 1024; ++i) {
    const double t = kTwoPi * static_cast<double>(i) / 1024.0;
    modulated[i] = healthy[i] + a * m * std::cos(t) * std::cos(34 * t);
  }
  const ConditionIndicatorValues h = Compute(MakeTsa(healthy), {34, 40});
  const ConditionIndicatorValues n = Compute(MakeTsa(modulated), {34, 40});
  EXPECT_GT(n.sideband_energy[0], 10.0 * h.sideband_energy[0]);
  EXPECT_NEAR(n.sideband_energy[1], h.sideband_energy[1], 1e-15);  // mesh 40 sees nothing
  EXPECT_GT(n[CI::kSidebandLevel], 5.0 * h[CI::kSidebandLevel]);
  // First-order sidebands are residual but not difference: ER and FM4 barely move.
  EXPECT_GT(n[CI::kResidualRms], 3.0 * h[CI::kResidualRms]);
  EXPECT_NEAR(n[CI::kEnergyRatio], h[CI::kEnergyRatio], 0.05 * h[CI::kEnergyRatio]);
}

TEST(GearConditionIndicators, SlfUsesTheLargestMeshOfTheShaft) {
  // Sidebands around 34 only; when mesh 40 is the larger one, SLF looks at 39 and 41.
  const Tsa t = MakeTsa(Lines(1024, {{34, 0.5}, {33, 0.1}, {35, 0.1}, {40, 1.0}}));
  EXPECT_LT(Compute(t, {34, 40})[CI::kSidebandLevel], 1e-12);
  const Tsa u = MakeTsa(Lines(1024, {{34, 1.0}, {33, 0.1}, {35, 0.1}, {40, 0.5}}));
  EXPECT_GT(Compute(u, {34, 40})[CI::kSidebandLevel], 0.1);
}

TEST(GearConditionIndicators, WideSmoothDipRaisesLowOrdersMoreThanHighAndASharpPulseTheReverse) {
  // A Hann-shaped dip over 2.5 tooth periods of a 34-tooth gear (75 of 1024 points): its
  // spectrum lies below ~27 orders. A pulse of 1.5 points spreads up to order ~100.
  const std::size_t m = 1024;
  std::vector<double> healthy = Lines(m, {{34, 1.0}, {68, 0.3}});
  AddNoise(healthy, 0.01, 9);
  std::vector<double> dip = healthy;
  const double width = 2.5 * static_cast<double>(m) / 34.0;
  for (std::size_t i = 0; i < m; ++i) {
    const double u = (static_cast<double>(i) - 300.0) / width;
    if (u >= 0.0 && u <= 1.0) dip[i] -= 0.3 * 0.5 * (1.0 - std::cos(kTwoPi * u));
  }
  std::vector<double> pulse = healthy;
  AddPulse(pulse, 300.0, 0.3, 1.5);
  const ConditionIndicatorValues h = Compute(MakeTsa(healthy), {34});
  const ConditionIndicatorValues d = Compute(MakeTsa(dip), {34});
  const ConditionIndicatorValues p = Compute(MakeTsa(pulse), {34});
  const double dip_low = d[CI::kResidualLowOrders] - h[CI::kResidualLowOrders];
  const double dip_high = d[CI::kResidualHighOrders] - h[CI::kResidualHighOrders];
  const double pulse_low = p[CI::kResidualLowOrders] - h[CI::kResidualLowOrders];
  const double pulse_high = p[CI::kResidualHighOrders] - h[CI::kResidualHighOrders];
  EXPECT_GT(dip_low, 10.0 * std::abs(dip_high));
  EXPECT_GT(pulse_high, 3.0 * std::abs(pulse_low));
}

TEST(GearConditionIndicators, HarmonicAndSidebandCountsFollowTheOptions) {
  // Lines at 2 x 34 +/- 2: counted with H = 0 (all) or H >= 2 and K >= 2, not with H = 1 or K = 1.
  const Tsa t = MakeTsa(Lines(1024, {{34, 1.0}, {68, 1.0}, {66, 0.2}, {70, 0.2}}));
  EXPECT_NEAR(Compute(t, {34}).sideband_energy[0], 0.04, 1e-12);
  IndicatorOptions one_harmonic;
  one_harmonic.mesh_harmonics = 1;
  const ConditionIndicatorValues h1 = Compute(t, {34}, 0.0, one_harmonic);
  EXPECT_LT(h1.sideband_energy[0], 1e-24);
  EXPECT_NEAR(h1[CI::kMeshHarmonics], 1.0, 1e-12);  // order 68 is now residual
  IndicatorOptions one_sideband;
  one_sideband.sideband_orders = 1;
  EXPECT_LT(Compute(t, {34}, 0.0, one_sideband).sideband_energy[0], 1e-24);
}

TEST(GearConditionIndicators, WorksOnTheTsaOfASampledGearSignal) {
  // End to end with core/dsp: a 12.3 Hz shaft, 34-tooth mesh modulated at the shaft rate,
  // sampled at 10 kHz. Mesh at 418 Hz (0.04 fs): interpolation droop < 0.1 %.
  const double fs = 10000.0;
  const double f = 12.3;
  const std::size_t n = 16384;
  std::vector<double> x(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double t = kTwoPi * f * static_cast<double>(i) / fs;
    x[i] = (1.0 + 0.3 * std::cos(t)) * std::cos(34 * t);
  }
  auto tsa = SynchronousAverage::Create(n, fs, 2048).value();
  SynchronousAverageRecord record = tsa.MakeRecord();
  ASSERT_TRUE(tsa.Process(x, f, record).ok());
  auto indicators = GearConditionIndicators::Create(2048).value();
  ConditionIndicatorValues v;
  ASSERT_TRUE(indicators.Compute(record.tsa(), record.orders(), std::vector<int>{34}, 0.0, v).ok());
  const double rms = std::sqrt(0.5 + 0.09 / 4);
  EXPECT_NEAR(v[CI::kSidebandLevel], 0.3 / rms, 0.01 * 0.3 / rms);
  EXPECT_NEAR(v.sideband_ratio[0], 0.09 / 2, 0.001);
}

TEST(GearConditionIndicators, CreateRejectsBadOptionsNamingTheField) {
  auto bad_points = GearConditionIndicators::Create(1000);
  ASSERT_FALSE(bad_points.ok());
  EXPECT_NE(bad_points.error().find("max points per revolution"), std::string::npos);
  IndicatorOptions o;
  o.mesh_harmonics = -1;
  auto h = GearConditionIndicators::Create(1024, o);
  ASSERT_FALSE(h.ok());
  EXPECT_NE(h.error().find("mesh_harmonics"), std::string::npos);
  o = {};
  o.low_shaft_orders = -2;
  auto l = GearConditionIndicators::Create(1024, o);
  ASSERT_FALSE(l.ok());
  EXPECT_NE(l.error().find("low_shaft_orders"), std::string::npos);
  o = {};
  o.sideband_orders = 0;
  auto k = GearConditionIndicators::Create(1024, o);
  ASSERT_FALSE(k.ok());
  EXPECT_NE(k.error().find("sideband_orders"), std::string::npos);
}

TEST(GearConditionIndicators, ComputeRejectsBadInputNamingTheArgument) {
  auto stage = GearConditionIndicators::Create(1024).value();
  const Tsa t = MakeTsa(Lines(1024, {{34, 1.0}}));
  ConditionIndicatorValues out;
  out.mesh_count = 99;  // a marker: rejected calls leave `out` untouched
  const auto expect_rejected = [&](std::span<const double> x,
                                   std::span<const std::complex<double>> orders,
                                   std::vector<int> meshes, double reference, const char* word) {
    const Status s = stage.Compute(x, orders, meshes, reference, out);
    ASSERT_FALSE(s.ok()) << word;
    EXPECT_NE(s.error().find(word), std::string::npos) << s.error();
    EXPECT_EQ(out.mesh_count, 99u);
  };
  expect_rejected(t.x, t.orders, {}, 0.0, "mesh_orders");
  expect_rejected(t.x, t.orders, {10, 20, 30, 40, 50}, 0.0, "mesh_orders");
  expect_rejected(t.x, t.orders, {1}, 0.0, "mesh_orders[0]");
  expect_rejected(t.x, t.orders, {34, 512}, 0.0, "mesh_orders[1]");
  expect_rejected(std::span<const double>(t.x).first(1000), t.orders, {34}, 0.0, "tsa");
  const Tsa big = MakeTsa(Lines(2048, {{34, 1.0}}));
  expect_rejected(big.x, big.orders, {34}, 0.0, "tsa");  // above the configured cap
  expect_rejected(t.x, std::span<const std::complex<double>>(t.orders).first(500), {34}, 0.0,
                  "orders");
  std::vector<double> nan_x = t.x;
  nan_x[5] = std::numeric_limits<double>::quiet_NaN();
  expect_rejected(nan_x, t.orders, {34}, 0.0, "tsa has a non-finite value at index 5");
  std::vector<std::complex<double>> inf_orders = t.orders;
  inf_orders[7] = std::numeric_limits<double>::infinity();
  expect_rejected(t.x, inf_orders, {34}, 0.0, "orders has a non-finite value at order 7");
  expect_rejected(t.x, t.orders, {34}, std::numeric_limits<double>::quiet_NaN(),
                  "na4_reference_variance");
}

TEST(GearConditionIndicators, CountingAllocatorIsTheOneInUse) {
  CountAllocations counter;
  int* volatile p = new int(3);  // volatile: the new/delete pair may not be elided
  delete p;
  EXPECT_EQ(counter.count(), 1) << "the counting operator new is not the one in use";
}

TEST(GearConditionIndicators, SynchronousAverageAndIndicatorsAllocateNothingPerBlock) {
  const double fs = 10000.0;
  const std::size_t n = 16384;
  std::vector<double> x(n);
  std::mt19937_64 rng(1);
  std::normal_distribution<double> normal(0.0, 0.1);
  for (std::size_t i = 0; i < n; ++i) {
    x[i] = std::cos(kTwoPi * 34 * 12.3 * static_cast<double>(i) / fs) + normal(rng);
  }
  auto tsa = SynchronousAverage::Create(n, fs, 2048).value();
  auto indicators = GearConditionIndicators::Create(2048).value();
  SynchronousAverageRecord record = tsa.MakeRecord();
  ConditionIndicatorValues v;
  const std::vector<int> meshes = {34, 40};
  // Several shaft rates, so several M (512 .. 2048) and plan sizes are exercised.
  for (const double f : {12.3, 25.0, 6.1}) {
    bool ok = false;
    long count = 0;
    {
      CountAllocations counter;
      ok = tsa.Process(x, f, record).ok() &&
           indicators.Compute(record.tsa(), record.orders(), meshes, 0.0, v).ok();
      count = counter.count();
    }
    EXPECT_TRUE(ok) << f;
    EXPECT_EQ(count, 0) << "shaft at " << f << " Hz, M = " << record.points_per_revolution;
  }
}

// The synchronous low-order ratio from hand-made spreads. M = 64, mesh order 20: the low band
// is orders 3..9 (above the shaft orders 1..2, 2 k < 20). With locked = 1 and spread = 2 per
// order over R = 3 revolutions, F = 7 / (14 / 2) = 1; raising one order's locked power to 8
// gives (6 + 8) / 7 = 2. Orders outside the band change nothing.
TEST(GearConditionIndicators, SynchronousLowOrdersIsLockedPowerOverWhatTheSpreadLeavesInAMean) {
  const Tsa t = MakeTsa(Lines(64, {{20, 1.0}}));
  auto stage = GearConditionIndicators::Create(4096).value();
  std::vector<double> locked(33, 1.0), spread(33, 2.0);
  const std::vector<int> meshes = {20};
  ConditionIndicatorValues v;
  const auto ratio = [&](std::size_t revolutions) {
    const RevolutionSpreadView view{locked, spread, revolutions, 32.0};
    const Status s = stage.Compute(t.x, t.orders, meshes, 0.0, v, view);
    EXPECT_TRUE(s.ok()) << s.error();
    return v[CI::kSynchronousLowOrders];
  };
  EXPECT_NEAR(ratio(3), 1.0, 1e-12);
  locked[5] = 8.0;
  EXPECT_NEAR(ratio(3), 2.0, 1e-12);
  locked[1] = locked[12] = 1e6;  // a shaft order and an order above the band
  spread[2] = 1e6;
  EXPECT_NEAR(ratio(3), 2.0, 1e-12);
  EXPECT_EQ(ratio(1), 0.0);  // one revolution: no spread to judge by
  EXPECT_EQ(ratio(0), 0.0);
  // Without a spread at all it is 0 and the other indicators are as before.
  ASSERT_TRUE(stage.Compute(t.x, t.orders, meshes, 0.0, v).ok());
  EXPECT_EQ(v[CI::kSynchronousLowOrders], 0.0);
}

TEST(GearConditionIndicators, SynchronousLowOrdersRejectsABadSpreadNamingIt) {
  const Tsa t = MakeTsa(Lines(64, {{20, 1.0}}));
  auto stage = GearConditionIndicators::Create(4096).value();
  std::vector<double> locked(33, 1.0), spread(33, 2.0), short_spread(20, 2.0);
  ConditionIndicatorValues v;
  const std::vector<int> meshes = {20};
  Status s = stage.Compute(t.x, t.orders, meshes, 0.0, v, {locked, short_spread, 3, 32.0});
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.error().find("revolution spread"), std::string::npos) << s.error();
  spread[4] = std::numeric_limits<double>::infinity();
  s = stage.Compute(t.x, t.orders, meshes, 0.0, v, {locked, spread, 3, 32.0});
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.error().find("order 4"), std::string::npos) << s.error();
  spread[4] = -1.0;
  EXPECT_FALSE(stage.Compute(t.x, t.orders, meshes, 0.0, v, {locked, spread, 3, 32.0}).ok());
}

}  // namespace
}  // namespace gearpath
