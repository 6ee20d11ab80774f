// Condition numbers sigma_max / sigma_min of the per-bin matrices, as reported in BinFigures.
#pragma once

#include <Eigen/Dense>

namespace gearpath {

// From singular values in descending order: +infinity when sigma_min (or sigma_max) is 0.
double ConditionFromSingularValues(const Eigen::VectorXd& sigma) noexcept;

}  // namespace gearpath
