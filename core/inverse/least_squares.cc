#include "core/inverse/least_squares.h"

#include <cmath>

#include "core/inverse/spectral_filter.h"
#include "core/inverse/validation.h"

namespace gearpath {

double LeastSquaresCutoff(double sigma_max, Eigen::Index rows, Eigen::Index cols,
                          double relative_tolerance) noexcept {
  if (relative_tolerance > 0.0) return relative_tolerance * sigma_max;
  return DefaultRankCutoff(sigma_max, rows, cols);
}

Result<Eigen::VectorXcd> SolveLeastSquares(const Eigen::MatrixXcd& h, const Eigen::VectorXcd& x,
                                           double relative_tolerance) {
  if (Status s = ValidateSystem(h, x); !s) return Error{s.error()};
  if (!std::isfinite(relative_tolerance) || relative_tolerance >= 1.0) {
    return Error{"relative_tolerance: rank tolerance must be finite and < 1 (<= 0 selects the "
                 "default max(m, n) * eps), got " + FormatNumber(relative_tolerance)};
  }
  const ScaledSvd svd = DecomposeScaled(h, Eigen::VectorXd::Ones(h.cols()));
  const double sigma_max = svd.sigma.size() > 0 ? svd.sigma(0) : 0.0;
  const double cutoff = LeastSquaresCutoff(sigma_max, h.rows(), h.cols(), relative_tolerance);
  return ApplyFilteredInverse(svd, x, InverseMethod::kLeastSquares, 0.0, 1, cutoff);
}

}  // namespace gearpath
