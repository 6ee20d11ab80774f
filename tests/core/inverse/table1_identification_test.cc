// Noise-free identification of the Table-1 model's bearing forces (seed Eq. 44) from housing
// responses through the virtually decoupled FRFs (seed Eqs. 22/24), 1-4000 Hz.
#include <gtest/gtest.h>

#include <vector>

#include "core/frf/virtual_decoupling.h"
#include "core/inverse/identification_operator.h"
#include "core/inverse/table1_validation.h"
#include "core/model/lumped_gearbox_model.h"

namespace gearpath {
namespace {

struct Table1Case {
  FrfMatrix pp;       // H_d,pp, seats x seats (square)
  FrfMatrix stacked;  // [H_d,pp; H_d,mp], (seats + housing) x seats
  Eigen::MatrixXcd x_pp;       // seat accelerations, seats x bins
  Eigen::MatrixXcd x_stacked;  // seat and housing accelerations
  Eigen::MatrixXcd forces;     // true bearing forces (Eq. 44), seats x bins
};

Table1Case BuildCase() {
  const LumpedGearboxModel model = LumpedGearboxModel::Create(Table1Parameters()).value();
  const Eigen::VectorXd grid = Eigen::VectorXd::LinSpaced(400, 10.0, 4000.0);
  const CoupledBlocks blocks = model.CoupledBlocksOnGrid(grid).value();
  Table1Case c;
  c.pp = DecoupleAtInterface(blocks).value().decoupled;
  const FrfMatrix mp = DecoupleAtMeasurementPoints(blocks).value().decoupled;
  const Eigen::Index seats = model.rotor_count();
  c.stacked.frequency_hz = grid;
  c.x_pp.resize(seats, grid.size());
  c.x_stacked.resize(seats + 1, grid.size());
  c.forces.resize(seats, grid.size());
  Eigen::VectorXcd te(model.stage_count());
  for (int s = 0; s < model.stage_count(); ++s) te(s) = Complex(1e-6, -0.4e-6 * s);
  for (Eigen::Index k = 0; k < grid.size(); ++k) {
    Eigen::MatrixXcd h(seats + 1, seats);
    h << c.pp.at[k], mp.at[k];
    c.stacked.at.push_back(h);
    const ForcedResponse r = model.RespondToTransmissionError(grid(k), te).value();
    // The model's FRFs and ForcedResponse::acceleration are both physical (a = -w^2 X), so the
    // identified forces must come out with the true bearing forces' sign.
    for (int i = 0; i < seats; ++i) c.x_pp(i, k) = r.acceleration(model.SeatDof(i));
    c.x_stacked.col(k) << c.x_pp.col(k), r.acceleration(model.HousingDof());
    c.forces.col(k) = r.bearing_force;
  }
  return c;
}

double IdentificationError(const FrfMatrix& frf, const Eigen::MatrixXcd& x,
                           const Eigen::MatrixXcd& forces, const IdentificationOptions& o) {
  Result<IdentificationOperator> op = IdentificationOperator::Create(frf, o);
  EXPECT_TRUE(op.ok()) << op.error();
  Eigen::MatrixXcd estimate(forces.rows(), forces.cols());
  EXPECT_EQ(op->IdentifyAll(x, estimate), IdentifyStatus::kOk);
  return (estimate - forces).norm() / forces.norm();  // Frobenius over all bins and paths
}

TEST(Table1Identification, RecoversTheBearingForcesFromVirtuallyDecoupledFrfsNoiseFree) {
  const Table1Case c = BuildCase();
  IdentificationOptions mwi;
  mwi.method = InverseMethod::kMwi;
  mwi.iterations = 100000;
  mwi.regularisation.rule = RegularisationRule::kFixed;
  mwi.regularisation.parameter = 1e-8;
  IdentificationOptions tikhonov;
  tikhonov.method = InverseMethod::kTikhonov;
  tikhonov.regularisation.rule = RegularisationRule::kNoiseFloor;
  tikhonov.regularisation.relative_noise = 1e-12;  // lambda = (1e-12 sigma_1)^2 -> 0
  IdentificationOptions ls;
  ls.method = InverseMethod::kLeastSquares;
  for (const auto* system : {&c.pp, &c.stacked}) {
    const Eigen::MatrixXcd& x = system == &c.pp ? c.x_pp : c.x_stacked;
    const char* name = system == &c.pp ? "H_d,pp" : "[H_d,pp; H_d,mp]";
    EXPECT_LT(IdentificationError(*system, x, c.forces, mwi), 1e-8) << "MWI " << name;
    EXPECT_LT(IdentificationError(*system, x, c.forces, tikhonov), 1e-8) << "Tikhonov " << name;
    EXPECT_LT(IdentificationError(*system, x, c.forces, ls), 1e-8) << "LS " << name;
  }
}

}  // namespace
}  // namespace gearpath

namespace gearpath {
namespace {

TEST(Table1Validation, DecouplingIsExactAndIdentificationErrorGrowsWithNoise) {
  Table1ValidationOptions o;
  o.draws = 2;
  o.bins = 100;
  Result<Table1ValidationResult> r = ValidateOnTable1Model(o);
  ASSERT_TRUE(r.ok()) << r.error();
  ASSERT_EQ(r->decoupling.size(), 3u + 9u);  // H_47, H_57, H_67 and the 3 x 3 H_d,pp
  EXPECT_EQ(r->decoupling[0].entry, "H_74");
  for (const DecouplingEntryError& e : r->decoupling) {
    EXPECT_LT(e.max_relative_error, 1e-9) << e.system << " " << e.entry;
    EXPECT_NEAR(e.frac, 1.0, 1e-9);
  }
  EXPECT_LT(r->noise_free_error_mwi, 1e-10);
  for (const IdentificationMethodResult& m : r->methods) {
    ASSERT_EQ(m.mean_error.size(), 3u);
    EXPECT_LT(m.mean_error[0], m.mean_error[1]) << m.name;
    EXPECT_LT(m.mean_error[1], m.mean_error[2]) << m.name;
  }
  o.draws = 0;
  EXPECT_NE(ValidateOnTable1Model(o).error().find("draws"), std::string::npos);
}

}  // namespace
}  // namespace gearpath
