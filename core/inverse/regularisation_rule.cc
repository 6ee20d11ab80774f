#include "core/inverse/regularisation_rule.h"

#include <cmath>
#include <limits>

namespace gearpath {
namespace {

constexpr int kGridPointsPerDecade = 10;
constexpr int kRefinementSteps = 60;

double Log10Cutoff(double sigma_max, double relative) { return std::log10(sigma_max * relative); }

}  // namespace

std::string_view ToString(RegularisationRule rule) noexcept {
  switch (rule) {
    case RegularisationRule::kFixed:
      return "fixed";
    case RegularisationRule::kNoiseFloor:
      return "noise_floor";
    case RegularisationRule::kDiscrepancy:
      return "discrepancy";
    case RegularisationRule::kGcv:
      return "gcv";
  }
  return "unknown";
}

std::string_view ToString(RuleOutcome outcome) noexcept {
  switch (outcome) {
    case RuleOutcome::kAsConfigured:
      return "as configured";
    case RuleOutcome::kNoParameter:
      return "no parameter (least squares)";
    case RuleOutcome::kGcvFellBackToNoiseFloor:
      return "gcv degenerate (channels <= rank), fell back to noise_floor";
    case RuleOutcome::kDiscrepancyBelowLeastSquaresResidual:
      return "discrepancy target below the least-squares residual, smallest parameter used";
    case RuleOutcome::kDiscrepancyAboveResponse:
      return "discrepancy target above the response norm, forces set to 0";
    case RuleOutcome::kZeroOperator:
      return "FRF matrix is zero at this bin, forces set to 0";
  }
  return "unknown";
}

double NoiseFloorParameter(InverseMethod method, double sigma_max, double relative_noise,
                           int iterations) noexcept {
  return ParameterForCutoff(method, relative_noise * sigma_max, iterations);
}

double ResidualNorm2(InverseMethod method, const Eigen::Ref<const Eigen::VectorXd>& sigma,
                     const Eigen::Ref<const Eigen::VectorXd>& beta2, double outside2,
                     double parameter, int iterations) noexcept {
  double sum = outside2;
  for (Eigen::Index i = 0; i < sigma.size(); ++i) {
    const double one_minus_phi =
        1.0 - FilterFactor(method, sigma(i), parameter, iterations, 0.0);
    sum += one_minus_phi * one_minus_phi * beta2(i);
  }
  return sum;
}

double GcvFunction(InverseMethod method, const Eigen::Ref<const Eigen::VectorXd>& sigma,
                   const Eigen::Ref<const Eigen::VectorXd>& beta2, double outside2,
                   Eigen::Index rows, double parameter, int iterations) noexcept {
  double trace = static_cast<double>(rows);
  for (Eigen::Index i = 0; i < sigma.size(); ++i) {
    trace -= FilterFactor(method, sigma(i), parameter, iterations, 0.0);
  }
  if (!(trace > 0.0)) return std::numeric_limits<double>::infinity();
  return ResidualNorm2(method, sigma, beta2, outside2, parameter, iterations) / (trace * trace);
}

double GcvParameter(InverseMethod method, const Eigen::Ref<const Eigen::VectorXd>& sigma,
                    const Eigen::Ref<const Eigen::VectorXd>& beta2, double outside2,
                    Eigen::Index rows, int iterations) noexcept {
  const double sigma_max = sigma.size() > 0 ? sigma(0) : 0.0;
  if (!(sigma_max > 0.0)) return std::numeric_limits<double>::infinity();
  // Search on t = log10(cutoff), where the filters are smooth and the range is uniform.
  const double lo = Log10Cutoff(sigma_max, kMinRelativeCutoff);
  const double hi = Log10Cutoff(sigma_max, kMaxRelativeCutoff);
  auto gcv_at = [&](double t) {
    return GcvFunction(method, sigma, beta2, outside2, rows,
                       ParameterForCutoff(method, std::pow(10.0, t), iterations), iterations);
  };
  const int points = static_cast<int>(std::lround((hi - lo) * kGridPointsPerDecade)) + 1;
  const double step = (hi - lo) / (points - 1);
  int best = 0;
  double best_value = std::numeric_limits<double>::infinity();
  for (int i = 0; i < points; ++i) {
    const double value = gcv_at(lo + step * i);
    if (value < best_value) {
      best_value = value;
      best = i;
    }
  }
  // Golden-section refinement inside the grid cell pair around the best grid point.
  double a = lo + step * (best > 0 ? best - 1 : 0);
  double b = lo + step * (best < points - 1 ? best + 1 : points - 1);
  const double g = 0.5 * (std::sqrt(5.0) - 1.0);
  double c = b - g * (b - a);
  double d = a + g * (b - a);
  double fc = gcv_at(c);
  double fd = gcv_at(d);
  for (int k = 0; k < kRefinementSteps; ++k) {
    if (fc <= fd) {
      b = d;
      d = c;
      fd = fc;
      c = b - g * (b - a);
      fc = gcv_at(c);
    } else {
      a = c;
      c = d;
      fc = fd;
      d = a + g * (b - a);
      fd = gcv_at(d);
    }
  }
  double t = 0.5 * (a + b);
  if (best_value < gcv_at(t)) t = lo + step * best;
  return ParameterForCutoff(method, std::pow(10.0, t), iterations);
}

ParameterChoice DiscrepancyParameter(InverseMethod method,
                                     const Eigen::Ref<const Eigen::VectorXd>& sigma,
                                     const Eigen::Ref<const Eigen::VectorXd>& beta2,
                                     double outside2, double target2, int iterations) noexcept {
  const double sigma_max = sigma.size() > 0 ? sigma(0) : 0.0;
  if (!(sigma_max > 0.0)) {
    return {std::numeric_limits<double>::infinity(), RuleOutcome::kZeroOperator};
  }
  const double total2 = outside2 + beta2.sum();
  if (target2 >= total2) {
    return {std::numeric_limits<double>::infinity(), RuleOutcome::kDiscrepancyAboveResponse};
  }
  double lo = Log10Cutoff(sigma_max, kMinRelativeCutoff);
  double hi = Log10Cutoff(sigma_max, kMaxRelativeCutoff);
  auto residual_at = [&](double t) {
    return ResidualNorm2(method, sigma, beta2, outside2,
                         ParameterForCutoff(method, std::pow(10.0, t), iterations), iterations);
  };
  if (residual_at(lo) >= target2) {
    return {ParameterForCutoff(method, std::pow(10.0, lo), iterations),
            RuleOutcome::kDiscrepancyBelowLeastSquaresResidual};
  }
  if (residual_at(hi) <= target2) {
    return {ParameterForCutoff(method, std::pow(10.0, hi), iterations),
            RuleOutcome::kAsConfigured};
  }
  // Residual is monotone increasing in the parameter: bisection to double precision in t.
  for (int k = 0; k < 100 && hi - lo > 1e-13; ++k) {
    const double mid = 0.5 * (lo + hi);
    if (residual_at(mid) < target2) {
      lo = mid;
    } else {
      hi = mid;
    }
  }
  return {ParameterForCutoff(method, std::pow(10.0, 0.5 * (lo + hi)), iterations),
          RuleOutcome::kAsConfigured};
}

}  // namespace gearpath
