#include "core/diagnosis/gear_verdict.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace gearpath {
namespace {

// Seed Table 1: G1 (28, input) - G2 (40, intermediate) mesh 0; G3 (34, intermediate) - G4 (34,
// output) mesh 1. Paths: one per shaft bearing (B1 input, B2 intermediate, B3 output); a
// bearing sees the meshes of the gears on its shaft.
VerdictTopology Table1() {
  VerdictTopology t;
  t.gear_names = {"G1", "G2", "G3", "G4"};
  t.gear_shaft = {0, 1, 1, 2};
  t.gear_mesh = {0, 0, 1, 1};
  t.shaft_names = {"input", "intermediate", "output"};
  t.shaft_ratio = {1.0, 0.7, 0.7};
  t.mesh_names = {"G1-G2", "G3-G4"};
  t.path_meshes = {{0}, {0, 1}, {1}};
  return t;
}

// Distinct tooth counts: G3 has 30 teeth, so the output shaft turns at 0.7*30/34 of the input.
VerdictTopology Distinct() {
  VerdictTopology t = Table1();
  t.shaft_ratio = {1.0, 0.7, 0.7 * 30.0 / 34.0};
  return t;
}

struct Case {
  std::vector<double> raw = {1, 1, 1};
  std::vector<double> rec = {1, 1, 1};
  std::vector<double> thr = {2, 2, 2};
  std::vector<double> crit = {1, 1, 1};
  int dominant = 0;
  bool learning = false;
  std::vector<double> mesh_evidence;
};

GearVerdict Decide(const VerdictTopology& t, const Case& c) {
  GearVerdict v;
  t.Reserve(v);
  VerdictInputs in;
  in.input_speed_hz = 10.0;
  in.raw = c.raw;
  in.reconstructed = c.rec;
  in.raw_threshold = c.thr;
  in.reconstructed_threshold = c.thr;
  in.path_criterion = c.crit;
  in.dominant_path = c.dominant;
  in.alarm_factor = 2.0;
  in.learning = c.learning;
  in.mesh_evidence = c.mesh_evidence;
  DecideGearVerdict(t, in, v);
  return v;
}

TEST(GearVerdictTest, ReportsLearningWhileTheBaselineIsNotKnown) {
  Case c;
  c.learning = true;
  const GearVerdict v = Decide(Table1(), c);
  EXPECT_EQ(v.state, FaultState::kLearning);
  EXPECT_EQ(v.gear, -1);
}

TEST(GearVerdictTest, IndicatorsUnderThresholdGiveNoFault) {
  const GearVerdict v = Decide(Table1(), Case{});
  EXPECT_EQ(v.state, FaultState::kNoFault);
  EXPECT_EQ(v.gear, -1);
  EXPECT_TRUE(v.candidates.empty());
  EXPECT_DOUBLE_EQ(v.confidence, 0.5);  // 1 - highest exceedance (1/2)
  EXPECT_EQ(std::string(v.reason.view()),
            "every shaft indicator under its threshold (highest: shaft 'input' at 50 %)");
}

TEST(GearVerdictTest, InputShaftHarmonicsNameGear1WhateverThePath) {
  Case c;
  c.rec = {6, 1, 1};
  c.crit = {3, 2, 1};
  c.dominant = 0;
  const GearVerdict v = Decide(Table1(), c);
  EXPECT_EQ(v.state, FaultState::kAlarm);  // 3x threshold >= alarm factor 2
  EXPECT_EQ(v.gear_name, "G1");
  EXPECT_EQ(v.shaft_name, "input");
  EXPECT_DOUBLE_EQ(v.characteristic_hz, 10.0);
  ASSERT_EQ(v.candidates.size(), 1u);
  EXPECT_GT(v.confidence, 0.0);
  EXPECT_LE(v.confidence, 1.0);
}

TEST(GearVerdictTest, SevenHertzWithInputBearingDominantNamesGear2) {
  Case c;
  c.rec = {1, 3, 3};
  c.crit = {5, 3, 1};
  c.dominant = 0;  // B1 sees mesh G1-G2 only
  const GearVerdict v = Decide(Table1(), c);
  EXPECT_EQ(v.state, FaultState::kSuspected);
  EXPECT_EQ(v.gear_name, "G2");
  ASSERT_EQ(v.candidates.size(), 1u);
  EXPECT_EQ(v.mesh, 0);
  EXPECT_DOUBLE_EQ(v.characteristic_hz, 7.0);
}

TEST(GearVerdictTest, SevenHertzWithOutputBearingDominantNamesGears3And4AsCandidates) {
  Case c;
  c.rec = {1, 3, 3};
  c.crit = {1, 3, 5};
  c.dominant = 2;  // B3 sees mesh G3-G4 only
  const GearVerdict v = Decide(Table1(), c);
  EXPECT_EQ(v.state, FaultState::kSuspected);
  ASSERT_EQ(v.candidate_names.size(), 2u);
  EXPECT_EQ(v.candidate_names[0], "G3");
  EXPECT_EQ(v.candidate_names[1], "G4");
  EXPECT_EQ(v.mesh, 1);
  const std::string reason(v.reason.view());
  EXPECT_NE(reason.find("they share mesh G3-G4 and shaft rate 7 Hz"), std::string::npos) << reason;
}

TEST(GearVerdictTest, SharedBearingDominantUsesTheOtherPathsToPickTheMesh) {
  Case c;
  c.rec = {1, 3, 3};
  c.crit = {4, 6, 1};  // B2 dominant, but B1 (mesh 0 only) carries far more than B3
  c.dominant = 1;
  const GearVerdict v = Decide(Table1(), c);
  EXPECT_EQ(v.gear_name, "G2");
  ASSERT_EQ(v.candidates.size(), 1u);
}

TEST(GearVerdictTest, SharedBearingWithBalancedEndsKeepsBothMeshesAndSaysSo) {
  Case c;
  c.rec = {1, 3, 3};
  c.crit = {2, 6, 2};
  c.dominant = 1;
  const GearVerdict v = Decide(Table1(), c);
  ASSERT_EQ(v.candidates.size(), 3u);  // G2, G3, G4
  EXPECT_EQ(v.mesh, -1);
  EXPECT_DOUBLE_EQ(v.confidence, 0.0);  // mesh separation is zero
  EXPECT_NE(std::string(v.reason.view()).find("does not separate their meshes"), std::string::npos);
}

TEST(GearVerdictTest, MeshEvidenceOverridesBalancedPathWeightsOnASharedBearing) {
  Case c;
  c.rec = {1, 3, 3};
  c.crit = {1, 6, 5};            // path weights alone would lean to mesh G3-G4
  c.dominant = 1;                // B2 sees both meshes
  c.mesh_evidence = {9.0, 1.0};  // but the evidence points at mesh G1-G2
  const GearVerdict v = Decide(Table1(), c);
  EXPECT_EQ(v.gear_name, "G2") << v.reason.view();
  ASSERT_EQ(v.candidates.size(), 1u);
  EXPECT_EQ(v.mesh, 0);
}

TEST(GearVerdictTest, MeshEvidenceCannotOverrideADominantPathOfTheOtherEnd) {
  Case c;
  c.rec = {1, 3, 3};
  c.crit = {1, 2, 5};
  c.dominant = 2;  // B3 sees mesh G3-G4 only
  c.mesh_evidence = {9.0, 1.0};
  const GearVerdict v = Decide(Table1(), c);
  EXPECT_EQ(v.mesh, 1);
  EXPECT_EQ(v.candidates.size(), 2u);
  EXPECT_DOUBLE_EQ(v.confidence, 0.0);  // the evidence conflicts: no separation
}

TEST(GearVerdictTest, DistinctToothCountsTellEveryGearApart) {
  const VerdictTopology t = Distinct();
  struct Expect {
    std::vector<double> rec;
    std::vector<double> crit;
    int dominant;
    const char* gear;
  };
  const std::vector<Expect> cases = {
      {{5, 1, 1}, {5, 3, 1}, 0, "G1"},
      {{1, 5, 1}, {5, 3, 1}, 0, "G2"},
      {{1, 5, 1}, {1, 3, 5}, 2, "G3"},
      {{1, 1, 5}, {1, 3, 5}, 2, "G4"},
  };
  for (const Expect& e : cases) {
    Case c;
    c.rec = e.rec;
    c.crit = e.crit;
    c.dominant = e.dominant;
    const GearVerdict v = Decide(t, c);
    EXPECT_EQ(v.gear_name, e.gear) << v.reason.view();
    EXPECT_EQ(v.candidates.size(), 1u) << v.reason.view();
  }
}

TEST(GearVerdictTest, ConfidenceGrowsWithExceedanceAndShrinksWithARivalShaft) {
  Case weak;
  weak.rec = {2.4, 1, 1};
  Case strong;
  strong.rec = {20, 1, 1};
  Case rival;
  rival.rec = {20, 16, 16};
  const double cw = Decide(Table1(), weak).confidence;
  const double cs = Decide(Table1(), strong).confidence;
  const double cr = Decide(Table1(), rival).confidence;
  EXPECT_LT(cw, cs);
  EXPECT_LT(cr, cs);
  EXPECT_NEAR(cs, (1.0 - 1.0 / 10.0) * (1.0 - 0.5 / 10.0), 1e-12);
}

TEST(GearVerdictTest, RawIndicatorAloneCanRaiseTheVerdict) {
  Case c;
  c.raw = {1, 1, 5};
  c.crit = {1, 1, 5};
  c.dominant = 2;
  const GearVerdict v = Decide(Table1(), c);
  EXPECT_EQ(v.state, FaultState::kAlarm);
  EXPECT_EQ(v.candidates.size(), 2u);
}

TEST(GearVerdictTest, MismatchedInputsAreReportedNotCrashed) {
  Case c;
  c.crit = {1, 1};
  const GearVerdict v = Decide(Table1(), c);
  EXPECT_EQ(v.state, FaultState::kNoFault);
  EXPECT_EQ(std::string(v.reason.view()),
            "verdict inputs do not match the machine (3 shafts, 3 paths expected)");
}

}  // namespace
}  // namespace gearpath
