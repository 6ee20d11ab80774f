// Condition numbers sigma_max / sigma_min of the per-bin matrices, as reported in BinFigures.
#pragma once

#include <Eigen/Dense>

namespace gearpath {

// From singular values in descending order: +infinity when sigma_min (or sigma_max) is 0.
double ConditionFromSingularValues(const Eigen::VectorXd& sigma) noexcept;

// The largest relative error ConditionFromGram allows itself before it falls back to the SVD.
inline constexpr double kGramConditionTolerance = 1e-8;

// Condition number of A (rows x cols, any shape) given gram = A^H A, as computed from A.
//
// The cheap way, the eigenvalues of the Gram matrix, squares the condition number: each
// eigenvalue carries an absolute error of at most delta = (rows * r + cols) * eps * lambda_max
// (forming A^H A, then a backward-stable eigen-solver; r = min(rows, cols)), so lambda_min is
// only trustworthy when it is far above delta. It is used when lambda_min >= delta /
// kGramConditionTolerance: then the relative error of lambda_min is at most about
// kGramConditionTolerance and that of the condition number about half that (for 12 x 12: up to
// a condition number of about 540). Otherwise the singular values of A itself (small_svd.h) are
// used, whose error is that of a Jacobi SVD. Allocates; configuration time only.
double ConditionFromGram(const Eigen::MatrixXcd& a, const Eigen::MatrixXcd& gram);

}  // namespace gearpath
