#include "core/model/lumped_gearbox_model.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <numbers>

#include "tests/core/model/three_stage_gearbox.h"

namespace gearpath {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

LumpedGearboxModel Table1Model() {
  Result<LumpedGearboxModel> model = LumpedGearboxModel::Create(Table1Parameters());
  EXPECT_TRUE(model.ok()) << (model.ok() ? "" : model.error());
  return std::move(model).value();
}

using gearpath::testing::ThreeStageParameters;

double RelativeError(const Eigen::MatrixXcd& a, const Eigen::MatrixXcd& b) {
  return (a - b).norm() / b.norm();
}

TEST(LumpedGearboxModel, ComputesTable1GearMassesFromSolidDiscsOfPitchRadius) {
  // By hand: rho = 7850 kg/m^3, b = 16 mm, m = 3 mm, r = m z / 2.
  //  gear 1 (z 28): r = 42 mm, mass = 7850 pi 0.042^2 0.016 = 0.696046 kg, J = m r^2/2 = 6.13913e-4
  //  gear 2 (z 40): r = 60 mm, mass = 1.420503 kg, J = 2.556905e-3
  //  gear 3, 4 (z 34): r = 51 mm, mass = 1.026313 kg, J = 1.334720e-3
  // Rotor 2 (intermediate shaft) carries gears 2 and 3.
  const LumpedGearboxModel model = Table1Model();
  ASSERT_EQ(model.rotors().size(), 3u);
  EXPECT_NEAR(model.rotors()[0].mass_kg, 0.696046, 1e-6);
  EXPECT_NEAR(model.rotors()[0].inertia_kg_m2, 6.13913e-4, 1e-9);
  EXPECT_NEAR(model.rotors()[1].mass_kg, 1.420503 + 1.026313, 2e-6);
  EXPECT_NEAR(model.rotors()[1].inertia_kg_m2, 2.556905e-3 + 1.334720e-3, 2e-9);
  EXPECT_NEAR(model.rotors()[2].mass_kg, 1.026313, 1e-6);
  EXPECT_NEAR(model.rotors()[2].inertia_kg_m2, 1.334720e-3, 1e-9);
  // Base radius rb = r cos 20 deg.
  const double cos20 = std::cos(20.0 * std::numbers::pi / 180.0);
  EXPECT_NEAR(model.meshes()[0].base_radius_driver_m, 0.042 * cos20, 1e-12);
  EXPECT_NEAR(model.meshes()[0].base_radius_driven_m, 0.060 * cos20, 1e-12);
}

TEST(LumpedGearboxModel, EstimatesMeshStiffnessWithIsoMeanMeshStiffness) {
  // Stage 1 (28/40, m 3 mm, alpha 20 deg, h_a* = 1), by hand:
  //  rb1 = 39.467 mm, rb2 = 56.382 mm, ra1 = 45 mm, ra2 = 63 mm,
  //  path of contact = sqrt(45^2 - 39.467^2) + sqrt(63^2 - 56.382^2) - 102 sin 20 = 14.841 mm,
  //  base pitch = pi 3 cos 20 = 8.8564 mm -> eps_alpha = 1.67577.
  //  c_gamma_alpha = 14 (0.75 * 1.67577 + 0.25) = 21.096 N/(mm um); k = 21.096 * 16 mm
  //  = 337.5 N/um = 3.3753e8 N/m.
  const LumpedGearboxModel model = Table1Model();
  EXPECT_NEAR(model.meshes()[0].contact_ratio, 1.67577, 1e-5);
  EXPECT_NEAR(model.meshes()[0].stiffness_n_per_m, 3.3753e8, 1e4);
  // Stage 2 (34/34): eps_alpha = 1.68057, k = 3.3834e8 N/m.
  EXPECT_NEAR(model.meshes()[1].contact_ratio, 1.68057, 1e-5);
  EXPECT_NEAR(model.meshes()[1].stiffness_n_per_m, 3.3834e8, 1e4);
}

TEST(LumpedGearboxModel, UsesAnExplicitMeshStiffnessWhenGiven) {
  GearboxParameters p = Table1Parameters();
  p.stages[1].mesh_stiffness_n_per_m = 2.5e8;
  const Result<LumpedGearboxModel> model = LumpedGearboxModel::Create(p);
  ASSERT_TRUE(model.ok()) << model.error();
  EXPECT_EQ(model->meshes()[1].stiffness_n_per_m, 2.5e8);
}

TEST(LumpedGearboxModel, MeshDampingFollowsDampingRatioAndEquivalentMass) {
  // Equivalent mass of stage 1 along the line of action, from the rotor inertias:
  //  J1 / rb1^2 = 6.13913e-4 / 0.0394671^2 = 0.394130 kg,
  //  J2 / rb2^2 = 3.891625e-3 / 0.0563816^2 = 1.224198 kg, m_e = 0.298142 kg;
  //  c = 2 * 0.02 * sqrt(3.3753e8 * 0.298142) = 401.3 N s/m.
  const LumpedGearboxModel model = Table1Model();
  EXPECT_NEAR(model.meshes()[0].equivalent_mass_kg, 0.298142, 2e-6);
  EXPECT_NEAR(model.meshes()[0].damping_ns_per_m, 401.3, 0.1);
}

TEST(LumpedGearboxModel, AssemblesSeedStiffnessMatrixFromMeshEnergy) {
  // Seed Eq. 4 for q = [x1, th1, x2, th2, x3, th3, x4, x5, x6, x7], with the two corrections
  // noted in the model header (symmetric (x2, th1) entry; k25 and k36 on the diagonal).
  const LumpedGearboxModel model = Table1Model();
  const Eigen::MatrixXd& k = model.stiffness();
  ASSERT_EQ(k.rows(), 10);
  const double k1 = model.meshes()[0].stiffness_n_per_m;
  const double k2 = model.meshes()[1].stiffness_n_per_m;
  const double rb1 = model.meshes()[0].base_radius_driver_m;
  const double rb2 = model.meshes()[0].base_radius_driven_m;
  const double rb3 = model.meshes()[1].base_radius_driver_m;
  const double rb4 = model.meshes()[1].base_radius_driven_m;
  const double tol = 1e-6;
  EXPECT_NEAR(k(0, 0), 1e7 + k1, tol);
  EXPECT_NEAR(k(0, 1), rb1 * k1, tol);
  EXPECT_NEAR(k(0, 2), -k1, tol);
  EXPECT_NEAR(k(0, 3), rb2 * k1, tol);
  EXPECT_NEAR(k(0, 6), -1e7, tol);
  EXPECT_NEAR(k(1, 1), rb1 * rb1 * k1, tol);
  EXPECT_NEAR(k(2, 1), -rb1 * k1, tol);      // printed as +rb1 k1 in the seed
  EXPECT_NEAR(k(2, 2), k1 + k2 + 1e7, tol);  // seed omits k25
  EXPECT_NEAR(k(2, 3), -rb2 * k1 + rb3 * k2, tol);
  EXPECT_NEAR(k(3, 3), rb2 * rb2 * k1 + rb3 * rb3 * k2, tol);
  EXPECT_NEAR(k(3, 5), rb3 * rb4 * k2, tol);
  EXPECT_NEAR(k(4, 4), k2 + 1e7, tol);  // seed omits k36
  EXPECT_NEAR(k(5, 4), -rb4 * k2, tol);
  EXPECT_NEAR(k(5, 5), rb4 * rb4 * k2, tol);
  EXPECT_NEAR(k(6, 6), 1e7 + 1e8, tol);
  EXPECT_NEAR(k(6, 9), -1e8, tol);
  EXPECT_NEAR(k(9, 9), 3e8 + 1e8, tol);  // k47 + k57 + k67 + k07
  EXPECT_TRUE(k.isApprox(k.transpose(), 1e-15));
  EXPECT_TRUE(model.damping().isApprox(model.damping().transpose(), 1e-15));
  EXPECT_TRUE(model.mass().isDiagonal());
}

TEST(LumpedGearboxModel, RollingGearTrainWithoutTransmissionErrorStoresNoEnergy) {
  // Independent check of the mesh sign convention: rb1 th1 = -rb2 th2, rb3 th2 = -rb4 th3,
  // x = 0 deflects no mesh, so K q = 0.
  const LumpedGearboxModel model = Table1Model();
  const auto& mesh = model.meshes();
  Eigen::VectorXd q = Eigen::VectorXd::Zero(10);
  q[1] = 1.0;
  q[3] = -mesh[0].base_radius_driver_m / mesh[0].base_radius_driven_m;
  q[5] = -mesh[1].base_radius_driver_m * q[3] / mesh[1].base_radius_driven_m;
  EXPECT_LT((model.stiffness() * q).norm(), 1e-9 * model.stiffness().norm());
  EXPECT_EQ(model.NaturalFrequenciesHz()[0], 0.0);
  EXPECT_GT(model.NaturalFrequenciesHz()[1], 1.0);
}

TEST(LumpedGearboxModel, HousingAloneMatchesSeedEq7) {
  const LumpedGearboxModel model = Table1Model();
  Eigen::MatrixXd expected_k(4, 4);
  expected_k << 1e8, 0, 0, -1e8,  //
      0, 1e8, 0, -1e8,            //
      0, 0, 1e8, -1e8,            //
      -1e8, -1e8, -1e8, 4e8;
  Eigen::MatrixXd expected_c(4, 4);
  expected_c << 1e3, 0, 0, -1e3,  //
      0, 1e3, 0, -1e3,            //
      0, 0, 1e3, -1e3,            //
      -1e3, -1e3, -1e3, 4e3;
  EXPECT_TRUE(model.housing_stiffness().isApprox(expected_k, 1e-14));
  EXPECT_TRUE(model.housing_damping().isApprox(expected_c, 1e-14));
  EXPECT_TRUE(
      model.housing_mass().isApprox(Eigen::Vector4d(1, 2, 3, 23.5).asDiagonal().toDenseMatrix()));
}

TEST(LumpedGearboxModel, StaticLimitOfReceptanceIsTheInverseStiffness) {
  // With torsional couplings to ground there is no rigid mode, so K is invertible.
  GearboxParameters p = Table1Parameters();
  p.torsional_stiffness_nm_per_rad = {2e5, 0.0, 3e5};
  const Result<LumpedGearboxModel> model = LumpedGearboxModel::Create(p);
  ASSERT_TRUE(model.ok()) << model.error();
  // Low enough that w C and w^2 M are below 1e-8 of K (w c14 / k14 = 6e-9 at 1e-6 Hz).
  const double f = 1e-6;
  const double w = kTwoPi * f;
  const Result<Eigen::MatrixXcd> h = model->Accelerance(f);
  ASSERT_TRUE(h.ok()) << h.error();
  const Eigen::MatrixXd k_inv = model->stiffness().inverse();
  // Physical accelerance -w^2 X / f, so -H / w^2 is the static flexibility.
  EXPECT_LT(RelativeError(-*h / (w * w), k_inv.cast<Complex>()), 1e-7);
  // Exactly at 0 Hz the accelerance is zero and a static load gives K^-1 f.
  EXPECT_EQ(model->Accelerance(0.0)->norm(), 0.0);
  Eigen::VectorXcd load = Eigen::VectorXcd::Zero(10);
  load[0] = 100.0;
  load[5] = 3.0;  // a torque on rotor 3, reacted by its coupling
  const Result<ForcedResponse> r = model->Respond(0.0, load);
  ASSERT_TRUE(r.ok()) << r.error();
  const Eigen::VectorXd x = k_inv * load.real();
  const Eigen::VectorXcd bearing = r->bearing_force;
  EXPECT_LT(std::abs(bearing[0] - 1e7 * (x(0) - x(6))), 1e-9 * 100.0);
  EXPECT_LT(std::abs(bearing[2] - 1e7 * (x(4) - x(8))), 1e-9 * 100.0);
}

TEST(LumpedGearboxModel, AcceleranceAtZeroHzIsTheFreeRotationLimit) {
  // -w^2 (K - w^2 M)^-1 -> +phi phi^T for the free gear-train rotation phi (phi^T M phi = 1).
  const LumpedGearboxModel model = Table1Model();
  const auto& mesh = model.meshes();
  Eigen::VectorXd phi = Eigen::VectorXd::Zero(10);
  phi[1] = 1.0;
  phi[3] = -mesh[0].base_radius_driver_m / mesh[0].base_radius_driven_m;
  phi[5] = -mesh[1].base_radius_driver_m * phi[3] / mesh[1].base_radius_driven_m;
  phi /= std::sqrt(phi.dot(model.mass() * phi));
  const Eigen::MatrixXd expected = phi * phi.transpose();
  const Result<Eigen::MatrixXcd> h0 = model.Accelerance(0.0);
  ASSERT_TRUE(h0.ok());
  EXPECT_LT(RelativeError(*h0, expected.cast<Complex>()), 1e-9);
  // A static net torque cannot be in equilibrium.
  Eigen::VectorXcd torque = Eigen::VectorXcd::Zero(10);
  torque[1] = 1.0;
  const Result<ForcedResponse> r = model.Respond(0.0, torque);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().find("free rotation"), std::string::npos) << r.error();
}

