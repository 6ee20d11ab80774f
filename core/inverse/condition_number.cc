#include "core/inverse/condition_number.h"

#include <limits>

namespace gearpath {

double ConditionFromSingularValues(const Eigen::VectorXd& sigma) noexcept {
  constexpr double kInfinity = std::numeric_limits<double>::infinity();
  if (sigma.size() == 0 || !(sigma(0) > 0.0)) return kInfinity;
  const double smallest = sigma(sigma.size() - 1);
  return smallest > 0.0 ? sigma(0) / smallest : kInfinity;
}

}  // namespace gearpath
