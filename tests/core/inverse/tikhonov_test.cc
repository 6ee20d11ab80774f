#include "core/inverse/tikhonov.h"

#include <gtest/gtest.h>

#include "core/inverse/least_squares.h"
#include "tests/core/inverse/random_system.h"

namespace gearpath {
namespace {

using testing::RandomSystems;
using testing::RelativeError;

TEST(Tikhonov, SolvesTheRegularisedNormalEquations) {
  // Eq. 27 solved directly, for a well-conditioned system where forming H^H H is harmless.
  RandomSystems rnd(21);
  const Eigen::MatrixXcd h = rnd.Conditioned(7, 4, 10.0);
  const Eigen::VectorXcd x = rnd.Vector(7);
  const double lambda = 0.05;
  const Eigen::VectorXcd expected =
      (h.adjoint() * h + lambda * Eigen::MatrixXcd::Identity(4, 4)).lu().solve(h.adjoint() * x);
  Result<Eigen::VectorXcd> est = SolveTikhonov(h, x, lambda);
  ASSERT_TRUE(est.ok());
  EXPECT_LT(RelativeError(*est, expected), 1e-12);
}

TEST(Tikhonov, TendsToLeastSquaresAsLambdaGoesToZero) {
  RandomSystems rnd(22);
  for (const auto& [rows, cols] : {std::pair{8, 3}, std::pair{4, 4}, std::pair{3, 6}}) {
    const Eigen::MatrixXcd h = rnd.Conditioned(rows, cols, 100.0);
    const Eigen::VectorXcd x = rnd.Vector(rows);
    Result<Eigen::VectorXcd> ls = SolveLeastSquares(h, x);
    Result<Eigen::VectorXcd> est = SolveTikhonov(h, x, 1e-20);
    ASSERT_TRUE(ls.ok());
    ASSERT_TRUE(est.ok());
    EXPECT_LT(RelativeError(*est, *ls), 1e-10) << rows << "x" << cols;
  }
}

TEST(Tikhonov, TendsToZeroAsLambdaGoesToInfinity) {
  RandomSystems rnd(23);
  const Eigen::MatrixXcd h = rnd.Conditioned(5, 3, 10.0);
  const Eigen::VectorXcd x = rnd.Vector(5);
  Result<Eigen::VectorXcd> est = SolveTikhonov(h, x, 1e12);
  ASSERT_TRUE(est.ok());
  // ||F|| <= ||H|| ||x|| / lambda.
  EXPECT_LE(est->norm(), 1.0 * x.norm() / 1e12);
  EXPECT_GT(est->norm(), 0.0);
}

TEST(Tikhonov, RejectsANonPositiveLambdaNamingIt) {
  RandomSystems rnd(24);
  Result<Eigen::VectorXcd> est = SolveTikhonov(rnd.Matrix(3, 3), rnd.Vector(3), 0.0);
  ASSERT_FALSE(est.ok());
  EXPECT_NE(est.error().find("lambda: Tikhonov parameter must be finite and > 0"),
            std::string::npos)
      << est.error();
}

}  // namespace
}  // namespace gearpath
