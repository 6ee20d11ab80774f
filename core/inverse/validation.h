// Argument checks shared by the inverse solvers; messages name the argument and say why.
#pragma once

#include <Eigen/Dense>
#include <string>
#include <string_view>

#include "core/common/result.h"

namespace gearpath {

// "%.6g" of value, for messages (std::to_string prints 1e-9 as 0.000000).
std::string FormatNumber(double value);

// Non-empty and finite; `name` is used in the message.
Status ValidateOperator(const Eigen::MatrixXcd& h, std::string_view name);
// H valid and x finite with as many entries as H has rows.
Status ValidateSystem(const Eigen::MatrixXcd& h, const Eigen::VectorXcd& x);
// alpha finite and > 0, K >= 1.
Status ValidateMwiParameters(double alpha, int iterations);
// lambda finite and > 0.
Status ValidateTikhonovParameter(double lambda);

}  // namespace gearpath
