// Test helpers: seeded random complex systems with prescribed singular values.
#pragma once

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <complex>
#include <random>

#include "core/common/frf_matrix.h"

namespace gearpath::testing {

class RandomSystems {
 public:
  explicit RandomSystems(unsigned seed) : engine_(seed) {}

  Eigen::MatrixXcd Matrix(Eigen::Index rows, Eigen::Index cols) {
    Eigen::MatrixXcd m(rows, cols);
    for (Eigen::Index j = 0; j < cols; ++j) {
      for (Eigen::Index i = 0; i < rows; ++i) m(i, j) = {normal_(engine_), normal_(engine_)};
    }
    return m;
  }

  Eigen::VectorXcd Vector(Eigen::Index size) { return Matrix(size, 1).col(0); }

  // Random unitary (orthonormal columns): Q of a QR of a Gaussian matrix.
  Eigen::MatrixXcd Orthonormal(Eigen::Index rows, Eigen::Index cols) {
    Eigen::HouseholderQR<Eigen::MatrixXcd> qr(Matrix(rows, cols));
    return qr.householderQ() * Eigen::MatrixXcd::Identity(rows, cols);
  }

  // rows x cols with singular values geometrically spaced from 1 down to 1/condition, and
  // columns scaled by `column_spread`^(j/(n-1)) (unequal path magnitudes, which MWI weights).
  Eigen::MatrixXcd Conditioned(Eigen::Index rows, Eigen::Index cols, double condition,
                               double column_spread = 1.0) {
    const Eigen::Index r = std::min(rows, cols);
    Eigen::VectorXd s(r);
    for (Eigen::Index i = 0; i < r; ++i) {
      s(i) = r > 1 ? std::pow(condition, -static_cast<double>(i) / static_cast<double>(r - 1))
                   : 1.0;
    }
    Eigen::MatrixXcd h = Orthonormal(rows, r) * s.asDiagonal() * Orthonormal(cols, r).adjoint();
    for (Eigen::Index j = 0; j < cols; ++j) {
      h.col(j) *= cols > 1 ? std::pow(column_spread, static_cast<double>(j) /
                                                         static_cast<double>(cols - 1))
                           : 1.0;
    }
    return h;
  }

 private:
  std::mt19937_64 engine_;
  std::normal_distribution<double> normal_{0.0, 1.0};
};

inline double RelativeError(const Eigen::VectorXcd& estimate, const Eigen::VectorXcd& truth) {
  return (estimate - truth).norm() / truth.norm();
}

}  // namespace gearpath::testing
