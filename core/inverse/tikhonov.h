// Tikhonov regularisation for one frequency bin, seed Eqs. 27-28, through the SVD of H.
//
// (H^H H + lambda I) F = H^H x has the solution F = V diag(sigma_i / (sigma_i^2 + lambda)) U^H x
// with H = U S V^H (thin). The SVD route never forms H^H H. lambda > 0; lambda -> 0 gives
// the minimum-norm least-squares solution, lambda -> infinity gives 0. The seed's baseline
// for MWI; choose lambda with a RegularisationRule (regularisation_rule.h).
#pragma once

#include <Eigen/Dense>

#include "core/common/result.h"

namespace gearpath {

Result<Eigen::VectorXcd> SolveTikhonov(const Eigen::MatrixXcd& h, const Eigen::VectorXcd& x,
                                       double lambda);

}  // namespace gearpath