TEST(LumpedGearboxModel, UndampedFrfGrowsWithoutBoundAtEveryNaturalFrequency) {
  GearboxParameters p = Table1Parameters();
  p.bearing_damping_ns_per_m = {0, 0, 0};
  p.seat_damping_ns_per_m = {0, 0, 0};
  p.ground_damping_ns_per_m = 0.0;
  p.mesh_damping_ratio = 0.0;
  const Result<LumpedGearboxModel> model = LumpedGearboxModel::Create(p);
  ASSERT_TRUE(model.ok()) << model.error();
  // Natural frequencies by an independent solve of K phi = w^2 M phi.
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eig(model->stiffness(), model->mass());
  int elastic = 0;
  for (Eigen::Index k = 0; k < eig.eigenvalues().size(); ++k) {
    if (eig.eigenvalues()[k] < 1.0) continue;  // the free rotation
    ++elastic;
    const double fn = std::sqrt(eig.eigenvalues()[k]) / kTwoPi;
    // Near a simple pole H ~ 1 / (fn - f): approaching 100x closer gives ~100x the response.
    const double near = model->Accelerance(fn * (1.0 - 1e-7))->norm();
    const double far = model->Accelerance(fn * (1.0 - 1e-5))->norm();
    EXPECT_GT(near / far, 50.0) << "mode at " << fn << " Hz";
    EXPECT_LT(near / far, 200.0) << "mode at " << fn << " Hz";
    EXPECT_NEAR(model->NaturalFrequenciesHz()[k], fn, 1e-9 * fn);
  }
  EXPECT_EQ(elastic, 9);
}

