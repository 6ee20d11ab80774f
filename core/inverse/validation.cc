#include "core/inverse/validation.h"

#include <cmath>
#include <cstdio>
#include <string>

namespace gearpath {
namespace {

std::string Shape(const Eigen::MatrixXcd& h) {
  return std::to_string(h.rows()) + " x " + std::to_string(h.cols());
}

}  // namespace

std::string FormatNumber(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.6g", value);
  return buffer;
}

Status ValidateOperator(const Eigen::MatrixXcd& h, std::string_view name) {
  if (h.rows() == 0 || h.cols() == 0) {
    return Error{std::string(name) + ": FRF matrix is empty (" + Shape(h) +
                 "); need at least one response channel and one path"};
  }
  for (Eigen::Index j = 0; j < h.cols(); ++j) {
    for (Eigen::Index i = 0; i < h.rows(); ++i) {
      if (!std::isfinite(h(i, j).real()) || !std::isfinite(h(i, j).imag())) {
        return Error{std::string(name) + ": entry (" + std::to_string(i) + ", " +
                     std::to_string(j) + ") is not finite"};
      }
    }
  }
  return Status::Ok();
}

Status ValidateSystem(const Eigen::MatrixXcd& h, const Eigen::VectorXcd& x) {
  if (Status s = ValidateOperator(h, "H"); !s) return s;
  if (x.size() != h.rows()) {
    return Error{"x: has " + std::to_string(x.size()) + " responses but H has " +
                 std::to_string(h.rows()) + " rows (channels)"};
  }
  if (!x.allFinite()) return Error{"x: response vector contains a non-finite value"};
  return Status::Ok();
}

Status ValidateMwiParameters(double alpha, int iterations) {
  if (!std::isfinite(alpha) || !(alpha > 0.0)) {
    return Error{"alpha: MWI weighting factor must be finite and > 0 (Appendix B), got " +
                 FormatNumber(alpha)};
  }
  if (iterations < 1) {
    return Error{"iterations: MWI needs K >= 1 iterations, got " + std::to_string(iterations)};
  }
  return Status::Ok();
}

Status ValidateTikhonovParameter(double lambda) {
  if (!std::isfinite(lambda) || !(lambda > 0.0)) {
    return Error{"lambda: Tikhonov parameter must be finite and > 0, got " +
                 FormatNumber(lambda)};
  }
  return Status::Ok();
}

}  // namespace gearpath
