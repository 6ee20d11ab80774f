#include "core/inverse/mwi.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <tuple>

#include "core/inverse/least_squares.h"
#include "core/inverse/spectral_filter.h"
#include "tests/core/inverse/random_system.h"

namespace gearpath {
namespace {

using testing::RandomSystems;
using testing::RelativeError;

TEST(MwiWeights, AreTheInverseRowNormsOfHHermitianH) {
  RandomSystems rnd(11);
  const Eigen::MatrixXcd h = rnd.Conditioned(6, 4, 50.0, 100.0);
  Result<Eigen::VectorXd> w = MwiWeights(h);
  ASSERT_TRUE(w.ok());
  const Eigen::MatrixXcd a = h.adjoint() * h;
  for (Eigen::Index i = 0; i < 4; ++i) {
    double sum = 0.0;  // Eq. 40 written out: sqrt(1 / sum_j |a_ij|^2).
    for (Eigen::Index j = 0; j < 4; ++j) sum += std::norm(a(i, j));
    EXPECT_DOUBLE_EQ((*w)(i), std::sqrt(1.0 / sum));
  }
}

TEST(MwiWeights, RejectAZeroColumnNamingIt) {
  Eigen::MatrixXcd h = Eigen::MatrixXcd::Identity(3, 3);
  h(2, 2) = 0.0;
  Result<Eigen::VectorXd> w = MwiWeights(h);
  ASSERT_FALSE(w.ok());
  EXPECT_NE(w.error().find("column 2 is zero"), std::string::npos) << w.error();
}

// (alpha, K, rows, cols)
class MwiClosedForm : public ::testing::TestWithParam<std::tuple<double, int, int, int>> {};

TEST_P(MwiClosedForm, EqualsTheLiteralIteration) {
  const auto [alpha, k, rows, cols] = GetParam();
  RandomSystems rnd(static_cast<unsigned>(100 * rows + cols + k));
  const Eigen::MatrixXcd h = rnd.Conditioned(rows, cols, 30.0, 20.0);
  const Eigen::VectorXcd x = rnd.Vector(rows);
  Result<Eigen::VectorXcd> literal = SolveMwiByIteration(h, x, alpha, k);
  Result<Eigen::VectorXcd> closed = SolveMwi(h, x, alpha, k);
  ASSERT_TRUE(literal.ok()) << literal.error();
  ASSERT_TRUE(closed.ok()) << closed.error();
  EXPECT_LT(RelativeError(*closed, *literal), 1e-10)
      << "alpha " << alpha << " K " << k << " shape " << rows << "x" << cols;
}

INSTANTIATE_TEST_SUITE_P(
    SeveralParametersAndShapes, MwiClosedForm,
    ::testing::Values(std::make_tuple(1e-3, 1, 6, 3), std::make_tuple(1e-3, 7, 6, 3),
                      std::make_tuple(0.1, 3, 4, 4), std::make_tuple(1e-4, 50, 4, 4),
                      std::make_tuple(1.0, 20, 3, 6), std::make_tuple(1e-2, 5, 2, 5),
                      std::make_tuple(10.0, 2, 12, 4), std::make_tuple(1e-6, 200, 5, 5)));

TEST(Mwi, ConvergesToLeastSquaresOnOverdeterminedAndSquareSystems) {
  RandomSystems rnd(12);
  for (const auto& [rows, cols] : {std::pair{8, 3}, std::pair{4, 4}}) {
    const Eigen::MatrixXcd h = rnd.Conditioned(rows, cols, 100.0, 50.0);
    const Eigen::VectorXcd f = rnd.Vector(cols);
    Result<Eigen::VectorXcd> est = SolveMwi(h, h * f, 1e-5, 100000);
    ASSERT_TRUE(est.ok());
    EXPECT_LT(RelativeError(*est, f), 1e-10) << rows << "x" << cols;
    // The literal iteration agrees in this converged regime too.
    Result<Eigen::VectorXcd> literal = SolveMwiByIteration(h, h * f, 1e-5, 100000);
    ASSERT_TRUE(literal.ok());
    EXPECT_LT(RelativeError(*literal, f), 1e-9);
  }
}

TEST(Mwi, ConvergesToTheWeightedMinimumNormSolutionOfAnUnderdeterminedSystem) {
  RandomSystems rnd(13);
  const Eigen::MatrixXcd h = rnd.Conditioned(3, 6, 20.0, 10.0);
  const Eigen::VectorXcd x = rnd.Vector(3);
  Result<Eigen::VectorXd> w = MwiWeights(h);
  ASSERT_TRUE(w.ok());
  // Minimum of ||W^{-1/2} F|| subject to H F = x: F = W H^H (H W H^H)^{-1} x.
  const Eigen::MatrixXcd hw = h * w->asDiagonal();
  const Eigen::VectorXcd expected = hw.adjoint() * (hw * h.adjoint()).lu().solve(x);
  Result<Eigen::VectorXcd> est = SolveMwi(h, x, 1e-5, 100000);
  ASSERT_TRUE(est.ok());
  EXPECT_LT(RelativeError(*est, expected), 1e-10);
  EXPECT_LT((h * *est - x).norm() / x.norm(), 1e-10);
}

TEST(Mwi, ZeroResponseGivesZeroForces) {
  RandomSystems rnd(14);
  Result<Eigen::VectorXcd> est = SolveMwi(rnd.Matrix(4, 3), Eigen::VectorXcd::Zero(4), 0.1, 5);
  ASSERT_TRUE(est.ok());
  EXPECT_EQ(est->norm(), 0.0);
}

TEST(Mwi, OneStepOnADiagonalSystemMatchesTheHandComputation) {
  // H = diag(2, 4): A = diag(4, 16), W = diag(1/4, 1/16), A W = I, so f_1 = H^H x / (1 + alpha)
  // and F = W f_1.
  Eigen::MatrixXcd h = Eigen::MatrixXcd::Zero(2, 2);
  h(0, 0) = 2.0;
  h(1, 1) = 4.0;
  Eigen::VectorXcd x(2);
  x << Complex(1, 2), Complex(-3, 1);
  const double alpha = 0.5;
  Eigen::VectorXcd expected(2);
  expected << 2.0 * x(0) / 1.5 / 4.0, 4.0 * x(1) / 1.5 / 16.0;
  Result<Eigen::VectorXcd> est = SolveMwi(h, x, alpha, 1);
  ASSERT_TRUE(est.ok());
  EXPECT_LT(RelativeError(*est, expected), 1e-14);
}

TEST(Mwi, RegularisationLowersTheConditionNumberOfTheWeightedMatrix) {
  // Appendix B: A W is similar to the Hermitian positive definite W^{1/2} A W^{1/2}, so its
  // eigenvalues are real and positive and adding alpha I lowers their max/min ratio.
  RandomSystems rnd(15);
  for (double alpha : {1e-6, 1e-3, 0.1, 10.0}) {
    const Eigen::MatrixXcd h = rnd.Conditioned(6, 4, 1e4, 30.0);
    Result<Eigen::VectorXd> w = MwiWeights(h);
    ASSERT_TRUE(w.ok());
    const Eigen::MatrixXcd aw = h.adjoint() * h * w->asDiagonal();
    auto spectral_condition = [](const Eigen::MatrixXcd& m) {
      const Eigen::VectorXd mags = Eigen::ComplexEigenSolver<Eigen::MatrixXcd>(m)
                                       .eigenvalues()
                                       .cwiseAbs();
      return mags.maxCoeff() / mags.minCoeff();
    };
    const Eigen::MatrixXcd shifted = aw + alpha * Eigen::MatrixXcd::Identity(4, 4);
    EXPECT_LT(spectral_condition(shifted), spectral_condition(aw)) << "alpha " << alpha;
  }
}

TEST(Mwi, RejectsInvalidParametersNamingThem) {
  RandomSystems rnd(16);
  const Eigen::MatrixXcd h = rnd.Matrix(3, 2);
  const Eigen::VectorXcd x = rnd.Vector(3);
  for (double alpha : {0.0, -1.0, std::nan(""), HUGE_VAL}) {
    Result<Eigen::VectorXcd> est = SolveMwi(h, x, alpha, 3);
    ASSERT_FALSE(est.ok());
    EXPECT_NE(est.error().find("alpha"), std::string::npos) << est.error();
    EXPECT_FALSE(SolveMwiByIteration(h, x, alpha, 3).ok());
  }
  Result<Eigen::VectorXcd> est = SolveMwi(h, x, 0.1, 0);
  ASSERT_FALSE(est.ok());
  EXPECT_NE(est.error().find("iterations: MWI needs K >= 1"), std::string::npos) << est.error();
  EXPECT_NE(SolveMwi(h, rnd.Vector(2), 0.1, 1).error().find("x: has 2 responses"),
            std::string::npos);
}

}  // namespace
}  // namespace gearpath
