// Thin SVD of one small dense complex matrix (a per-bin FRF operator: a few to a few tens of rows
// and columns), by one-sided (Hestenes) Jacobi preconditioned with the eigenvectors of the Gram
// matrix.
//
// Why not Eigen::JacobiSVD: its two-sided complex 2 x 2 steps cost about 200 us on a 12 x 12
// bin, and the precompute of an 8001-bin FRF set did two of them per bin (issue 9).
//
// Why not the eigen-decomposition of A^H A alone: its small eigenvalues carry an absolute error
// of about eps sigma_1^2, i.e. it squares the condition number (relative error eps kappa^2 on
// sigma_min instead of eps kappa).
//
// What is done: the Gram eigenvectors V0 are only the starting basis. The columns of A V0 are
// then already nearly orthogonal, and one-sided Jacobi rotates pairs of them until every pair is
// orthogonal to sqrt(rows) * eps relative to the product of their norms; sigma_i is the norm of
// column i and u_i that column normalised. The result is the Jacobi SVD of A itself (absolute
// error ~ eps sigma_1 on every sigma_i, as for any backward-stable SVD), reached in one or two
// sweeps instead of six to eight: the preconditioner changes the work, not the accuracy.
//
// Inputs are scaled by a power of two (exact) so that the largest entry is in [0.5, 1); a
// singular value below ~1e-150 of that, far under the eps sigma_1 any SVD resolves, comes out 0.
// Configuration-time code: allocates. Deterministic: same input, same bits, whatever thread.
#pragma once

#include <Eigen/Dense>

namespace gearpath {

// A = U diag(sigma) V^H with r = min(rows, cols): u is rows x r, v is cols x r, both with
// orthonormal columns (columns for sigma_i = 0 complete the basis), sigma descending, >= 0.
struct SmallSvd {
  Eigen::MatrixXcd u;
  Eigen::VectorXd sigma;
  Eigen::MatrixXcd v;
};

SmallSvd ThinSvd(const Eigen::MatrixXcd& a);

// The same, for a caller that already has gram = A^H A: it only chooses the starting basis, so
// its rounding does not matter. Used when rows >= cols (a wide A needs A A^H: formed here).
SmallSvd ThinSvd(const Eigen::MatrixXcd& a, const Eigen::MatrixXcd& gram);

// The r singular values only (descending): skips accumulating V and normalising U.
Eigen::VectorXd SingularValues(const Eigen::MatrixXcd& a);

// A^H A.
Eigen::MatrixXcd GramMatrix(const Eigen::MatrixXcd& a);

// 2^e with 2^(e-1) <= max(|Re a_ij|, |Im a_ij|) < 2^e, or 0 for a zero (or empty) matrix.
// Dividing by it is exact and brings the largest entry into [0.5, 1), away from overflow and
// underflow in Gram matrices and squared norms.
double PowerOfTwoScale(const Eigen::MatrixXcd& a);

}  // namespace gearpath
