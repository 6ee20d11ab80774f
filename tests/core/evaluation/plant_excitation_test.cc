// PlantExcitation: fault models of different physics, checked against their definitions
// (additive vs multiplicative, which stage, when) rather than against the code's own output.
#include "core/evaluation/plant_excitation.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/evaluation/plant_family.h"

namespace gearpath {
namespace {

PlantExcitation Make(PlantFaultKind kind, const std::string& gear, std::uint64_t seed = 11,
                     TrainVariant variant = TrainVariant::kTable1) {
  PlantExcitationConfig c;
  c.fault = kind;
  c.faulty_gear = gear;
  c.seed = seed;
  Result<PlantExcitation> e = PlantExcitation::Create(MakeTrain(variant), c);
  EXPECT_TRUE(e.ok()) << e.error();
  return std::move(e).value();
}

TEST(PlantExcitation, NamesRoundTrip) {
  for (PlantFaultKind k : kAllPlantFaultKinds) {
    EXPECT_EQ(ParsePlantFaultKind(PlantFaultKindName(k)), k);
  }
  EXPECT_FALSE(ParsePlantFaultKind("fracture").has_value());
}

TEST(PlantExcitation, KinematicsFollowTheToothCounts) {
  const PlantExcitation e = Make(PlantFaultKind::kNone, "");
  ASSERT_EQ(e.stage_count(), 2);
  EXPECT_DOUBLE_EQ(e.mesh_order(0), 28.0);                  // G1 on the input shaft
  EXPECT_NEAR(e.mesh_order(1), 34.0 * 28.0 / 40.0, 1e-12);  // G3 at 0.7 x input
  EXPECT_NEAR(e.shaft_orders()[2], 0.7, 1e-12);
  const PlantExcitation d = Make(PlantFaultKind::kNone, "", 11, TrainVariant::kDistinct);
  EXPECT_NEAR(d.shaft_orders()[2], 0.7 * 34.0 / 29.0, 1e-12);
}

TEST(PlantExcitation, FaultTouchesOnlyItsStageAndOnlyInsideItsWindow) {
  for (PlantFaultKind kind : {PlantFaultKind::kTePulse, PlantFaultKind::kMeshAm,
                              PlantFaultKind::kWearDip, PlantFaultKind::kCombined}) {
    const PlantExcitation e = Make(kind, "G2");  // stage 0, intermediate shaft (0.7 x input)
    ASSERT_EQ(e.fault_stage(), 0);
    EXPECT_EQ(e.fault_teeth(), 40);
    int changed = 0;
    const int n = 20000;
    for (int i = 0; i < n; ++i) {
      const double revs = 3.0 * i / n;  // 3 input revolutions = 2.1 revolutions of G2
      EXPECT_EQ(e.Te(1, revs, true), e.Te(1, revs, false)) << PlantFaultKindName(kind);
      if (e.Te(0, revs, true) != e.Te(0, revs, false)) {
        ++changed;
        double u = e.fault_shaft_order() * revs - e.fault_onset_revs();
        u -= std::floor(u);
        const double window = kind == PlantFaultKind::kWearDip ? e.dip_length_periods() : 1.0;
        EXPECT_LT(u * 40.0, window + 1e-9) << PlantFaultKindName(kind) << " at " << revs;
      }
    }
    // 2.1 revolutions, window 1..3 of 40 mesh periods: a few percent of the samples.
    EXPECT_GT(changed, n / 200) << PlantFaultKindName(kind);
    EXPECT_LT(changed, n / 4) << PlantFaultKindName(kind);
  }
}

TEST(PlantExcitation, MeshAmIsMultiplicativeAndPulseIsAdditive) {
  const PlantExcitation am = Make(PlantFaultKind::kMeshAm, "G1");
  const PlantExcitation pulse = Make(PlantFaultKind::kTePulse, "G1");
  const PlantFaultSeverity& sv = am.severity();
  for (int i = 0; i < 5000; ++i) {
    const double revs = i / 5000.0;
    double u = revs - am.fault_onset_revs();
    u -= std::floor(u);
    const double w = TaperedWindow(u * 28.0, sv.am_length_periods, sv.am_taper);
    const double healthy = am.Te(0, revs, false);
    EXPECT_NEAR(am.Te(0, revs, true), (1.0 - sv.am_depth * w) * healthy, 1e-18);
    const double wp = TaperedWindow(u * 28.0, sv.pulse_length_periods, sv.pulse_taper);
    // Same seed: same phases and the same damaged tooth for both kinds.
    EXPECT_NEAR(pulse.Te(0, revs, true), healthy + sv.pulse_depth_m * wp, 1e-18);
  }
}

TEST(PlantExcitation, FaultDeviationIsFaultyMinusHealthy) {
  for (PlantFaultKind kind : kAllPlantFaultKinds) {
    const PlantExcitation e = Make(kind, kind == PlantFaultKind::kNone ? "" : "G3");
    for (int i = 0; i < 20000; ++i) {
      const double revs = 2.0 * i / 20000.0;
      for (int s = 0; s < 2; ++s) {
        EXPECT_NEAR(e.FaultDeviation(s, revs) + e.Te(s, revs, false), e.Te(s, revs, true), 1e-20)
            << PlantFaultKindName(kind) << " stage " << s << " at " << revs;
      }
    }
  }
  // Healthy TE band: 4 harmonics of the 28-tooth mesh plus the input shaft's sideband.
  EXPECT_DOUBLE_EQ(Make(PlantFaultKind::kNone, "").HealthyBandwidthOrder(), 4 * 28.0 + 1.0);
}

TEST(PlantExcitation, DeterministicPerSeedAndDifferentAcrossSeeds) {
  const PlantExcitation a = Make(PlantFaultKind::kCombined, "G3", 5);
  const PlantExcitation b = Make(PlantFaultKind::kCombined, "G3", 5);
  const PlantExcitation c = Make(PlantFaultKind::kCombined, "G3", 6);
  bool differs = false;
  for (int i = 0; i < 100; ++i) {
    const double revs = 0.0137 * i;
    EXPECT_EQ(a.Te(1, revs, true), b.Te(1, revs, true));
    differs |= a.Te(1, revs, false) != c.Te(1, revs, false);
  }
  EXPECT_TRUE(differs);
}

TEST(PlantExcitation, ScaleSeverityRespectsTheCaps) {
  PlantExcitation e = Make(PlantFaultKind::kCombined, "G1");
  const double pulse = e.severity().pulse_depth_m;
  e.ScaleSeverity(2.0);
  EXPECT_DOUBLE_EQ(e.severity().pulse_depth_m, 2.0 * pulse);
  e.ScaleSeverity(1e6);
  EXPECT_DOUBLE_EQ(e.severity().pulse_depth_m, e.severity().max_pulse_depth_m);
  EXPECT_DOUBLE_EQ(e.severity().am_depth, e.severity().max_am_depth);
  EXPECT_DOUBLE_EQ(e.severity().dip_depth_m, e.severity().max_dip_depth_m);
}

TEST(PlantExcitation, RejectsBadArgumentsByName) {
  PlantExcitationConfig c;
  c.fault = PlantFaultKind::kTePulse;
  c.faulty_gear = "G9";
  Result<PlantExcitation> e = PlantExcitation::Create(GearTrain::Table1(), c);
  ASSERT_FALSE(e.ok());
  EXPECT_NE(e.error().find("faulty_gear 'G9'"), std::string::npos) << e.error();
  c.faulty_gear = "G1";
  c.severity.am_depth = 1.5;
  e = PlantExcitation::Create(GearTrain::Table1(), c);
  ASSERT_FALSE(e.ok());
  EXPECT_NE(e.error().find("am_depth"), std::string::npos) << e.error();
  c = PlantExcitationConfig{};
  c.mesh_harmonics = 0;
  e = PlantExcitation::Create(GearTrain::Table1(), c);
  ASSERT_FALSE(e.ok());
  EXPECT_NE(e.error().find("mesh_harmonics"), std::string::npos) << e.error();
}

}  // namespace
}  // namespace gearpath