TEST(LumpedGearboxModel, CoupledAcceleranceIsReciprocal) {
  const LumpedGearboxModel model = Table1Model();
  for (double f : {1.0, 137.0, 950.0, 2600.0, 4000.0}) {
    const Eigen::MatrixXcd h = *model.Accelerance(f);
    EXPECT_LT(RelativeError(h.transpose(), h), 1e-12) << f << " Hz";
  }
}

TEST(LumpedGearboxModel, BearingForcesBalanceHousingInertiaAndGroundReaction) {
  // Housing (seats + central mass) free body: sum_i F_i - (k07 + j w c07) X_7 = sum m a.
  // Rotor side under a pure mesh excitation: the mesh forces cancel in translation, so
  // sum over rotors of m a_x = -sum_i F_i.
  const LumpedGearboxModel model = LumpedGearboxModel::Create(ThreeStageParameters()).value();
  const GearboxParameters& p = model.parameters();
  Eigen::VectorXcd te(3);
  te << Complex(1e-6, 2e-7), Complex(-3e-7, 5e-7), Complex(2e-7, 0.0);
  for (double f : {3.0, 420.0, 1777.0, 3900.0}) {
    const double w = kTwoPi * f;
    const Result<ForcedResponse> r = model.RespondToTransmissionError(f, te);
    ASSERT_TRUE(r.ok()) << r.error();
    const Eigen::VectorXcd& a = r->acceleration;
    Complex housing_inertia = p.housing_mass_kg * a[model.HousingDof()];
    Complex rotor_inertia = 0.0;
    for (int i = 0; i < model.rotor_count(); ++i) {
      housing_inertia += p.seat_mass_kg[i] * a[model.SeatDof(i)];
      rotor_inertia += model.rotors()[i].mass_kg * a[model.RotorTranslationDof(i)];
    }
    const Complex x7 = -a[model.HousingDof()] / (w * w);
    const Complex ground = Complex(p.ground_stiffness_n_per_m, w * p.ground_damping_ns_per_m) * x7;
    const Complex bearing_sum = r->bearing_force.sum();
    const double scale = r->bearing_force.cwiseAbs().maxCoeff();
    EXPECT_LT(std::abs(bearing_sum - ground - housing_inertia), 1e-9 * scale) << f << " Hz";
    EXPECT_LT(std::abs(rotor_inertia + bearing_sum), 1e-9 * scale) << f << " Hz";
  }
}

