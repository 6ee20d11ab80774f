#include "core/simulation/fault_excitation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <numbers>
#include <vector>

namespace gearpath {
namespace {

constexpr double kFs = 8000.0;

FaultExcitation Make(FaultType type, const std::string& gear, double severity = 1.0,
                     double input_hz = 10.0, std::uint64_t seed = 7) {
  ExcitationParameters p;
  p.seed = seed;
  Result<FaultExcitation> e =
      FaultExcitation::Create(GearTrain::Table1(), input_hz, {type, gear, severity}, p);
  EXPECT_TRUE(e.ok()) << e.error();
  return std::move(e).value();
}

// One-sided amplitude of the line at `hz` in x sampled at kFs over a whole number of its
// periods, by a direct DFT sum (independent of any FFT code).
double LineAmplitude(const std::vector<double>& x, double hz) {
  std::complex<double> acc = 0.0;
  for (std::size_t n = 0; n < x.size(); ++n) {
    const double phase = -2.0 * std::numbers::pi * hz * static_cast<double>(n) / kFs;
    acc += x[n] * std::complex<double>(std::cos(phase), std::sin(phase));
  }
  return 2.0 * std::abs(acc) / static_cast<double>(x.size());
}

std::vector<double> SampleOnePeriod(const FaultExcitation& e, int stage, bool fault_only) {
  const auto n = static_cast<std::size_t>(std::lround(e.common_period_s() * kFs));
  std::vector<double> x(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double t = static_cast<double>(i) / kFs;
    x[i] = fault_only ? e.Fault(stage, t) : e.Total(stage, t);
  }
  return x;
}

TEST(FaultExcitationTest, HealthyGearboxHasNoFaultPart) {
  const FaultExcitation e = Make(FaultType::kNone, "");
  EXPECT_EQ(e.fault_stage(), -1);
  EXPECT_EQ(e.fault_depth_m(), 0.0);
  for (int s = 0; s < 2; ++s) {
    for (const double v : SampleOnePeriod(e, s, /*fault_only=*/true)) ASSERT_EQ(v, 0.0);
  }
}

TEST(FaultExcitationTest, HealthySpectrumHasTheMeshHarmonicsAndShaftSidebands) {
  // e_h = (1 + mu cos(w_dr t) + mu cos(w_dn t)) sum A_h cos(h w_m t): carrier A_h at h f_m,
  // sidebands mu A_h / 2 at h f_m +- f_dr and h f_m +- f_dn, nothing else.
  const FaultExcitation e = Make(FaultType::kNone, "");
  const ExcitationParameters p;
  const std::vector<double> te0 = SampleOnePeriod(e, 0, false);
  const std::vector<double> te1 = SampleOnePeriod(e, 1, false);
  EXPECT_EQ(te0.size(), 8000u);  // common period 1 s at 600 r/min
  for (int h = 1; h <= 3; ++h) {
    const double a = p.mesh_harmonic_amplitude_m[static_cast<std::size_t>(h - 1)];
    EXPECT_NEAR(LineAmplitude(te0, 280.0 * h), a, 1e-12) << h;
    EXPECT_NEAR(LineAmplitude(te1, 238.0 * h), a, 1e-12) << h;
    EXPECT_NEAR(LineAmplitude(te0, 280.0 * h + 10.0), 0.5 * p.shaft_modulation_depth * a, 1e-12);
    EXPECT_NEAR(LineAmplitude(te0, 280.0 * h - 7.0), 0.5 * p.shaft_modulation_depth * a, 1e-12);
    // Stage 2: driver and driven shafts both turn at 7 Hz, their sidebands add as phasors.
    EXPECT_LE(LineAmplitude(te1, 238.0 * h + 7.0), p.shaft_modulation_depth * a + 1e-12);
  }
  EXPECT_NEAR(LineAmplitude(te0, 150.0), 0.0, 1e-12);
  EXPECT_NEAR(LineAmplitude(te1, 280.0), 0.0, 1e-12);
}

TEST(FaultExcitationTest, FaultPulseRepeatsExactlyAtTheFaultyGearsShaftPeriod) {
  for (const char* gear : {"G1", "G2", "G3", "G4"}) {
    const FaultExcitation e = Make(FaultType::kToothFracture, gear);
    const double shaft_hz = std::string(gear) == "G1" ? 10.0 : 7.0;
    EXPECT_DOUBLE_EQ(e.fault_period_s(), 1.0 / shaft_hz) << gear;
    // Same value one period later, anywhere.
    for (int i = 0; i < 2000; ++i) {
      const double t = 0.37e-3 * i;
      ASSERT_NEAR(e.Fault(e.fault_stage(), t + e.fault_period_s()), e.Fault(e.fault_stage(), t),
                  1e-12 * e.fault_depth_m())
          << gear << " t=" << t;
    }
    // Event times: the pulse starts (rises from 0) exactly shaft_hz times per second, at
    // onset + n * period.
    const std::vector<double> x = SampleOnePeriod(e, e.fault_stage(), true);
    std::vector<double> onsets;
    for (std::size_t n = 1; n < x.size(); ++n) {
      if (x[n - 1] == 0.0 && x[n] != 0.0) onsets.push_back(static_cast<double>(n) / kFs);
    }
    ASSERT_EQ(onsets.size(), static_cast<std::size_t>(shaft_hz)) << gear;
    for (std::size_t k = 0; k < onsets.size(); ++k) {
      const double expected = e.fault_onset_s() + static_cast<double>(k) * e.fault_period_s();
      EXPECT_NEAR(onsets[k], expected, 1.0 / kFs + 1e-12) << gear << " event " << k;
    }
  }
}

TEST(FaultExcitationTest, FaultLivesOnTheMeshOfTheFaultyGearOnly) {
  const int want_stage[] = {0, 0, 1, 1};
  for (int g = 0; g < 4; ++g) {
    const std::string gear = "G" + std::to_string(g + 1);
    const FaultExcitation faulty = Make(FaultType::kChippedTooth, gear);
    const FaultExcitation healthy = Make(FaultType::kNone, "");
    ASSERT_EQ(faulty.fault_stage(), want_stage[g]) << gear;
    const int other = 1 - want_stage[g];
    double fault_energy = 0.0;
    for (int i = 0; i < 8000; ++i) {
      const double t = i / kFs;
      ASSERT_EQ(faulty.Fault(other, t), 0.0);
      // Same seed: the healthy part is the same with or without the fault.
      ASSERT_EQ(faulty.Total(other, t), healthy.Total(other, t));
      ASSERT_EQ(faulty.Healthy(want_stage[g], t), healthy.Healthy(want_stage[g], t));
      fault_energy += std::pow(faulty.Fault(want_stage[g], t), 2);
    }
    EXPECT_GT(fault_energy, 0.0) << gear;
  }
}

TEST(FaultExcitationTest, PulseEnergyMatchesTheTaperedBoxIntegralAndIsOrderedByFaultType) {
  // Integral of a tapered box squared: depth^2 * length * (1 - 5/4 taper) (each cosine ramp of
  // length r L contributes 3/8 r L instead of r L).
  double energy[4] = {};
  for (FaultType type :
       {FaultType::kChippedTooth, FaultType::kLocalizedWear, FaultType::kToothFracture}) {
    const FaultExcitation e = Make(type, "G2");
    const double fine_fs = 4.0e6;  // fine grid for the numerical integral of one pulse
    double sum = 0.0;
    const double t0 = e.fault_onset_s();
    for (double t = t0; t < t0 + e.fault_length_s() + 1e-4; t += 1.0 / fine_fs) {
      sum += std::pow(e.Fault(0, t), 2) / fine_fs;
    }
    const FaultShape shape = FaultShapeOf(type);
    const double analytic =
        e.fault_depth_m() * e.fault_depth_m() * e.fault_length_s() * (1.0 - 1.25 * shape.taper);
    EXPECT_NEAR(sum, analytic, 1e-3 * analytic) << FaultTypeName(type);
    energy[static_cast<int>(type)] = sum;
  }
  EXPECT_GT(energy[static_cast<int>(FaultType::kToothFracture)],
            energy[static_cast<int>(FaultType::kChippedTooth)]);
  EXPECT_GT(energy[static_cast<int>(FaultType::kChippedTooth)],
            energy[static_cast<int>(FaultType::kLocalizedWear)]);
}

TEST(FaultExcitationTest, FaultPulseLastsTheEngagementOfOneTooth) {
  // Fracture: the whole engagement, contact ratio x mesh period (1.676 / 280 Hz for G1-G2).
  const FaultExcitation e = Make(FaultType::kToothFracture, "G1");
  EXPECT_NEAR(e.fault_length_s(), 1.676 / 280.0, 2e-3 / 280.0);
  EXPECT_NEAR(e.fault_depth_m(), 5e-6, 1e-18);
  // The damaged tooth engages at a whole number of mesh periods.
  const double teeth_in = e.fault_onset_s() * 280.0;
  EXPECT_NEAR(teeth_in, std::round(teeth_in), 1e-9);
}

TEST(FaultExcitationTest, SeverityScalesTheFaultLinearlyAndZeroMeansHealthy) {
  const FaultExcitation one = Make(FaultType::kLocalizedWear, "G4", 1.0);
  const FaultExcitation two = Make(FaultType::kLocalizedWear, "G4", 2.0);
  const FaultExcitation zero = Make(FaultType::kLocalizedWear, "G4", 0.0);
  EXPECT_EQ(zero.fault_stage(), -1);
  for (int i = 0; i < 8000; ++i) {
    const double t = i / kFs;
    ASSERT_NEAR(two.Fault(1, t), 2.0 * one.Fault(1, t), 1e-20);
    ASSERT_EQ(zero.Fault(1, t), 0.0);
  }
}

TEST(FaultExcitationTest, WholeExcitationIsPeriodicOverTheCommonPeriodAtEverySpeed) {
  for (double rpm : {600.0, 500.0, 400.0, 300.0}) {
    const FaultExcitation e = Make(FaultType::kToothFracture, "G3", 1.0, RpmToHz(rpm));
    EXPECT_NEAR(e.common_period_s(), 10.0 / RpmToHz(rpm), 1e-12);
    for (int s = 0; s < 2; ++s) {
      for (int i = 0; i < 500; ++i) {
        const double t = 1.3e-3 * i;
        ASSERT_NEAR(e.Total(s, t + e.common_period_s()), e.Total(s, t), 1e-17) << rpm;
      }
    }
  }
}

TEST(FaultExcitationTest, MeshHarmonicsStayTheLargestLinesOfTheFaultyTransmissionError) {
  // The fault must not dominate the raw spectrum: its lines (at multiples of the shaft rate)
  // stay below the mesh fundamental for every type at the seed's severity.
  for (FaultType type :
       {FaultType::kChippedTooth, FaultType::kLocalizedWear, FaultType::kToothFracture}) {
    for (const char* gear : {"G1", "G2"}) {
      const FaultExcitation e = Make(type, gear);
      const std::vector<double> x = SampleOnePeriod(e, 0, false);
      const double mesh = LineAmplitude(x, 280.0);
      for (double f = 1.0; f < 1000.0; f += 1.0) {
        if (std::abs(f - 280.0) < 0.5) continue;
        ASSERT_LT(LineAmplitude(x, f), mesh) << FaultTypeName(type) << " " << gear << " " << f;
      }
    }
  }
}

TEST(FaultExcitationTest, SameSeedGivesTheSameSignalAndAnotherSeedAnother) {
  const FaultExcitation a = Make(FaultType::kToothFracture, "G2", 1.0, 10.0, 11);
  const FaultExcitation b = Make(FaultType::kToothFracture, "G2", 1.0, 10.0, 11);
  const FaultExcitation c = Make(FaultType::kToothFracture, "G2", 1.0, 10.0, 12);
  std::vector<double> xa(4000), xb(4000), xc(4000);
  a.Sample(0, 0.0, kFs, xa);
  b.Sample(0, 0.0, kFs, xb);
  c.Sample(0, 0.0, kFs, xc);
  EXPECT_EQ(xa, xb);
  EXPECT_NE(xa, xc);
}

TEST(FaultExcitationTest, ShapeOverrideReplacesTheTableAndIsValidated) {
  ExcitationParameters p;
  p.shape = FaultShape{2.0, 0.5, 0.5};
  Result<FaultExcitation> e =
      FaultExcitation::Create(GearTrain::Table1(), 10.0, {FaultType::kLocalizedWear, "G1"}, p);
  ASSERT_TRUE(e.ok()) << e.error();
  EXPECT_DOUBLE_EQ(e->fault_depth_m(), 2.0 * p.deflection_scale_m);
  EXPECT_NEAR(e->fault_length_s(), 0.5 * 1.676 / 280.0, 1e-3 / 280.0);
  p.shape = FaultShape{1.0, 1.0, 0.0};
  e = FaultExcitation::Create(GearTrain::Table1(), 10.0, {FaultType::kLocalizedWear, "G1"}, p);
  ASSERT_FALSE(e.ok());
  EXPECT_EQ(e.error(),
            "fault excitation: shape must have depth_factor >= 0, length_factor in (0, 2] and "
            "taper in (0, 0.5]");
}

TEST(FaultExcitationTest, FaultTypeNamesRoundTrip) {
  for (FaultType t : {FaultType::kNone, FaultType::kChippedTooth, FaultType::kLocalizedWear,
                      FaultType::kToothFracture}) {
    EXPECT_EQ(ParseFaultType(FaultTypeName(t)), t);
  }
  EXPECT_FALSE(ParseFaultType("crack").has_value());
}

TEST(FaultExcitationValidationTest, RejectsUnknownGearNegativeSeverityAndBadParameters) {
  const GearTrain train = GearTrain::Table1();
  Result<FaultExcitation> r =
      FaultExcitation::Create(train, 10.0, {FaultType::kChippedTooth, "G9", 1.0});
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error(), "fault excitation: fault gear 'G9' is not a gear of the train");
  r = FaultExcitation::Create(train, 10.0, {FaultType::kChippedTooth, "G1", -1.0});
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().find("fault severity must be finite and >= 0"), std::string::npos);
  r = FaultExcitation::Create(train, -10.0, {});
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().find("input speed"), std::string::npos) << r.error();
  ExcitationParameters p;
  p.mesh_harmonic_amplitude_m = {1e-6, -1e-6};
  r = FaultExcitation::Create(train, 10.0, {}, p);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().find("mesh_harmonic_amplitude_m[1]"), std::string::npos) << r.error();
  p = {};
  p.deflection_scale_m = 0.0;
  r = FaultExcitation::Create(train, 10.0, {}, p);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().find("deflection_scale_m"), std::string::npos) << r.error();
  GearTrain broken = train;
  broken.gears[1].teeth = 0;
  r = FaultExcitation::Create(broken, 10.0, {});
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().find("gears[1] (G2): teeth must be >= 1"), std::string::npos);
}

}  // namespace
}  // namespace gearpath
