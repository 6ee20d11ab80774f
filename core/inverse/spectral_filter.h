// Spectral filtering: least squares, Tikhonov and MWI as one filtered SVD.
//
// Every solver in core/inverse computes, per frequency bin, F = D V diag(phi_i / sigma_i) U^H x,
// where B = H D = U diag(sigma) V^H is the thin SVD of the operator actually inverted and
// D = diag(column_scale) is a positive column scaling (D = W^{1/2} for MWI, seed Eq. 40;
// D = I for Tikhonov and least squares). Only the filter factors phi_i differ:
//   least squares (minimum norm): phi = 1 if sigma > cutoff, else 0;
//   Tikhonov (seed Eqs. 27-28):   phi = sigma^2 / (sigma^2 + lambda);
//   MWI, K steps from f_0 = 0 (seed Eqs. 40-43): phi = 1 - (alpha / (sigma^2 + alpha))^K.
// The derivation of the MWI form is in mwi.h. Working from the SVD of B never solves with
// H^H H, whose condition number is the square of H's (the SVD forms B^H B only to choose its
// starting basis; the singular values and vectors come from B itself, small_svd.h).
#pragma once

#include <Eigen/Dense>
#include <string_view>

namespace gearpath {

enum class InverseMethod { kMwi, kTikhonov, kLeastSquares };

std::string_view ToString(InverseMethod method) noexcept;

// Thin SVD of B = H diag(column_scale): u is m x r, sigma has r entries (descending), v is
// n x r, r = min(m, n).
struct ScaledSvd {
  Eigen::MatrixXcd u;
  Eigen::VectorXd sigma;
  Eigen::MatrixXcd v;
  Eigen::VectorXd column_scale;
};

// Decomposes H diag(column_scale). Allocates; configuration time only. A caller that has
// H^H H already (MWI forms it for its weights) passes it as gram_of_h: the SVD then does not
// form the Gram matrix of B again.
ScaledSvd DecomposeScaled(const Eigen::MatrixXcd& h, const Eigen::VectorXd& column_scale,
                          const Eigen::MatrixXcd* gram_of_h = nullptr);

// The default rank cutoff of least squares: sigma_max * max(m, n) * machine epsilon, the
// convention of LAPACK's xGELSD callers, NumPy's pinv/lstsq and MATLAB's rank.
double DefaultRankCutoff(double sigma_max, Eigen::Index rows, Eigen::Index cols) noexcept;

// phi(sigma) for `method`. `parameter` is lambda (Tikhonov) or alpha (MWI) and must be > 0;
// +infinity gives phi = 0. `iterations` is K (MWI only). `rank_cutoff` is the absolute
// singular-value cutoff (least squares only). phi = 0 for sigma = 0 whatever the method.
double FilterFactor(InverseMethod method, double sigma, double parameter, int iterations,
                    double rank_cutoff) noexcept;

// The regularisation parameter whose filter factor is exactly 1/2 at singular value `cutoff`:
// lambda = cutoff^2 for Tikhonov, alpha = cutoff^2 / (2^{1/K} - 1) for MWI (for K = 1 both are
// cutoff^2). Parameterising by the cutoff makes one search range serve every method and K.
double ParameterForCutoff(InverseMethod method, double cutoff, int iterations) noexcept;

}  // namespace gearpath

namespace gearpath {

// F = D V diag(phi_i / sigma_i) U^H x for one response vector. Allocates (reference/free
// functions); the per-block path is IdentificationOperator.
Eigen::VectorXcd ApplyFilteredInverse(const ScaledSvd& svd, const Eigen::VectorXcd& x,
                                      InverseMethod method, double parameter, int iterations,
                                      double rank_cutoff);

}  // namespace gearpath
