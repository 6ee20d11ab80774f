// Plant families: the perturbed plant is really different from the model the daemon gets, by
// the expected order; the daemon's FRF set is the nominal model's; the modal housing's
// responses are H_true F and its model is the shifted one. (parametric_plate: its own tests,
// parametric_plate_plant_test.cc and the simulator's.)
#include "core/evaluation/plant_family.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iterator>

#include "core/simulation/model_frf_set.h"

namespace gearpath {
namespace {

double Median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

TEST(PlantFamily, NamesAndHeldOut) {
  for (PlantFamily f : kAllPlantFamilies) EXPECT_EQ(ParsePlantFamily(PlantFamilyName(f)), f);
  // Held out: exactly the listed families, parametric_plate among them (modal_housing may
  // move to the tuning side by leaving the list; nothing else has to change).
  for (PlantFamily f : kAllPlantFamilies) {
    EXPECT_EQ(IsHeldOut(f), std::find(std::begin(kHeldOutFamilies), std::end(kHeldOutFamilies),
                                      f) != std::end(kHeldOutFamilies));
  }
  EXPECT_TRUE(IsHeldOut(PlantFamily::kParametricPlate));
  EXPECT_EQ(PlantFamilyName(PlantFamily::kParametricPlate), "parametric_plate");
  EXPECT_FALSE(IsHeldOut(PlantFamily::kLumpedPerturbed));
  EXPECT_FALSE(IsHeldOut(PlantFamily::kLumpedTorsional));
  EXPECT_FALSE(IsHeldOut(PlantFamily::kModalHousing));  // tuning since parametric_plate came
  EXPECT_EQ(MakeTrain(TrainVariant::kTable1).gears[3].teeth, 34);
  EXPECT_EQ(MakeTrain(TrainVariant::kDistinct).gears[3].teeth, 29);
}

TEST(PlantFamily, PerturbedParametersStayWithinThirtyPercent) {
  const GearboxParameters nominal = NominalParameters(GearTrain::Table1());
  for (std::uint64_t seed : {1u, 2u, 3u}) {
    const GearboxParameters p = PerturbedParameters(nominal, false, seed);
    auto within = [](double v, double n) { return v >= 0.7 * n - 1e-12 && v <= 1.3 * n + 1e-12; };
    for (std::size_t i = 0; i < 3; ++i) {
      EXPECT_TRUE(within(p.seat_mass_kg[i], nominal.seat_mass_kg[i]));
      EXPECT_TRUE(within(p.bearing_stiffness_n_per_m[i], nominal.bearing_stiffness_n_per_m[i]));
      EXPECT_TRUE(within(p.seat_damping_ns_per_m[i], nominal.seat_damping_ns_per_m[i]));
    }
    EXPECT_TRUE(within(p.housing_mass_kg, nominal.housing_mass_kg));
    EXPECT_TRUE(within(p.mesh_damping_ratio, nominal.mesh_damping_ratio));
    EXPECT_NE(p.seat_mass_kg[0], nominal.seat_mass_kg[0]);
    EXPECT_TRUE(p.torsional_stiffness_nm_per_rad.empty());
    const GearboxParameters t = PerturbedParameters(nominal, true, seed);
    ASSERT_EQ(t.torsional_stiffness_nm_per_rad.size(), 3u);
    EXPECT_GE(t.torsional_stiffness_nm_per_rad[0], 2e3);
    EXPECT_EQ(t.torsional_stiffness_nm_per_rad[1], 0.0);
    EXPECT_GE(t.mesh_damping_ratio, 0.05);
    EXPECT_LE(t.mesh_damping_ratio, 0.10);
  }
}

TEST(PlantFamily, LumpedPlantGivesTheDaemonTheNominalModelNotItself) {
  const GearTrain train = GearTrain::Table1();
  Result<LumpedGearboxModel> nominal = LumpedGearboxModel::Create(NominalParameters(train));
  ASSERT_TRUE(nominal.ok());
  Result<Plant> plant = MakePlant(
      {PlantFamily::kLumpedPerturbed, TrainVariant::kTable1, ChannelSet::kSeatsAndHousing, 4});
  ASSERT_TRUE(plant.ok()) << plant.error();
  const FrfSet& set = plant->model_frf;
  ASSERT_EQ(set.channels.size(), 4u);
  EXPECT_EQ(set.channels[3].sensor, "m1");
  ASSERT_EQ(set.paths.size(), 3u);
  EXPECT_EQ(set.paths[1].gears, (std::vector<std::string>{"G2", "G3"}));
  // Eq. 22 / Eq. 24 are exact on the lumped model: the stacked set equals the nominal
  // housing-alone FRFs (seats, then m1).
  const Eigen::VectorXd grid = EvaluationFrfGrid();
  Result<FrfMatrix> pp = nominal->PhysicalDecoupledPp(grid);
  Result<FrfMatrix> mp = nominal->PhysicalDecoupledMp(grid);
  ASSERT_TRUE(pp.ok() && mp.ok());
  for (Eigen::Index k = 0; k < grid.size(); k += 97) {
    const Eigen::MatrixXcd& h = set.decoupled.at[static_cast<std::size_t>(k)];
    EXPECT_LT((h.topRows(3) - pp->at[k]).norm(), 1e-6 * pp->at[k].norm()) << grid[k];
    EXPECT_LT((h.bottomRows(1) - mp->at[k]).norm(), 1e-6 * mp->at[k].norm()) << grid[k];
  }
  // The plant's own housing differs from the nominal one by the order of its +/- 30 % scatter:
  // more than a few percent typically, not orders of magnitude.
  auto* lumped = dynamic_cast<const LumpedPlantDynamics*>(plant->dynamics.get());
  ASSERT_NE(lumped, nullptr);
  Result<FrfMatrix> truth = lumped->model().PhysicalDecoupledPp(grid);
  ASSERT_TRUE(truth.ok());
  std::vector<double> rel;
  for (Eigen::Index k = 0; k < grid.size(); k += 7) {
    rel.push_back((truth->at[k] - pp->at[k]).norm() / pp->at[k].norm());
  }
  EXPECT_GT(Median(rel), 0.03);
  EXPECT_LT(Median(rel), 1.0);
}

TEST(PlantFamily, ModalHousingIsHTrueTimesTheBearingForces) {
  const GearTrain train = GearTrain::Table1();
  const ModalHousingDynamics d = ModalHousingDynamics::Random(train, true, 17);
  ASSERT_GE(d.modes().size(), 6u);
  ASSERT_LE(d.modes().size(), 12u);
  for (std::size_t r = 0; r < d.modes().size(); ++r) {
    const HousingMode& t = d.modes()[r];
    const HousingMode& m = d.model_modes()[r];
    EXPECT_GE(t.frequency_hz, 300.0);
    EXPECT_LE(t.frequency_hz, 3500.0);
    EXPECT_GE(t.damping_ratio, 0.01);
    EXPECT_LE(t.damping_ratio, 0.04);
    EXPECT_LE(std::abs(m.frequency_hz / t.frequency_hz - 1.0), 0.05 + 1e-12);
    EXPECT_LE(std::abs(m.damping_ratio / t.damping_ratio - 1.0), 0.30 + 1e-12);
    EXPECT_EQ(m.shape, t.shape);
  }
  Eigen::VectorXd f(3);
  f << 280.0, 1234.5, 3100.0;
  Result<FrfMatrix> transfer = d.TeTransfer(f);
  ASSERT_TRUE(transfer.ok());
  for (Eigen::Index k = 0; k < f.size(); ++k) {
    // H_true written out from the modal sum, independently of Accelerance().
    const double w = 2.0 * std::numbers::pi * f[k];
    Eigen::MatrixXcd h = Eigen::MatrixXcd::Zero(4, 3);
    for (const HousingMode& m : d.modes()) {
      const double wr = 2.0 * std::numbers::pi * m.frequency_hz;
      for (int c = 0; c < 4; ++c) {
        for (int b = 0; b < 3; ++b) {
          h(c, b) += m.shape[c] * m.shape[b] * (-w * w) /
                     std::complex<double>(wr * wr - w * w, 2.0 * m.damping_ratio * wr * w);
        }
      }
    }
    const Eigen::MatrixXcd g = d.ForceTransfer(f[k]);
    ASSERT_EQ(g.rows(), 3);
    ASSERT_EQ(g.cols(), 2);
    // Stage s pushes on bearings s and s + 1 only, in opposite directions.
    EXPECT_EQ(g(2, 0), 0.0);
    EXPECT_EQ(g(0, 1), 0.0);
    EXPECT_LT((g(0, 0) / g(1, 0)).real(), 0.0);
    EXPECT_LT((h * g - transfer->at[static_cast<std::size_t>(k)]).norm(), 1e-12 * (h * g).norm());
  }
}

TEST(PlantFamily, ModalPlantGivesTheDaemonTheShiftedModel) {
  Result<Plant> plant =
      MakePlant({PlantFamily::kModalHousing, TrainVariant::kDistinct, ChannelSet::kSeats, 8});
  ASSERT_TRUE(plant.ok()) << plant.error();
  auto* modal = dynamic_cast<const ModalHousingDynamics*>(plant->dynamics.get());
  ASSERT_NE(modal, nullptr);
  const FrfSet& set = plant->model_frf;
  ASSERT_EQ(set.channels.size(), 3u);
  ASSERT_EQ(set.decoupled.outputs(), 3);
  ASSERT_EQ(set.decoupled.inputs(), 3);
  std::vector<double> rel;
  for (Eigen::Index k = 0; k < set.decoupled.bins(); k += 11) {
    const double fk = set.decoupled.frequency_hz[k];
    const Eigen::MatrixXcd truth = modal->Accelerance(modal->modes(), fk);
    const Eigen::MatrixXcd model = modal->Accelerance(modal->model_modes(), fk);
    EXPECT_LT((set.decoupled.at[static_cast<std::size_t>(k)] - model).norm(), 1e-12 * model.norm());
    rel.push_back((truth - model).norm() / truth.norm());
  }
  EXPECT_GT(Median(rel), 1e-3);  // a model, not the truth
}

}  // namespace
}  // namespace gearpath
