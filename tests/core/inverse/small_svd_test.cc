#include "core/inverse/small_svd.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <utility>

#include "tests/core/inverse/random_system.h"

// ThinSvd against Eigen::JacobiSVD, the decomposition it replaces, as the independent reference.
// Tolerances (any two backward-stable SVDs differ by about eps * sigma_1 per singular value):
//   singular values: |sigma_i - sigma_i(ref)| <= 1e-13 sigma_1 (measured <= 6e-15);
//   U and V orthonormal, U S V^H = A: 1e-13 (measured <= 7e-15);
//   regularised inverse with cutoff 1e-3 sigma_1 (the default noise floor): relative 1e-11
//   (measured <= 3e-12 up to condition 1e10);
//   unregularised pseudo-inverse: relative 100 * eps * condition (its own sensitivity).
namespace gearpath {
namespace {

using testing::RandomSystems;

constexpr double kEps = std::numeric_limits<double>::epsilon();

struct Shape {
  Eigen::Index rows;
  Eigen::Index cols;
};

// V diag(sigma / (sigma^2 + lambda)) U^H, or the pseudo-inverse for lambda = 0.
Eigen::MatrixXcd FilteredInverse(const Eigen::MatrixXcd& u, const Eigen::VectorXd& sigma,
                                 const Eigen::MatrixXcd& v, double lambda) {
  Eigen::VectorXd gain(sigma.size());
  for (Eigen::Index i = 0; i < sigma.size(); ++i) {
    gain(i) = lambda > 0.0 ? sigma(i) / (sigma(i) * sigma(i) + lambda) : 1.0 / sigma(i);
  }
  return v * gain.asDiagonal() * u.adjoint();
}

double RelativeDifference(const Eigen::MatrixXcd& a, const Eigen::MatrixXcd& reference) {
  return (a - reference).norm() / reference.norm();
}

TEST(SmallSvd, MatchesEigenJacobiSvdOnEveryShapeUpToConditionTenToTheTen) {
  RandomSystems rnd(91);
  for (const Shape shape : {Shape{12, 12}, Shape{18, 12}, Shape{7, 3}, Shape{6, 9}, Shape{1, 4},
                            Shape{4, 1}, Shape{1, 1}}) {
    for (const double condition : {1.0, 1e3, 1e6, 1e10}) {
      const std::string where = std::to_string(shape.rows) + "x" + std::to_string(shape.cols) +
                                " condition " + std::to_string(condition);
      const Eigen::MatrixXcd a = rnd.Conditioned(shape.rows, shape.cols, condition, 20.0);
      const Eigen::JacobiSVD<Eigen::MatrixXcd> ref(a, Eigen::ComputeThinU | Eigen::ComputeThinV);
      const SmallSvd svd = ThinSvd(a);
      const Eigen::Index r = std::min(shape.rows, shape.cols);
      ASSERT_EQ(svd.sigma.size(), r) << where;
      ASSERT_EQ(svd.u.rows(), shape.rows) << where;
      ASSERT_EQ(svd.u.cols(), r) << where;
      ASSERT_EQ(svd.v.rows(), shape.cols) << where;
      ASSERT_EQ(svd.v.cols(), r) << where;
      const double sigma_1 = ref.singularValues()(0);
      EXPECT_LE((svd.sigma - ref.singularValues()).cwiseAbs().maxCoeff(), 1e-13 * sigma_1) << where;
      for (Eigen::Index i = 1; i < r; ++i) EXPECT_GE(svd.sigma(i - 1), svd.sigma(i)) << where;
      const Eigen::MatrixXcd identity = Eigen::MatrixXcd::Identity(r, r);
      EXPECT_LE((svd.u.adjoint() * svd.u - identity).norm(), 1e-13) << where;
      EXPECT_LE((svd.v.adjoint() * svd.v - identity).norm(), 1e-13) << where;
      EXPECT_LE((svd.u * svd.sigma.asDiagonal() * svd.v.adjoint() - a).norm(), 1e-13 * a.norm())
          << where;
      const double lambda = 1e-6 * sigma_1 * sigma_1;  // cutoff 1e-3 sigma_1
      EXPECT_LE(RelativeDifference(
                    FilteredInverse(svd.u, svd.sigma, svd.v, lambda),
                    FilteredInverse(ref.matrixU(), ref.singularValues(), ref.matrixV(), lambda)),
                1e-11)
          << where;
      EXPECT_LE(RelativeDifference(
                    FilteredInverse(svd.u, svd.sigma, svd.v, 0.0),
                    FilteredInverse(ref.matrixU(), ref.singularValues(), ref.matrixV(), 0.0)),
                100.0 * kEps * condition)
          << where;
    }
  }
}

TEST(SmallSvd, AGramMatrixFromTheCallerOnlyChoosesTheStartingBasis) {
  // Even a Gram matrix off by 1e-6 (relative) leaves the result at Jacobi accuracy: the
  // rotations on A decide, the Gram matrix only saves sweeps. Wide matrices ignore it.
  RandomSystems rnd(96);
  for (const Shape shape : {Shape{12, 12}, Shape{18, 12}, Shape{6, 9}}) {
    for (const double condition : {10.0, 1e6}) {
      const Eigen::MatrixXcd a = rnd.Conditioned(shape.rows, shape.cols, condition, 20.0);
      const Eigen::MatrixXcd gram = a.adjoint() * a;
      const Eigen::MatrixXcd perturbed =
          gram + 1e-6 * gram.norm() * rnd.Matrix(gram.rows(), gram.cols());
      const Eigen::JacobiSVD<Eigen::MatrixXcd> ref(a, Eigen::ComputeThinU | Eigen::ComputeThinV);
      const double sigma_1 = ref.singularValues()(0);
      for (const Eigen::MatrixXcd* g : {&gram, &perturbed}) {
        const SmallSvd svd = ThinSvd(a, *g);
        const Eigen::Index r = svd.sigma.size();
        EXPECT_LE((svd.sigma - ref.singularValues()).cwiseAbs().maxCoeff(), 1e-13 * sigma_1);
        EXPECT_LE((svd.u.adjoint() * svd.u - Eigen::MatrixXcd::Identity(r, r)).norm(), 1e-13);
        EXPECT_LE((svd.v.adjoint() * svd.v - Eigen::MatrixXcd::Identity(r, r)).norm(), 1e-13);
        EXPECT_LE((svd.u * svd.sigma.asDiagonal() * svd.v.adjoint() - a).norm(), 1e-13 * a.norm());
      }
    }
  }
}

TEST(SmallSvd, KeepsTheSmallestSingularValueWhereTheGramMatrixLosesIt) {
  // Condition 1e6: the eigenvalues of A^H A carry an absolute error ~eps sigma_1^2, i.e. a
  // relative error up to ~eps * 1e12 on sigma_min^2. The Jacobi result must not inherit it.
  RandomSystems rnd(92);
  const double exact_min = 1e-6;  // Conditioned(): singular values from 1 down to 1/condition
  double worst_gram = 0.0;
  double worst_svd = 0.0;
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::MatrixXcd a = rnd.Conditioned(12, 12, 1e6);
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXcd> gram(a.adjoint() * a,
                                                               Eigen::EigenvaluesOnly);
    const double from_gram = std::sqrt(std::max(gram.eigenvalues()(0), 0.0));
    worst_gram = std::max(worst_gram, std::abs(from_gram - exact_min) / exact_min);
    worst_svd = std::max(worst_svd, std::abs(ThinSvd(a).sigma(11) - exact_min) / exact_min);
  }
  EXPECT_GT(worst_gram, 1e-5);  // what the Gram route loses (measured ~1e-4 .. 1e-3)
  EXPECT_LT(worst_svd, 1e-8);   // eps * 1e6, in the SVD and in the construction
}

TEST(SmallSvd, SingularValuesAloneAreBitIdenticalToTheThinSvds) {
  RandomSystems rnd(93);
  for (const Shape shape : {Shape{12, 12}, Shape{5, 8}, Shape{9, 2}}) {
    const Eigen::MatrixXcd a = rnd.Conditioned(shape.rows, shape.cols, 1e4, 5.0);
    const Eigen::VectorXd values = SingularValues(a);
    const SmallSvd svd = ThinSvd(a);
    ASSERT_EQ(values.size(), svd.sigma.size());
    for (Eigen::Index i = 0; i < values.size(); ++i) EXPECT_EQ(values(i), svd.sigma(i));
    const SmallSvd again = ThinSvd(a);  // deterministic: same input, same bits
    EXPECT_TRUE(again.u == svd.u && again.v == svd.v && again.sigma == svd.sigma);
  }
}

TEST(SmallSvd, RankDeficientAndZeroMatricesKeepOrthonormalBases) {
  RandomSystems rnd(94);
  Eigen::MatrixXcd zero_column = rnd.Matrix(6, 4);
  zero_column.col(2).setZero();  // a path with no FRF at this bin
  const Eigen::MatrixXcd rank_one = rnd.Vector(5) * rnd.Vector(3).adjoint();
  for (const Eigen::MatrixXcd& a :
       {zero_column, rank_one, Eigen::MatrixXcd(Eigen::MatrixXcd::Zero(4, 3)),
        Eigen::MatrixXcd(Eigen::MatrixXcd::Zero(2, 5))}) {
    const SmallSvd svd = ThinSvd(a);
    const Eigen::Index r = std::min(a.rows(), a.cols());
    const Eigen::MatrixXcd identity = Eigen::MatrixXcd::Identity(r, r);
    EXPECT_LE((svd.u.adjoint() * svd.u - identity).norm(), 1e-13);
    EXPECT_LE((svd.v.adjoint() * svd.v - identity).norm(), 1e-13);
    EXPECT_LE((svd.u * svd.sigma.asDiagonal() * svd.v.adjoint() - a).norm(),
              1e-13 * std::max(a.norm(), 1.0));
    const Eigen::VectorXd ref = Eigen::JacobiSVD<Eigen::MatrixXcd>(a).singularValues();
    const double sigma_1 = std::max(ref(0), 1.0);
    EXPECT_LE((svd.sigma - ref).cwiseAbs().maxCoeff(), 1e-13 * sigma_1);
  }
  EXPECT_EQ(ThinSvd(Eigen::MatrixXcd::Zero(3, 3)).sigma, Eigen::VectorXd::Zero(3));
}

TEST(SmallSvd, ExtremeMagnitudesNeitherOverflowNorUnderflow) {
  RandomSystems rnd(95);
  const Eigen::MatrixXcd a = rnd.Conditioned(8, 6, 1e3);
  const Eigen::VectorXd unit = ThinSvd(a).sigma;
  for (const double magnitude : {1e-150, 1e150}) {
    const Eigen::VectorXd scaled = ThinSvd(a * magnitude).sigma / magnitude;
    EXPECT_LE((scaled - unit).cwiseAbs().maxCoeff(), 1e-13 * unit(0)) << magnitude;
  }
}

TEST(SmallSvd, PowerOfTwoScaleBracketsTheLargestComponent) {
  Eigen::MatrixXcd a = Eigen::MatrixXcd::Zero(2, 2);
  EXPECT_EQ(PowerOfTwoScale(a), 0.0);
  a(1, 0) = std::complex<double>(0.3, -5.0);
  EXPECT_EQ(PowerOfTwoScale(a), 8.0);
  a(0, 1) = 8.0;
  EXPECT_EQ(PowerOfTwoScale(a), 16.0);
}

}  // namespace
}  // namespace gearpath
