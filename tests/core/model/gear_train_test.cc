#include "core/model/gear_train.h"

#include <gtest/gtest.h>

#include <string>

namespace gearpath {
namespace {

// The seed's Table 6: input-shaft (f1) and intermediate-shaft (f2) frequencies per speed.
struct Table6Row {
  double rpm;
  double f1_hz;
  double f2_hz;
};

class GearTrainTable6Test : public ::testing::TestWithParam<Table6Row> {};

TEST_P(GearTrainTable6Test, ShaftFrequenciesMatchTheSeedsTable6) {
  const Table6Row row = GetParam();
  const Result<TrainKinematics> k = GearTrain::Table1().Kinematics(RpmToHz(row.rpm));
  ASSERT_TRUE(k.ok()) << k.error();
  ASSERT_EQ(k->shafts.size(), 3u);
  // Table 6 prints two decimals (4.669 once); compare to its printed precision.
  EXPECT_NEAR(k->shafts[0].rotation_hz, row.f1_hz, 0.006);
  EXPECT_NEAR(k->shafts[1].rotation_hz, row.f2_hz, 0.006);
  // Z3 = Z4 = 34: the output shaft turns with the intermediate shaft.
  EXPECT_NEAR(k->shafts[2].rotation_hz, k->shafts[1].rotation_hz, 1e-12);
  // Exact kinematics: f2 = f1 * 28 / 40.
  EXPECT_NEAR(k->shafts[1].rotation_hz, RpmToHz(row.rpm) * 28.0 / 40.0, 1e-12);
}

INSTANTIATE_TEST_SUITE_P(SeedSpeeds, GearTrainTable6Test,
                         ::testing::Values(Table6Row{600, 10.0, 7.0}, Table6Row{500, 8.33, 5.83},
                                           Table6Row{400, 6.67, 4.669}, Table6Row{300, 5.0, 3.5}));

TEST(GearTrainTest, MeshFrequenciesAt600RpmAre280And238Hz) {
  const Result<TrainKinematics> k = GearTrain::Table1().Kinematics(10.0);
  ASSERT_TRUE(k.ok()) << k.error();
  ASSERT_EQ(k->meshes.size(), 2u);
  EXPECT_NEAR(k->meshes[0].mesh_hz, 280.0, 1e-9);  // 28 * 10 Hz = 40 * 7 Hz
  EXPECT_NEAR(k->meshes[1].mesh_hz, 238.0, 1e-9);  // 34 * 7 Hz
  // The mesh frequency is the same seen from either gear of the pair.
  EXPECT_NEAR(k->meshes[0].mesh_hz, 40 * k->shafts[1].rotation_hz, 1e-9);
  EXPECT_NEAR(k->meshes[1].mesh_hz, 34 * k->shafts[2].rotation_hz, 1e-9);
}

TEST(GearTrainTest, EveryGearKnowsItsShaftStageAndCharacteristicFrequency) {
  const Result<TrainKinematics> k = GearTrain::Table1().Kinematics(10.0);
  ASSERT_TRUE(k.ok()) << k.error();
  ASSERT_EQ(k->gears.size(), 4u);
  const int want_shaft[] = {0, 1, 1, 2};
  const int want_stage[] = {0, 0, 1, 1};
  const double want_hz[] = {10.0, 7.0, 7.0, 7.0};
  for (int g = 0; g < 4; ++g) {
    EXPECT_EQ(k->gears[g].name, "G" + std::to_string(g + 1));
    EXPECT_EQ(k->gears[g].shaft, want_shaft[g]) << k->gears[g].name;
    EXPECT_EQ(k->gears[g].stage, want_stage[g]) << k->gears[g].name;
    EXPECT_NEAR(k->gears[g].characteristic_hz, want_hz[g], 1e-12) << k->gears[g].name;
  }
}

TEST(GearTrainTest, BearingsAreNearTheGearsOfTheirShaft) {
  const GearTrain t = GearTrain::Table1();
  EXPECT_EQ(t.GearsNearBearing(0), (std::vector<std::string>{"G1"}));
  EXPECT_EQ(t.GearsNearBearing(1), (std::vector<std::string>{"G2", "G3"}));
  EXPECT_EQ(t.GearsNearBearing(2), (std::vector<std::string>{"G4"}));
  EXPECT_TRUE(t.GearsNearBearing(3).empty());
}

TEST(GearTrainTest, StagesListedAgainstThePowerFlowStillPropagate) {
  GearTrain t = GearTrain::Table1();
  std::swap(t.stages[0], t.stages[1]);  // output stage first
  std::swap(t.shafts[1], t.shafts[2]);  // output shaft listed before intermediate
  const Result<TrainKinematics> k = t.Kinematics(10.0);
  ASSERT_TRUE(k.ok()) << k.error();
  EXPECT_NEAR(k->shafts[1].rotation_hz, 7.0, 1e-12);  // "output"
  EXPECT_NEAR(k->shafts[2].rotation_hz, 7.0, 1e-12);  // "intermediate"
}

TEST(GearTrainTest, ContactRatioMatchesTheTextbookValueForTwentyToothPairs) {
  // Two standard 20-tooth gears, 20 deg pressure angle, full-depth: eps = 1.557 (textbook).
  EXPECT_NEAR(StandardContactRatio(20, 20, 20.0, 1.0), 1.557, 1e-3);
  // Table 1's pairs, evaluated by hand from the same definition: 1.676 and 1.681.
  const Result<TrainKinematics> k = GearTrain::Table1().Kinematics(10.0);
  ASSERT_TRUE(k.ok());
  EXPECT_NEAR(k->meshes[0].contact_ratio, 1.676, 2e-3);
  EXPECT_NEAR(k->meshes[1].contact_ratio, 1.681, 2e-3);
}

TEST(GearTrainTest, CommonPeriodOfTable1IsTenInputRevolutions) {
  // Intermediate and output turn at 7/10 of the input: after 10 input revolutions (1 s at
  // 600 r/min) they have made exactly 7.
  const Result<std::int64_t> n = GearTrain::Table1().InputRevolutionsPerCommonPeriod();
  ASSERT_TRUE(n.ok()) << n.error();
  EXPECT_EQ(*n, 10);
}

TEST(GearTrainTest, CommonPeriodOfCoprimeRatiosIsTheProductOfTheDenominators) {
  // 20 -> 30 (2/3), then 25 -> 35 (5/7): shaft speeds 1, 2/3, 10/21 -> lcm(1, 3, 21) = 21.
  GearTrain t;
  t.shafts = {{"in", {"A"}}, {"mid", {"B", "C"}}, {"out", {"D"}}};
  t.gears = {{"A", 20}, {"B", 30}, {"C", 25}, {"D", 35}};
  t.stages = {{"A", "B"}, {"C", "D"}};
  const Result<std::int64_t> n = t.InputRevolutionsPerCommonPeriod();
  ASSERT_TRUE(n.ok()) << n.error();
  EXPECT_EQ(*n, 21);
  const Result<TrainKinematics> k = t.Kinematics(21.0);
  ASSERT_TRUE(k.ok());
  EXPECT_NEAR(k->shafts[2].rotation_hz, 10.0, 1e-12);  // 21 * 10/21 revolutions per second
}

// Validation: each broken train is rejected with a message naming the field.
std::string WhyInvalid(const GearTrain& t) {
  std::string why;
  EXPECT_FALSE(t.IsValid(&why));
  return why;
}

TEST(GearTrainValidationTest, Table1IsValid) {
  std::string why = "not cleared";
  EXPECT_TRUE(GearTrain::Table1().IsValid(&why)) << why;
  EXPECT_TRUE(why.empty());
  EXPECT_TRUE(GearTrain::Table1().Validate().ok());
}

TEST(GearTrainValidationTest, RejectsToothCountBelowOne) {
  GearTrain t = GearTrain::Table1();
  t.gears[2].teeth = 0;
  EXPECT_EQ(WhyInvalid(t), "gears[2] (G3): teeth must be >= 1, got 0");
}

TEST(GearTrainValidationTest, RejectsGearOnTwoShafts) {
  GearTrain t = GearTrain::Table1();
  t.shafts[2].gears.push_back("G1");
  EXPECT_EQ(WhyInvalid(t), "gears[0] (G1): on two shafts, 'input' and 'output'");
}

TEST(GearTrainValidationTest, RejectsBearingOnUnknownShaft) {
  GearTrain t = GearTrain::Table1();
  t.bearings[1].shaft = "shaft9";
  EXPECT_EQ(WhyInvalid(t), "bearings[1] (B2): unknown shaft 'shaft9'");
}

TEST(GearTrainValidationTest, RejectsShaftListingUnknownGear) {
  GearTrain t = GearTrain::Table1();
  t.shafts[1].gears.push_back("G9");
  EXPECT_EQ(WhyInvalid(t), "shafts[1] (intermediate): unknown gear 'G9'");
}

TEST(GearTrainValidationTest, RejectsGearOnNoShaft) {
  GearTrain t = GearTrain::Table1();
  t.shafts[2].gears.clear();
  EXPECT_EQ(WhyInvalid(t), "gears[3] (G4): on no shaft");
}

TEST(GearTrainValidationTest, RejectsStageWithUnknownGearOrBothGearsOnOneShaft) {
  GearTrain t = GearTrain::Table1();
  t.stages[1].driven = "G7";
  EXPECT_EQ(WhyInvalid(t), "stages[1] (G3->G7): unknown gear 'G7'");
  t = GearTrain::Table1();
  t.stages = {{"G1", "G2"}, {"G2", "G3"}};
  EXPECT_EQ(WhyInvalid(t),
            "gears[1] (G2): meshes in two stages (0 and 1); idler gears are not "
            "supported");
}

TEST(GearTrainValidationTest, RejectsShaftNotDrivenFromTheInput) {
  GearTrain t = GearTrain::Table1();
  t.shafts.push_back({"spare", {"G5", "G6"}});
  t.gears.push_back({"G5", 20});
  t.gears.push_back({"G6", 30});
  t.shafts[3].gears = {"G5"};
  t.shafts.push_back({"spare2", {"G6"}});
  t.stages.push_back({"G5", "G6"});
  EXPECT_EQ(WhyInvalid(t),
            "shafts[3] (spare): not connected to the input shaft through any "
            "stage, so its speed is unknown");
}

TEST(GearTrainValidationTest, RejectsDuplicateNamesAndEmptyLists) {
  GearTrain t = GearTrain::Table1();
  t.gears[3].name = "G1";
  EXPECT_EQ(WhyInvalid(t), "gears[3] (G1): duplicate gear name");
  EXPECT_EQ(WhyInvalid(GearTrain{}), "shafts: at least one shaft (the input shaft) is required");
}

TEST(GearTrainValidationTest, KinematicsRejectsNonPositiveSpeedAndInvalidTrain) {
  const Result<TrainKinematics> bad_speed = GearTrain::Table1().Kinematics(0.0);
  ASSERT_FALSE(bad_speed.ok());
  EXPECT_NE(bad_speed.error().find("input speed"), std::string::npos) << bad_speed.error();
  GearTrain t = GearTrain::Table1();
  t.gears[0].teeth = -3;
  const Result<TrainKinematics> bad_train = t.Kinematics(10.0);
  ASSERT_FALSE(bad_train.ok());
  EXPECT_EQ(bad_train.error(), "gear train: gears[0] (G1): teeth must be >= 1, got -3");
}

}  // namespace
}  // namespace gearpath
