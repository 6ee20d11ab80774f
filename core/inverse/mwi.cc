#include "core/inverse/mwi.h"

#include <string>

#include "core/inverse/spectral_filter.h"
#include "core/inverse/validation.h"

namespace gearpath {

Result<Eigen::VectorXd> MwiWeights(const Eigen::MatrixXcd& h) {
  if (Status s = ValidateOperator(h, "H"); !s) return Error{s.error()};
  const Eigen::MatrixXcd a = h.adjoint() * h;
  Eigen::VectorXd w(a.rows());
  for (Eigen::Index i = 0; i < a.rows(); ++i) {
    const double norm = a.row(i).norm();
    if (!(norm > 0.0)) {
      return Error{"H: column " + std::to_string(i) +
                   " is zero, so row " + std::to_string(i) +
                   " of A = H^H H is zero and the MWI weight 1/||row(A)|| (Eq. 40) is undefined"};
    }
    w(i) = 1.0 / norm;
  }
  return w;
}

Result<Eigen::VectorXcd> SolveMwiByIteration(const Eigen::MatrixXcd& h, const Eigen::VectorXcd& x,
                                              double alpha, int iterations) {
  if (Status s = ValidateSystem(h, x); !s) return Error{s.error()};
  if (Status s = ValidateMwiParameters(alpha, iterations); !s) return Error{s.error()};
  Result<Eigen::VectorXd> w = MwiWeights(h);
  if (!w) return Error{w.error()};
  const Eigen::Index n = h.cols();
  const Eigen::MatrixXcd a = h.adjoint() * h;
  const Eigen::MatrixXcd m = a * w->asDiagonal() + alpha * Eigen::MatrixXcd::Identity(n, n);
  const Eigen::PartialPivLU<Eigen::MatrixXcd> lu(m);
  const Eigen::VectorXcd y = h.adjoint() * x;
  Eigen::VectorXcd f = Eigen::VectorXcd::Zero(n);
  Eigen::VectorXcd rhs(n);
  for (int k = 0; k < iterations; ++k) {
    rhs = y + alpha * f;  // separate vector: the LU solve must not read f while writing it
    f = lu.solve(rhs);
  }
  return Eigen::VectorXcd(w->asDiagonal() * f);
}

Result<Eigen::VectorXcd> SolveMwi(const Eigen::MatrixXcd& h, const Eigen::VectorXcd& x,
                                  double alpha, int iterations) {
  if (Status s = ValidateSystem(h, x); !s) return Error{s.error()};
  if (Status s = ValidateMwiParameters(alpha, iterations); !s) return Error{s.error()};
  Result<Eigen::VectorXd> w = MwiWeights(h);
  if (!w) return Error{w.error()};
  const ScaledSvd svd = DecomposeScaled(h, w->cwiseSqrt());
  return ApplyFilteredInverse(svd, x, InverseMethod::kMwi, alpha, iterations, 0.0);
}

}  // namespace gearpath