TEST(LumpedGearboxModel, StaticTransmissionErrorOfAFreeGearTrainIsTakenUpByRotation) {
  // Nothing holds the seed's gear train in rotation: a static TE e1 is absorbed by turning
  // rotor 1 by e1 / rb1, which deflects no spring, so no bearing carries a static force.
  const LumpedGearboxModel model = Table1Model();
  Eigen::VectorXcd te(2);
  te << 1e-6, 0.0;
  const Result<ForcedResponse> r = model.RespondToTransmissionError(0.0, te);
  ASSERT_TRUE(r.ok()) << r.error();
  const double mesh_force = model.meshes()[0].stiffness_n_per_m * 1e-6;
  EXPECT_LT(r->bearing_force.cwiseAbs().maxCoeff(), 1e-9 * mesh_force);
  EXPECT_EQ(r->acceleration.norm(), 0.0);
}

TEST(LumpedGearboxModel, StaticTransmissionErrorAgainstCouplingsLoadsBearingsWithZeroNetForce) {
  // With torsional couplings the TE is reacted: bearings carry static forces, but a mesh force
  // is internal to the rotor side, so they sum to zero.
  GearboxParameters p = Table1Parameters();
  p.torsional_stiffness_nm_per_rad = {2e5, 0.0, 3e5};
  const LumpedGearboxModel model = LumpedGearboxModel::Create(p).value();
  Eigen::VectorXcd te(2);
  te << 1e-6, 0.0;
  const Result<ForcedResponse> r = model.RespondToTransmissionError(0.0, te);
  ASSERT_TRUE(r.ok()) << r.error();
  const double mesh_force = model.meshes()[0].stiffness_n_per_m * 1e-6;
  EXPECT_GT(r->bearing_force.cwiseAbs().maxCoeff(), 1e-3 * mesh_force);
  EXPECT_LT(std::abs(r->bearing_force.sum()), 1e-9 * mesh_force);
}

