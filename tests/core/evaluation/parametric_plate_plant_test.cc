// The parametric_plate family's draw: parameters in their documented ranges; the daemon's FRF
// set is the MODEL plate's accelerance (Eq. 22 / 24 of a housing-alone model), which differs
// from the truth by the intended model error: not zero, bounded, and largest above the model's
// cutoff where its modes are missing; the tooth fault draw.
#include "core/evaluation/parametric_plate_plant.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "core/evaluation/plant_family.h"

namespace gearpath {
namespace {

double Median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

TEST(ParametricPlatePlant, ParametersLieInTheirDocumentedRanges) {
  for (std::uint64_t seed : {1u, 2u, 3u, 4u}) {
    for (TrainVariant variant : {TrainVariant::kTable1, TrainVariant::kDistinct}) {
      const GearTrain train = MakeTrain(variant);
      Result<ParametricPlatePlant> plant = DrawParametricPlatePlant(train, true, seed);
      ASSERT_TRUE(plant.ok()) << plant.error();
      const ParametricGearboxParameters& p = plant->truth->parameters();
      ASSERT_EQ(p.shafts.size(), 3u);
      ASSERT_EQ(p.stages.size(), 2u);
      EXPECT_EQ(p.shafts[0].rotation_sign, 1);
      EXPECT_EQ(p.shafts[1].rotation_sign, -1);
      EXPECT_EQ(p.shafts[2].rotation_sign, 1);
      EXPECT_NEAR(p.shafts[1].revs_per_input_rev, 0.7, 1e-12);
      for (const ShaftRotor& r : p.shafts) {
        EXPECT_GE(r.bearing_stiffness_n_per_m, 1e8);
        EXPECT_LE(r.bearing_stiffness_n_per_m, 4e8);
      }
      for (int s = 0; s < 2; ++s) {
        const ToothMesh& m = plant->truth->meshes()[s];
        EXPECT_GE(m.parameters().contact_ratio, 1.4);
        EXPECT_LE(m.parameters().contact_ratio, 1.8);
        // ISO 6336-1 mean stiffness c' (0.75 eps + 0.25) b, c' = 14 N/(mm um), b = 16 mm, +/-15 %.
        const double iso = 14e9 * (0.75 * m.parameters().contact_ratio + 0.25) * 0.016;
        EXPECT_GE(m.mean_stiffness(), 0.85 * iso * (1 - 1e-9));
        EXPECT_LE(m.mean_stiffness(), 1.15 * iso * (1 + 1e-9));
        EXPECT_EQ(m.parameters().profile_amplitude_m.size(), 4u);
      }
      EXPECT_GE(p.load_torque_nm, 40.0);
      EXPECT_LE(p.load_torque_nm, 90.0);
      const PlateHousing& plate = p.plate;
      EXPECT_EQ(plate.point_count(), 4);  // three bearing seats and m1
      EXPECT_LE(plate.modes().back().frequency_hz, 5000.0);
      EXPECT_GT(plate.mode_count(), 10);
      // The model: modes up to its cutoff only (2.2 .. 2.8 kHz), fewer than the truth.
      EXPECT_GE(plant->model_cutoff_hz, 2200.0);
      EXPECT_LE(plant->model_cutoff_hz, 2800.0);
      EXPECT_LE(plant->model_plate.modes().back().frequency_hz, plant->model_cutoff_hz);
      EXPECT_LT(plant->model_plate.mode_count(), plate.mode_count());
      const double h_ratio = plant->model_plate.geometry().thickness_m / plate.geometry().thickness_m;
      EXPECT_GE(h_ratio, 0.97);
      EXPECT_LE(h_ratio, 1.03);
      for (const PlateMode& m : plant->model_plate.modes()) {
        const auto t = std::find_if(plate.modes().begin(), plate.modes().end(),
                                    [&m](const PlateMode& q) { return q.m == m.m && q.n == m.n; });
        ASSERT_NE(t, plate.modes().end());
        EXPECT_GE(m.damping_ratio / t->damping_ratio, 0.7 - 1e-12);
        EXPECT_LE(m.damping_ratio / t->damping_ratio, 1.3 + 1e-12);
      }
    }
  }
}

TEST(ParametricPlatePlant, TheDaemonGetsTheModelNotTheTruthWithTheIntendedError) {
  Result<Plant> plant = MakePlant(
      {PlantFamily::kParametricPlate, TrainVariant::kTable1, ChannelSet::kSeatsAndHousing, 6});
  ASSERT_TRUE(plant.ok()) << plant.error();
  ASSERT_TRUE(plant->parametric != nullptr);
  EXPECT_TRUE(plant->dynamics == nullptr);
  const FrfSet& set = plant->model_frf;
  ASSERT_EQ(set.channels.size(), 4u);
  EXPECT_EQ(set.channels[3].sensor, "m1");
  ASSERT_EQ(set.paths.size(), 3u);
  EXPECT_EQ(set.paths[1].name, "B2x");
  EXPECT_EQ(set.paths[1].gears, (std::vector<std::string>{"G2", "G3"}));
  ASSERT_EQ(set.decoupled.bins(), 4096);
  const PlateHousing& truth = plant->parametric->truth->plate();
  const PlateHousing& model = plant->parametric->model_plate;
  const std::vector<int> rows = {0, 1, 2, 3}, cols = {0, 1, 2};
  std::vector<double> low, high;
  for (Eigen::Index k = 0; k < set.decoupled.bins(); k += 7) {
    const double f = set.decoupled.frequency_hz[k];
    const Eigen::MatrixXcd& h = set.decoupled.at[static_cast<std::size_t>(k)];
    const Eigen::MatrixXcd m = model.Accelerance(f, rows, cols);
    EXPECT_LT((h - m).norm(), 1e-12 * m.norm()) << f;  // the set is the model plate's
    const double rel = (truth.Accelerance(f, rows, cols) - h).norm() / truth.Accelerance(f, rows, cols).norm();
    if (f > 50.0 && f < 2000.0) low.push_back(rel);
    if (f > 3000.0) high.push_back(rel);
  }
  std::printf("model vs truth, median relative FRF error: %.3f below 2 kHz, %.3f above 3 kHz\n",
              Median(low), Median(high));
  EXPECT_GT(Median(low), 0.01);   // a model, not the truth
  EXPECT_LT(Median(low), 1.0);    // not another plate altogether
  EXPECT_GT(Median(high), Median(low));  // the missing modes
  EXPECT_LT(Median(high), 3.0);
}

TEST(ParametricPlatePlant, ToothFaultDrawNamesTheGearsStageAndSide) {
  const GearTrain train = GearTrain::Table1();
  Result<ParametricPlatePlant> plant = DrawParametricPlatePlant(train, false, 2);
  ASSERT_TRUE(plant.ok());
  struct Case {
    const char* gear;
    int stage;
    bool driver;
    int teeth;
  };
  for (const Case& c : {Case{"G1", 0, true, 28}, Case{"G2", 0, false, 40}, Case{"G3", 1, true, 34},
                        Case{"G4", 1, false, 34}}) {
    Result<ToothFault> f = DrawToothFault(*plant, train, PlantFaultKind::kCombined, c.gear, 99);
    ASSERT_TRUE(f.ok()) << f.error();
    EXPECT_EQ(f->stage, c.stage) << c.gear;
    EXPECT_EQ(f->on_driver, c.driver) << c.gear;
    EXPECT_GE(f->tooth, 0);
    EXPECT_LT(f->tooth, c.teeth);
    EXPECT_GE(f->severity.pulse_length_periods, 0.4);
    EXPECT_LE(f->severity.pulse_length_periods, 0.8);
    EXPECT_GE(f->wear_length, 2.0);
    EXPECT_LE(f->wear_length, 3.0);
  }
  EXPECT_FALSE(DrawToothFault(*plant, train, PlantFaultKind::kMeshAm, "G9", 1).ok());
  Result<ToothFault> none = DrawToothFault(*plant, train, PlantFaultKind::kNone, "", 1);
  ASSERT_TRUE(none.ok());
  EXPECT_EQ(none->kind, PlantFaultKind::kNone);
}

}  // namespace
}  // namespace gearpath
