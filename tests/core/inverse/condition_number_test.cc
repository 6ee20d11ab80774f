#include "core/inverse/condition_number.h"

#include <gtest/gtest.h>

#include <limits>

namespace gearpath {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

TEST(ConditionNumber, SingularValuesWithAZeroAreInfinite) {
  EXPECT_EQ(ConditionFromSingularValues(Eigen::VectorXd()), kInfinity);
  EXPECT_EQ(ConditionFromSingularValues(Eigen::Vector3d(2.0, 1.0, 0.0)), kInfinity);
  EXPECT_EQ(ConditionFromSingularValues(Eigen::Vector3d(2.0, 1.0, 0.5)), 4.0);
}

}  // namespace
}  // namespace gearpath
