// Minimum-norm least squares for one frequency bin, via the SVD of H.
//
// F = V diag(1/sigma_i for sigma_i > cutoff, else 0) U^H x: the least-squares solution of
// x = H F with the smallest ||F||_2 among all least-squares solutions. Works for any shape:
// overdetermined (m > n, full column rank: the usual (H^H H)^{-1} H^H x), square, and
// underdetermined (m < n, full row rank: H^H (H H^H)^{-1} x). Rank tolerance: singular values
// <= cutoff are treated as zero. The default cutoff (relative_tolerance <= 0) is
// sigma_max * max(m, n) * eps, the LAPACK/NumPy/MATLAB convention: anything smaller is below
// the rounding error of computing the SVD itself. A relative_tolerance > 0 gives
// cutoff = relative_tolerance * sigma_max.
#pragma once

#include <Eigen/Dense>

#include "core/common/result.h"

namespace gearpath {

Result<Eigen::VectorXcd> SolveLeastSquares(const Eigen::MatrixXcd& h, const Eigen::VectorXcd& x,
                                           double relative_tolerance = 0.0);

// The absolute singular-value cutoff used for a given sigma_max and shape (see above).
double LeastSquaresCutoff(double sigma_max, Eigen::Index rows, Eigen::Index cols,
                          double relative_tolerance) noexcept;

}  // namespace gearpath
