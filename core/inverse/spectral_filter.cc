#include "core/inverse/spectral_filter.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <utility>

#include "core/inverse/small_svd.h"

namespace gearpath {

std::string_view ToString(InverseMethod method) noexcept {
  switch (method) {
    case InverseMethod::kMwi:
      return "mwi";
    case InverseMethod::kTikhonov:
      return "tikhonov";
    case InverseMethod::kLeastSquares:
      return "least_squares";
  }
  return "unknown";
}

ScaledSvd DecomposeScaled(const Eigen::MatrixXcd& h, const Eigen::VectorXd& column_scale,
                          const Eigen::MatrixXcd* gram_of_h) {
  // A Jacobi SVD (small_svd.h): the accuracy of Eigen::JacobiSVD on the small singular values
  // that regularisation is all about, at a fraction of its cost on the per-bin sizes.
  const Eigen::MatrixXcd b = h * column_scale.asDiagonal();
  // B^H B = D (H^H H) D.
  SmallSvd svd = gram_of_h == nullptr
                     ? ThinSvd(b)
                     : ThinSvd(b, column_scale.asDiagonal() * *gram_of_h *
                                      column_scale.asDiagonal());
  return ScaledSvd{std::move(svd.u), std::move(svd.sigma), std::move(svd.v), column_scale};
}

double DefaultRankCutoff(double sigma_max, Eigen::Index rows, Eigen::Index cols) noexcept {
  return sigma_max * static_cast<double>(std::max(rows, cols)) *
         std::numeric_limits<double>::epsilon();
}

double FilterFactor(InverseMethod method, double sigma, double parameter, int iterations,
                    double rank_cutoff) noexcept {
  if (!(sigma > 0.0)) return 0.0;
  switch (method) {
    case InverseMethod::kLeastSquares:
      return sigma > rank_cutoff ? 1.0 : 0.0;
    case InverseMethod::kTikhonov: {
      if (std::isinf(parameter)) return 0.0;
      const double s2 = sigma * sigma;
      return s2 / (s2 + parameter);
    }
    case InverseMethod::kMwi: {
      if (std::isinf(parameter)) return 0.0;
      // 1 - (alpha / (s^2 + alpha))^K = -expm1(K log1p(-s^2 / (s^2 + alpha))): accurate both
      // when phi is tiny (s^2 << alpha) and when it is close to 1.
      const double s2 = sigma * sigma;
      const double t = s2 / (s2 + parameter);
      return -std::expm1(static_cast<double>(iterations) * std::log1p(-t));
    }
  }
  return 0.0;
}

double ParameterForCutoff(InverseMethod method, double cutoff, int iterations) noexcept {
  const double c2 = cutoff * cutoff;
  if (method == InverseMethod::kMwi) {
    return c2 / std::expm1(std::log(2.0) / static_cast<double>(iterations));
  }
  return c2;
}

}  // namespace gearpath

namespace gearpath {

Eigen::VectorXcd ApplyFilteredInverse(const ScaledSvd& svd, const Eigen::VectorXcd& x,
                                      InverseMethod method, double parameter, int iterations,
                                      double rank_cutoff) {
  Eigen::VectorXcd c = svd.u.adjoint() * x;
  for (Eigen::Index i = 0; i < c.size(); ++i) {
    const double sigma = svd.sigma(i);
    const double phi = FilterFactor(method, sigma, parameter, iterations, rank_cutoff);
    c(i) = phi > 0.0 ? c(i) * (phi / sigma) : std::complex<double>(0.0, 0.0);
  }
  return svd.column_scale.asDiagonal() * (svd.v * c);
}

}  // namespace gearpath
