#include "core/frf/virtual_decoupling.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <utility>

#include "core/frf/frac.h"
#include "core/model/lumped_gearbox_model.h"
#include "tests/core/model/three_stage_gearbox.h"

namespace gearpath {
namespace {

// 1 Hz steps over 1-4000 Hz (4000 bins), the band of the seed's Fig. 5.
Eigen::VectorXd FineGrid() { return Eigen::VectorXd::LinSpaced(4000, 1.0, 4000.0); }

using gearpath::testing::ThreeStageParameters;

// Worst over bins of ||virtual - physical||_F / ||physical||_F.
double WorstRelativeError(const FrfMatrix& virtual_frf, const FrfMatrix& physical) {
  double worst = 0.0;
  for (Eigen::Index k = 0; k < physical.bins(); ++k) {
    worst = std::max(worst, (virtual_frf.at[k] - physical.at[k]).norm() / physical.at[k].norm());
  }
  return worst;
}

// Checks Eqs. 22 and 24 against the housing-alone model (seed Eq. 7) on the fine grid, with
// and without H_ap, and FRAC = 1 for every entry.
void ExpectVirtualEqualsPhysical(const GearboxParameters& parameters) {
  const Result<LumpedGearboxModel> model = LumpedGearboxModel::Create(parameters);
  ASSERT_TRUE(model.ok()) << model.error();
  const Eigen::VectorXd grid = FineGrid();
  const Result<CoupledBlocks> blocks = model->CoupledBlocksOnGrid(grid);
  ASSERT_TRUE(blocks.ok()) << blocks.error();
  const Result<FrfMatrix> physical_pp = model->PhysicalDecoupledPp(grid);
  const Result<FrfMatrix> physical_mp = model->PhysicalDecoupledMp(grid);
  ASSERT_TRUE(physical_pp.ok() && physical_mp.ok());

  const Result<VirtualDecouplingResult> pp = DecoupleAtInterface(*blocks);
  const Result<VirtualDecouplingResult> mp = DecoupleAtMeasurementPoints(*blocks);
  ASSERT_TRUE(pp.ok()) << pp.error();
  ASSERT_TRUE(mp.ok()) << mp.error();
  const double err_pp = WorstRelativeError(pp->decoupled, *physical_pp);
  const double err_mp = WorstRelativeError(mp->decoupled, *physical_mp);
  EXPECT_LE(err_pp, 1e-9);
  EXPECT_LE(err_mp, 1e-9);
  std::printf(
      "  stages %zu: worst relative error (Frobenius, per bin) H_d,pp %.3g, H_d,mp %.3g; "
      "worst condition %.3g at %.0f Hz\n",
      parameters.stages.size(), err_pp, err_mp, pp->report.worst_condition_number,
      pp->report.worst_frequency_hz);

  struct Pair {
    const char* name;
    const FrfMatrix* virtual_frf;
    const FrfMatrix* physical;
  };
  for (const Pair& pair : {Pair{"H_d,pp", &pp->decoupled, &*physical_pp},
                           Pair{"H_d,mp", &mp->decoupled, &*physical_mp}}) {
    const FrfMatrix* virtual_frf = pair.virtual_frf;
    const FrfMatrix* physical = pair.physical;
    const Result<Eigen::MatrixXd> frac = FracPerEntry(*virtual_frf, *physical, 1.0, 4000.0);
    ASSERT_TRUE(frac.ok()) << frac.error();
    const double worst_frac_deviation = (frac->array() - 1.0).abs().maxCoeff();
    EXPECT_LE(worst_frac_deviation, 1e-9) << *frac;
    std::printf("  stages %zu: worst |FRAC - 1| over the entries of %s, 1-4000 Hz: %.3g\n",
                parameters.stages.size(), pair.name, worst_frac_deviation);
  }

  // Leaving H_ap out (reciprocity H_ap = H_pa^T) gives the same result.
  CoupledBlocks without_ap = *blocks;
  without_ap.ap.clear();
  const Result<VirtualDecouplingResult> pp_recip = DecoupleAtInterface(without_ap);
  const Result<VirtualDecouplingResult> mp_recip = DecoupleAtMeasurementPoints(without_ap);
  ASSERT_TRUE(pp_recip.ok() && mp_recip.ok());
  EXPECT_LE(WorstRelativeError(pp_recip->decoupled, pp->decoupled), 1e-10);
  EXPECT_LE(WorstRelativeError(mp_recip->decoupled, mp->decoupled), 1e-10);
}

TEST(VirtualDecoupling, EqualsPhysicalDecouplingOnTable1ModelFrom1To4000Hz) {
  ExpectVirtualEqualsPhysical(Table1Parameters());
}

TEST(VirtualDecoupling, EqualsPhysicalDecouplingOnAThreeStageVariant) {
  ExpectVirtualEqualsPhysical(ThreeStageParameters());
}

TEST(VirtualDecoupling, UncoupledInterfaceGivesTheCoupledFrfBack) {
  // H_pa = 0 (nothing links a and p): Eq. 22 returns H_pp, Eq. 24 returns H_mp.
  CoupledBlocks b;
  b.frequency_hz = Eigen::Vector2d(10.0, 20.0);
  for (int k = 0; k < 2; ++k) {
    b.aa.push_back(Eigen::MatrixXcd::Random(2, 2) + 3.0 * Eigen::MatrixXcd::Identity(2, 2));
    b.pa.push_back(Eigen::MatrixXcd::Zero(2, 2));
    b.ap.push_back(Eigen::MatrixXcd::Zero(2, 2));
    b.pp.push_back(Eigen::MatrixXcd::Random(2, 2));
    b.ma.push_back(Eigen::MatrixXcd::Zero(1, 2));
    b.mp.push_back(Eigen::MatrixXcd::Random(1, 2));
  }
  const Result<VirtualDecouplingResult> pp = DecoupleAtInterface(b);
  const Result<VirtualDecouplingResult> mp = DecoupleAtMeasurementPoints(b);
  ASSERT_TRUE(pp.ok() && mp.ok());
  for (int k = 0; k < 2; ++k) {
    EXPECT_TRUE(pp->decoupled.at[k].isApprox(b.pp[k], 1e-14));
    EXPECT_TRUE(mp->decoupled.at[k].isApprox(b.mp[k], 1e-14));
  }
}

TEST(VirtualDecoupling, ReportsFiniteConditionNumbersAndTheWorstBin) {
  const LumpedGearboxModel model = LumpedGearboxModel::Create(Table1Parameters()).value();
  const Eigen::VectorXd grid = Eigen::VectorXd::LinSpaced(400, 10.0, 4000.0);
  const Result<VirtualDecouplingResult> r = DecoupleAtInterface(*model.CoupledBlocksOnGrid(grid));
  ASSERT_TRUE(r.ok()) << r.error();
  const Eigen::VectorXd& cond = r->report.condition_number;
  ASSERT_EQ(cond.size(), grid.size());
  EXPECT_TRUE(cond.allFinite());
  EXPECT_GE(cond.minCoeff(), 1.0);  // a 2-norm condition number is never below 1
  Eigen::Index worst = 0;
  cond.maxCoeff(&worst);
  EXPECT_EQ(r->report.worst_bin, worst);
  EXPECT_EQ(r->report.worst_condition_number, cond[worst]);
  EXPECT_EQ(r->report.worst_frequency_hz, grid[worst]);
  EXPECT_DOUBLE_EQ(r->report.limit, 1.0 / (3.0 * std::numeric_limits<double>::epsilon()));
}

CoupledBlocks DiagonalBlocks(int bins, int n) {
  CoupledBlocks b;
  b.frequency_hz = Eigen::VectorXd::LinSpaced(bins, 10.0, 10.0 + 2.5 * (bins - 1));
  for (int k = 0; k < bins; ++k) {
    b.aa.push_back(2.0 * Eigen::MatrixXcd::Identity(n, n));
    b.pa.push_back(Eigen::MatrixXcd::Identity(n, n));
    b.pp.push_back(Eigen::MatrixXcd::Identity(n, n));
  }
  return b;
}

TEST(VirtualDecoupling, SingularInterfaceBlockIsAnErrorNamingTheFrequency) {
  CoupledBlocks b = DiagonalBlocks(4, 3);
  b.pa[2] = b.aa[2];  // H_pa - H_aa = 0 at 15 Hz
  Result<VirtualDecouplingResult> r = DecoupleAtInterface(b);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().find("singular at 15 Hz (bin 2)"), std::string::npos) << r.error();
  EXPECT_NE(r.error().find("Eq. 22"), std::string::npos) << r.error();

