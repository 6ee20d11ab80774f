#include "core/inverse/least_squares.h"

#include <gtest/gtest.h>

#include "tests/core/inverse/random_system.h"

namespace gearpath {
namespace {

using testing::RandomSystems;
using testing::RelativeError;

TEST(LeastSquares, RecoversKnownForcesOfAnOverdeterminedSystem) {
  RandomSystems rnd(1);
  const Eigen::MatrixXcd h = rnd.Conditioned(9, 4, 1e3);
  const Eigen::VectorXcd f = rnd.Vector(4);
  Result<Eigen::VectorXcd> est = SolveLeastSquares(h, h * f);
  ASSERT_TRUE(est.ok()) << est.error();
  EXPECT_LT(RelativeError(*est, f), 1e-10);
}

TEST(LeastSquares, RecoversKnownForcesOfASquareSystem) {
  RandomSystems rnd(2);
  const Eigen::MatrixXcd h = rnd.Conditioned(5, 5, 1e3);
  const Eigen::VectorXcd f = rnd.Vector(5);
  Result<Eigen::VectorXcd> est = SolveLeastSquares(h, h * f);
  ASSERT_TRUE(est.ok()) << est.error();
  EXPECT_LT(RelativeError(*est, f), 1e-10);
}

TEST(LeastSquares, GivesTheMinimumNormSolutionOfAnUnderdeterminedSystem) {
  RandomSystems rnd(3);
  const Eigen::MatrixXcd h = rnd.Conditioned(3, 7, 1e2);
  const Eigen::VectorXcd x = rnd.Vector(3);
  // Analytical minimum-norm solution H^H (H H^H)^{-1} x.
  const Eigen::VectorXcd expected = h.adjoint() * (h * h.adjoint()).lu().solve(x);
  Result<Eigen::VectorXcd> est = SolveLeastSquares(h, x);
  ASSERT_TRUE(est.ok()) << est.error();
  EXPECT_LT(RelativeError(*est, expected), 1e-10);
  EXPECT_LT((h * *est - x).norm() / x.norm(), 1e-12);
}

TEST(LeastSquares, ProjectsAnInconsistentResponseOntoTheRangeOfH) {
  RandomSystems rnd(4);
  const Eigen::MatrixXcd h = rnd.Matrix(8, 3);
  const Eigen::VectorXcd x = rnd.Vector(8);
  Result<Eigen::VectorXcd> est = SolveLeastSquares(h, x);
  ASSERT_TRUE(est.ok());
  // Normal equations: the residual is orthogonal to every column of H.
  EXPECT_LT((h.adjoint() * (x - h * *est)).norm(), 1e-12 * h.norm() * x.norm());
}

TEST(LeastSquares, DropsSingularValuesBelowTheRankTolerance) {
  // Exactly rank one: H = u v^H. Minimum-norm solution is v (u^H x) / (|u|^2 |v|^2).
  Eigen::VectorXcd u(3), v(2);
  u << Complex(1, 0), Complex(0, 2), Complex(-1, 1);
  v << Complex(2, -1), Complex(1, 1);
  const Eigen::MatrixXcd h = u * v.adjoint();
  Eigen::VectorXcd x(3);
  x << Complex(1, 1), Complex(2, 0), Complex(0, -1);
  const Eigen::VectorXcd expected = v * (u.dot(x) / (u.squaredNorm() * v.squaredNorm()));
  Result<Eigen::VectorXcd> est = SolveLeastSquares(h, x);
  ASSERT_TRUE(est.ok());
  EXPECT_LT(RelativeError(*est, expected), 1e-12);
}

TEST(LeastSquares, ZeroResponseGivesZeroForces) {
  RandomSystems rnd(5);
  Result<Eigen::VectorXcd> est = SolveLeastSquares(rnd.Matrix(4, 2), Eigen::VectorXcd::Zero(4));
  ASSERT_TRUE(est.ok());
  EXPECT_EQ(est->norm(), 0.0);
}

TEST(LeastSquares, RejectsInvalidInputNamingTheArgument) {
  RandomSystems rnd(6);
  const Eigen::MatrixXcd h = rnd.Matrix(3, 2);
  EXPECT_NE(SolveLeastSquares(Eigen::MatrixXcd(0, 2), Eigen::VectorXcd(0)).error().find("empty"),
            std::string::npos);
  EXPECT_NE(SolveLeastSquares(h, Eigen::VectorXcd::Zero(4)).error().find("x: has 4 responses"),
            std::string::npos);
  const Eigen::MatrixXcd bad = Eigen::MatrixXcd::Constant(3, 2, Complex(0.0, std::nan("")));
  EXPECT_NE(SolveLeastSquares(bad, Eigen::VectorXcd::Zero(3)).error().find("H: entry (0, 0) is not finite"),
            std::string::npos);
  EXPECT_NE(SolveLeastSquares(h, Eigen::VectorXcd::Zero(3), 2.0).error().find("relative_tolerance"),
            std::string::npos);
}

}  // namespace
}  // namespace gearpath