TEST(LumpedGearboxModel, MeshForceIsMeshImpedanceTimesErrorAlongMeshVector) {
  const LumpedGearboxModel model = Table1Model();
  Eigen::VectorXcd te(2);
  te << Complex(2e-6, -1e-6), Complex(0.0, 3e-7);
  const double f = 500.0;
  const double w = kTwoPi * f;
  const Eigen::VectorXcd force = *model.MeshForce(f, te);
  const auto& m = model.meshes();
  // Stage 1 pushes +(k1 + j w c1) e1 on x1 and -(...) on x2; stage 2 likewise on x2, x3.
  const Complex z1(m[0].stiffness_n_per_m, w * m[0].damping_ns_per_m);
  const Complex z2(m[1].stiffness_n_per_m, w * m[1].damping_ns_per_m);
  EXPECT_LT(std::abs(force[0] - z1 * te[0]), 1e-12 * std::abs(z1 * te[0]));
  EXPECT_LT(std::abs(force[1] - z1 * te[0] * m[0].base_radius_driver_m), 1e-6);
  EXPECT_LT(std::abs(force[2] - (-z1 * te[0] + z2 * te[1])), 1e-6);
  EXPECT_LT(std::abs(force[5] - z2 * te[1] * m[1].base_radius_driven_m), 1e-6);
  EXPECT_EQ(force.tail(4).norm(), 0.0);
}

TEST(LumpedGearboxModel, TransmissionErrorTransferColumnsAreUnitErrorResponses) {
  const LumpedGearboxModel model = LumpedGearboxModel::Create(ThreeStageParameters()).value();
  const Eigen::VectorXd grid = Eigen::VectorXd::LinSpaced(5, 0.0, 2000.0);
  const Result<TransmissionErrorTransfer> t = model.TransmissionErrorTransferOnGrid(grid);
  ASSERT_TRUE(t.ok()) << t.error();
  ASSERT_EQ(t->seat_acceleration.at[0].rows(), 4);
  ASSERT_EQ(t->seat_acceleration.at[0].cols(), 3);
  for (Eigen::Index k = 0; k < grid.size(); ++k) {
    for (int s = 0; s < 3; ++s) {
      Eigen::VectorXcd te = Eigen::VectorXcd::Zero(3);
      te[s] = 1.0;
      const ForcedResponse r = *model.RespondToTransmissionError(grid[k], te);
      const double scale = r.bearing_force.norm();
      EXPECT_LT((t->bearing_force.at[k].col(s) - r.bearing_force).norm(), 1e-12 * scale);
      const double accel_scale = r.acceleration.norm() + 1e-300;
      for (int i = 0; i < 4; ++i) {
        EXPECT_LT(std::abs(t->seat_acceleration.at[k](i, s) - r.acceleration[model.SeatDof(i)]),
                  1e-12 * accel_scale);
      }
      EXPECT_LT(std::abs(t->housing_acceleration.at[k](0, s) - r.acceleration[model.HousingDof()]),
                1e-12 * accel_scale);
    }
  }
}