  // Numerically singular: rank 2 up to rounding -> condition number beyond 1/(n eps).
  b = DiagonalBlocks(4, 3);
  b.pa[1](2, 2) = 2.0;
  b.aa[1](2, 2) = Complex(2.0, 1e-17);  // singular values 1, 1, 1e-17
  r = DecoupleAtInterface(b);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().find("numerically singular at 12.5 Hz"), std::string::npos) << r.error();
  EXPECT_NE(r.error().find("condition number"), std::string::npos) << r.error();

  // A user limit applies.
  b = DiagonalBlocks(4, 3);
  b.pa[3](0, 0) = 2.001;  // singular values 1, 1, 0.001 -> condition number 1000
  r = DecoupleAtInterface(b, VirtualDecouplingOptions{100.0});
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().find("17.5 Hz"), std::string::npos) << r.error();
  EXPECT_NE(r.error().find("1e+03"), std::string::npos) << r.error();
  EXPECT_TRUE(DecoupleAtInterface(b, VirtualDecouplingOptions{1e4}).ok());
}

TEST(VirtualDecoupling, RejectsMismatchedShapesNamingTheBlock) {
  CoupledBlocks b = DiagonalBlocks(3, 3);
  b.pa[0] = Eigen::MatrixXcd::Identity(2, 3);
  Result<VirtualDecouplingResult> r = DecoupleAtInterface(b);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().find("one p DOF per a DOF"), std::string::npos) << r.error();

  b = DiagonalBlocks(3, 3);
  b.pp[1] = Eigen::MatrixXcd::Identity(3, 2);
  r = DecoupleAtInterface(b);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().find("H_pp at bin 1 is 3 x 2, expected 3 x 3"), std::string::npos)
      << r.error();

  b = DiagonalBlocks(3, 3);
  b.ap.assign(2, Eigen::MatrixXcd::Identity(3, 3));
  r = DecoupleAtInterface(b);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().find("H_ap has 2 bins"), std::string::npos) << r.error();

  b = DiagonalBlocks(3, 3);
  r = DecoupleAtMeasurementPoints(b);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().find("H_ma is missing"), std::string::npos) << r.error();
  b.ma.assign(3, Eigen::MatrixXcd::Zero(1, 3));
  r = DecoupleAtMeasurementPoints(b);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().find("H_mp is missing"), std::string::npos) << r.error();
  b.mp.assign(3, Eigen::MatrixXcd::Zero(2, 3));
  r = DecoupleAtMeasurementPoints(b);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().find("H_mp at bin 0 is 2 x 3, expected 1 x 3"), std::string::npos)
      << r.error();

  b = DiagonalBlocks(3, 3);
  b.aa[2](0, 1) = Complex(std::nan(""), 0.0);
  r = DecoupleAtInterface(b);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().find("H_aa at bin 2 has a non-finite entry"), std::string::npos) << r.error();

  r = DecoupleAtInterface(CoupledBlocks{});
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().find("no frequency bins"), std::string::npos) << r.error();
}

}  // namespace
}  // namespace gearpath
