#include "core/inverse/condition_number.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/inverse/small_svd.h"

namespace gearpath {

double ConditionFromSingularValues(const Eigen::VectorXd& sigma) noexcept {
  constexpr double kInfinity = std::numeric_limits<double>::infinity();
  if (sigma.size() == 0 || !(sigma(0) > 0.0)) return kInfinity;
  const double smallest = sigma(sigma.size() - 1);
  return smallest > 0.0 ? sigma(0) / smallest : kInfinity;
}

double ConditionFromGram(const Eigen::MatrixXcd& a, const Eigen::MatrixXcd& gram) {
  const Eigen::Index r = std::min(a.rows(), a.cols());
  const double scale = PowerOfTwoScale(gram);
  if (r > 0 && gram.rows() == a.cols() && gram.cols() == a.cols() && scale > 0.0) {
    // The eigenvalues of the real tridiagonal form; scaled by a power of two (exact) to keep
    // the QR steps away from overflow and underflow (small_svd.h says why not
    // SelfAdjointEigenSolver<MatrixXcd>).
    const Eigen::Tridiagonalization<Eigen::MatrixXcd> tridiagonal(gram * (1.0 / scale));
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen;
    eigen.computeFromTridiagonal(tridiagonal.diagonal(), tridiagonal.subDiagonal(),
                                 Eigen::EigenvaluesOnly);
    if (eigen.info() == Eigen::Success) {
      // Ascending; a wide A has cols - r further eigenvalues that are zero but for rounding.
      const Eigen::VectorXd& lambda = eigen.eigenvalues();
      const double lambda_max = lambda(lambda.size() - 1);
      const double lambda_min = lambda(lambda.size() - r);
      const double delta = static_cast<double>(a.rows() * r + a.cols()) *
                           std::numeric_limits<double>::epsilon() * lambda_max;
      if (lambda_max > 0.0 && lambda_min * kGramConditionTolerance >= delta) {
        return std::sqrt(lambda_max / lambda_min);
      }
    }
  }
  return ConditionFromSingularValues(SingularValues(a));
}

}  // namespace gearpath