TEST(LumpedGearboxModel, StageCountSetsDofLayoutAndRoles) {
  for (int stages : {1, 2, 3, 5}) {
    GearboxParameters p = Table1Parameters();
    p.stages.assign(stages, GearStage{23, 37, std::nullopt});
    const std::size_t rotors = static_cast<std::size_t>(stages) + 1;
    p.bearing_stiffness_n_per_m.assign(rotors, 1e7);
    p.bearing_damping_ns_per_m.assign(rotors, 1e4);
    p.seat_mass_kg.assign(rotors, 1.2);
    p.seat_stiffness_n_per_m.assign(rotors, 1e8);
    p.seat_damping_ns_per_m.assign(rotors, 1e3);
    const Result<LumpedGearboxModel> model = LumpedGearboxModel::Create(p);
    ASSERT_TRUE(model.ok()) << model.error();
    EXPECT_EQ(model->dof_count(), 3 * stages + 4);
    EXPECT_EQ(model->housing_dof_count(), stages + 2);
    EXPECT_EQ(model->ActiveDofs().size(), rotors);
    EXPECT_EQ(model->PassiveDofs().size(), rotors);
    EXPECT_EQ(model->MeasurementDofs(), std::vector<Eigen::Index>{3 * stages + 3});
    EXPECT_EQ(model->PassiveDofs().front(), 2 * stages + 2);
    const Result<CoupledBlocks> blocks =
        model->CoupledBlocksOnGrid(Eigen::VectorXd::LinSpaced(3, 10.0, 30.0), false);
    ASSERT_TRUE(blocks.ok());
    EXPECT_FALSE(blocks->has_ap());
    EXPECT_EQ(blocks->aa[0].rows(), stages + 1);
    EXPECT_EQ(blocks->mp[0].rows(), 1);
  }
}

TEST(LumpedGearboxModel, RejectsParametersWithMessagesNamingTheField) {
  GearboxParameters p = Table1Parameters();
  p.stages.clear();
  Result<LumpedGearboxModel> m = LumpedGearboxModel::Create(p);
  ASSERT_FALSE(m.ok());
  EXPECT_NE(m.error().find("stages"), std::string::npos);

  p = Table1Parameters();
  p.seat_mass_kg = {1.0, 2.0};
  m = LumpedGearboxModel::Create(p);
  ASSERT_FALSE(m.ok());
  EXPECT_NE(m.error().find("seat_mass_kg has 2 entries, expected 3"), std::string::npos)
      << m.error();

  p = Table1Parameters();
  p.bearing_stiffness_n_per_m[1] = -1.0;
  m = LumpedGearboxModel::Create(p);
  ASSERT_FALSE(m.ok());
  EXPECT_NE(m.error().find("bearing_stiffness_n_per_m[1]"), std::string::npos) << m.error();

  p = Table1Parameters();
  p.ground_stiffness_n_per_m = 0.0;
  m = LumpedGearboxModel::Create(p);
  ASSERT_FALSE(m.ok());
  EXPECT_NE(m.error().find("ground_stiffness_n_per_m"), std::string::npos) << m.error();

  p = Table1Parameters();
  p.stages[0].z_driver = 0;
  m = LumpedGearboxModel::Create(p);
  ASSERT_FALSE(m.ok());
  EXPECT_NE(m.error().find("stages[0]"), std::string::npos) << m.error();
}

TEST(LumpedGearboxModel, RejectsBadFrequenciesAndForceSizes) {
  const LumpedGearboxModel model = Table1Model();
  Result<Eigen::MatrixXcd> h = model.Accelerance(-1.0);
  ASSERT_FALSE(h.ok());
  EXPECT_NE(h.error().find("-1 Hz"), std::string::npos) << h.error();
  Eigen::VectorXd grid(3);
  grid << 1.0, 3.0, 2.0;
  const Result<FrfMatrix> frf = model.Accelerance(grid);
  ASSERT_FALSE(frf.ok());
  EXPECT_NE(frf.error().find("bin 2"), std::string::npos) << frf.error();
  const Result<ForcedResponse> r = model.Respond(10.0, Eigen::VectorXcd::Zero(4));
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().find("has 4 entries, expected 10"), std::string::npos) << r.error();
  const Result<Eigen::VectorXcd> mf = model.MeshForce(10.0, Eigen::VectorXcd::Zero(3));
  ASSERT_FALSE(mf.ok());
  EXPECT_NE(mf.error().find("one per stage"), std::string::npos) << mf.error();
}

}  // namespace
}  // namespace gearpath
