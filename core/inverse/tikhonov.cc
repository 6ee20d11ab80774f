#include "core/inverse/tikhonov.h"

#include "core/inverse/spectral_filter.h"
#include "core/inverse/validation.h"

namespace gearpath {

Result<Eigen::VectorXcd> SolveTikhonov(const Eigen::MatrixXcd& h, const Eigen::VectorXcd& x,
                                       double lambda) {
  if (Status s = ValidateSystem(h, x); !s) return Error{s.error()};
  if (Status s = ValidateTikhonovParameter(lambda); !s) return Error{s.error()};
  const ScaledSvd svd = DecomposeScaled(h, Eigen::VectorXd::Ones(h.cols()));
  return ApplyFilteredInverse(svd, x, InverseMethod::kTikhonov, lambda, 1, 0.0);
}

}  // namespace gearpath
