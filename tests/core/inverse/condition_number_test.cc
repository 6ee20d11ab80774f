#include "core/inverse/condition_number.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "tests/core/inverse/random_system.h"

// ConditionFromGram against the prescribed condition number of RandomSystems::Conditioned
// (singular values exactly 1 .. 1/condition, up to eps in the construction). Below about 540
// (12 x 12) it reads the Gram eigenvalues, whose relative error it bounds by
// kGramConditionTolerance / 2; above, it falls back to the singular values of A (error about
// eps * condition, that of any SVD).
namespace gearpath {
namespace {

using testing::RandomSystems;

constexpr double kInfinity = std::numeric_limits<double>::infinity();

TEST(ConditionNumber, FromGramMatchesThePrescribedConditionOnBothRoutes) {
  RandomSystems rnd(101);
  struct Shape {
    Eigen::Index rows;
    Eigen::Index cols;
  };
  for (const Shape shape : {Shape{12, 12}, Shape{18, 12}, Shape{4, 7}}) {
    for (const double condition : {1.0, 10.0, 300.0, 2e3, 1e6}) {
      const Eigen::MatrixXcd a = rnd.Conditioned(shape.rows, shape.cols, condition, 20.0);
      // Column scaling changes the singular values: the reference is A's own, from JacobiSVD
      // where the column spread applies (and the prescribed value without it, below).
      const Eigen::VectorXd sv = Eigen::JacobiSVD<Eigen::MatrixXcd>(a).singularValues();
      const double reference = sv(0) / sv(sv.size() - 1);
      const double tolerance = std::max(kGramConditionTolerance,
                                        1e3 * std::numeric_limits<double>::epsilon() * reference);
      EXPECT_NEAR(ConditionFromGram(a, a.adjoint() * a) / reference, 1.0, tolerance)
          << shape.rows << "x" << shape.cols << " condition " << reference;
      const Eigen::MatrixXcd plain = rnd.Conditioned(shape.rows, shape.cols, condition);
      EXPECT_NEAR(ConditionFromGram(plain, plain.adjoint() * plain) / condition, 1.0, tolerance)
          << shape.rows << "x" << shape.cols << " prescribed condition " << condition;
    }
  }
}

TEST(ConditionNumber, SingularAndZeroMatricesAreInfiniteOrHuge) {
  EXPECT_EQ(ConditionFromGram(Eigen::MatrixXcd::Zero(3, 2), Eigen::MatrixXcd::Zero(2, 2)),
            kInfinity);
  RandomSystems rnd(102);
  Eigen::MatrixXcd h = rnd.Matrix(5, 3);
  h.col(1).setZero();
  EXPECT_GT(ConditionFromGram(h, h.adjoint() * h), 1e14);
  EXPECT_EQ(ConditionFromSingularValues(Eigen::VectorXd()), kInfinity);
  EXPECT_EQ(ConditionFromSingularValues(Eigen::Vector3d(2.0, 1.0, 0.0)), kInfinity);
  EXPECT_EQ(ConditionFromSingularValues(Eigen::Vector3d(2.0, 1.0, 0.5)), 4.0);
}

}  // namespace
}  // namespace gearpath
