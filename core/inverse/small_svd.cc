#include "core/inverse/small_svd.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <numeric>
#include <utility>
#include <vector>

namespace gearpath {
namespace {

using Complex = std::complex<double>;

// After preconditioning the sweeps needed are one or two (plus the sweep that finds nothing left
// to rotate); unpreconditioned Jacobi needs about eight at these sizes. The cap only bounds the
// work on an input the rotations cannot improve any further.
constexpr int kMaxSweeps = 30;

// Beyond this the rotation angle is t = 1 / (2 zeta) to full precision, and zeta^2 would overflow.
constexpr double kLargeZeta = 1e100;

// Columns i and j of m become cs * c_i - sn * (phase * c_j) and sn * c_i + cs * (phase * c_j).
// Written in real arithmetic: std::complex products carry a NaN-recovery branch (__muldc3)
// that showed in the profile, and nothing here can be NaN (the FRFs are validated finite).
void RotateColumns(Eigen::MatrixXcd& m, Eigen::Index i, Eigen::Index j, double cs, double sn,
                   Complex phase) {
  const double pr = phase.real();
  const double pi = phase.imag();
  Complex* ci = m.col(i).data();
  Complex* cj = m.col(j).data();
  for (Eigen::Index k = 0; k < m.rows(); ++k) {
    const double xr = ci[k].real();
    const double xi = ci[k].imag();
    const double yr = pr * cj[k].real() - pi * cj[k].imag();
    const double yi = pr * cj[k].imag() + pi * cj[k].real();
    ci[k] = Complex(cs * xr - sn * yr, cs * xi - sn * yi);
    cj[k] = Complex(sn * xr + cs * yr, sn * xi + cs * yi);
  }
}

// One-sided Jacobi on the columns of w (rows >= cols): rotates pairs until each pair is
// orthogonal to `tolerance` relative to the product of their norms. Every rotation is applied
// to v too when v is non-null, so w_in v_in^{-1} = w_out v_out^{-1}.
void OrthogonaliseColumns(Eigen::MatrixXcd& w, Eigen::MatrixXcd* v) {
  const Eigen::Index n = w.cols();
  const double tolerance =
      std::sqrt(static_cast<double>(w.rows())) * std::numeric_limits<double>::epsilon();
  Eigen::VectorXd norm2(n);
  for (int sweep = 0; sweep < kMaxSweeps; ++sweep) {
    for (Eigen::Index i = 0; i < n; ++i) norm2(i) = w.col(i).squaredNorm();
    bool rotated = false;
    for (Eigen::Index i = 0; i + 1 < n; ++i) {
      for (Eigen::Index j = i + 1; j < n; ++j) {
        const double scale = std::sqrt(norm2(i)) * std::sqrt(norm2(j));
        if (!(scale > 0.0)) continue;
        const Complex g = w.col(i).dot(w.col(j));  // c_i^H c_j
        // |g| without hypot (its cost showed in the profile); hypot only where |g|^2 underflows.
        const double abs_g2 = std::norm(g);
        const double abs_g =
            abs_g2 >= std::numeric_limits<double>::min() ? std::sqrt(abs_g2) : std::abs(g);
        if (!(abs_g > tolerance * scale)) continue;
        // Multiplying c_j by the unit phase conj(g)/|g| makes the pair's Gram entry real; then
        // the real symmetric 2 x 2 Jacobi rotation (the smaller angle) zeroes it.
        const Complex phase(g.real() / abs_g, -g.imag() / abs_g);  // conj(g) / |g|
        const double zeta = (norm2(j) - norm2(i)) / (2.0 * abs_g);
        const double t =
            std::abs(zeta) > kLargeZeta
                ? 0.5 / zeta
                : std::copysign(1.0, zeta) / (std::abs(zeta) + std::sqrt(1.0 + zeta * zeta));
        const double cs = 1.0 / std::sqrt(1.0 + t * t);
        const double sn = cs * t;
        RotateColumns(w, i, j, cs, sn, phase);
        if (v != nullptr) RotateColumns(*v, i, j, cs, sn, phase);
        // Recomputed, not updated by formula: the shrinking column would lose its accuracy to
        // cancellation, and after preconditioning rotations are few.
        norm2(i) = w.col(i).squaredNorm();
        norm2(j) = w.col(j).squaredNorm();
        rotated = true;
      }
    }
    if (!rotated) return;
  }
}

// Eigenvectors of gram = b^H b, strongest first (the descending order of the result), or the
// identity if the eigen-solver fails (which would only cost sweeps). Built from Eigen's public
// pieces rather than SelfAdjointEigenSolver<MatrixXcd>: that one rescales its input (a hypot
// and a complex division per entry) and accumulates its rotations in complex arithmetic, about
// a third of its cost at these sizes; here b is already scaled and the rotations of the real
// tridiagonal problem are accumulated in a real matrix.
Eigen::MatrixXcd GramEigenvectors(const Eigen::MatrixXcd& gram) {
  const Eigen::Tridiagonalization<Eigen::MatrixXcd> tridiagonal(gram);
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> real_problem;
  real_problem.computeFromTridiagonal(tridiagonal.diagonal(), tridiagonal.subDiagonal());
  if (real_problem.info() != Eigen::Success) {
    return Eigen::MatrixXcd::Identity(gram.cols(), gram.cols());
  }
  // Q Z with the reflectors applied to Z directly (Q itself is never formed).
  Eigen::MatrixXcd vectors = real_problem.eigenvectors().rowwise().reverse().cast<Complex>();
  vectors.applyOnTheLeft(tridiagonal.matrixQ());
  return vectors;
}

// The tall case (rows >= cols, cols >= 1) of both entry points. v is null for values only;
// gram is A^H A or null. Returns the unsorted column norms; w holds U diag(sigma) in the same
// (unsorted) order.
Eigen::VectorXd JacobiOnTall(const Eigen::MatrixXcd& a, double scale, Eigen::MatrixXcd& w,
                             Eigen::MatrixXcd* v, const Eigen::MatrixXcd* gram) {
  const double inverse = 1.0 / scale;  // exact: scale is a power of two
  const Eigen::MatrixXcd b = a * inverse;
  Eigen::MatrixXcd start = GramEigenvectors(
      gram != nullptr ? Eigen::MatrixXcd(*gram * (inverse * inverse)) : GramMatrix(b));
  w = b * start;
  if (v != nullptr) *v = std::move(start);
  OrthogonaliseColumns(w, v);
  Eigen::VectorXd norms(w.cols());
  for (Eigen::Index i = 0; i < w.cols(); ++i) norms(i) = w.col(i).norm() * scale;
  return norms;
}

std::vector<Eigen::Index> DescendingOrder(const Eigen::VectorXd& values) {
  std::vector<Eigen::Index> order(static_cast<std::size_t>(values.size()));
  std::iota(order.begin(), order.end(), Eigen::Index{0});
  std::stable_sort(order.begin(), order.end(),
                   [&](Eigen::Index x, Eigen::Index y) { return values(x) > values(y); });
  return order;
}

// Columns [first, cols) of u, whose singular value is 0, become an orthonormal completion of
// columns [0, first): each is the projection of a unit vector e_k, the one the projection keeps
// most of, orthogonalised twice.
void CompleteOrthonormalColumns(Eigen::MatrixXcd& u, Eigen::Index first) {
  for (Eigen::Index c = first; c < u.cols(); ++c) {
    const auto basis = u.leftCols(c);
    Eigen::MatrixXcd projector = Eigen::MatrixXcd::Identity(u.rows(), u.rows());
    projector.noalias() -= basis * basis.adjoint();
    Eigen::Index best = 0;
    projector.colwise().squaredNorm().maxCoeff(&best);
    Eigen::VectorXcd candidate = projector.col(best);
    candidate.noalias() -= basis * (basis.adjoint() * candidate);
    u.col(c) = candidate.normalized();
  }
}

SmallSvd TallThinSvd(const Eigen::MatrixXcd& a, const Eigen::MatrixXcd* gram) {
  const Eigen::Index n = a.cols();
  SmallSvd out;
  const double scale = PowerOfTwoScale(a);
  if (scale == 0.0) {
    out.sigma = Eigen::VectorXd::Zero(n);
    out.u = Eigen::MatrixXcd::Identity(a.rows(), n);
    out.v = Eigen::MatrixXcd::Identity(n, n);
    return out;
  }
  Eigen::MatrixXcd w;
  Eigen::MatrixXcd v;
  const Eigen::VectorXd norms = JacobiOnTall(a, scale, w, &v, gram);
  const std::vector<Eigen::Index> order = DescendingOrder(norms);
  out.sigma.resize(n);
  out.u.resize(a.rows(), n);
  out.v.resize(n, n);
  Eigen::Index nonzero = 0;
  for (Eigen::Index k = 0; k < n; ++k) {
    const Eigen::Index from = order[static_cast<std::size_t>(k)];
    out.sigma(k) = norms(from);
    out.v.col(k) = v.col(from);
    if (norms(from) > 0.0) {
      out.u.col(k) = w.col(from).normalized();
      ++nonzero;
    }
  }
  CompleteOrthonormalColumns(out.u, nonzero);
  return out;
}

}  // namespace

Eigen::MatrixXcd GramMatrix(const Eigen::MatrixXcd& a) {
  // Each entry a dot product of two contiguous columns: at these sizes about a fifth cheaper
  // than Eigen's blocked product, which packs the conjugated transpose first.
  return a.adjoint().lazyProduct(a);
}

double PowerOfTwoScale(const Eigen::MatrixXcd& a) {
  if (a.size() == 0) return 0.0;
  const double largest = std::max(a.real().cwiseAbs().maxCoeff(), a.imag().cwiseAbs().maxCoeff());
  if (!(largest > 0.0)) return 0.0;
  int exponent = 0;
  std::frexp(largest, &exponent);
  return std::ldexp(1.0, exponent);
}

SmallSvd ThinSvd(const Eigen::MatrixXcd& a) {
  if (a.size() == 0) {
    const Eigen::Index r = std::min(a.rows(), a.cols());
    return SmallSvd{Eigen::MatrixXcd(a.rows(), r), Eigen::VectorXd(r),
                    Eigen::MatrixXcd(a.cols(), r)};
  }
  if (a.rows() >= a.cols()) return TallThinSvd(a, nullptr);
  // A^H = U' S V'^H  =>  A = V' S U'^H.
  SmallSvd transposed = TallThinSvd(a.adjoint(), nullptr);
  std::swap(transposed.u, transposed.v);
  return transposed;
}

SmallSvd ThinSvd(const Eigen::MatrixXcd& a, const Eigen::MatrixXcd& gram) {
  if (a.size() == 0 || a.rows() < a.cols() || gram.rows() != a.cols() || gram.cols() != a.cols()) {
    return ThinSvd(a);
  }
  return TallThinSvd(a, &gram);
}

Eigen::VectorXd SingularValues(const Eigen::MatrixXcd& a) {
  if (a.size() == 0) return Eigen::VectorXd(std::min(a.rows(), a.cols()));
  const Eigen::MatrixXcd tall = a.rows() >= a.cols() ? a : Eigen::MatrixXcd(a.adjoint());
  const double scale = PowerOfTwoScale(tall);
  if (scale == 0.0) return Eigen::VectorXd::Zero(tall.cols());
  Eigen::MatrixXcd w;
  const Eigen::VectorXd norms = JacobiOnTall(tall, scale, w, nullptr, nullptr);
  const std::vector<Eigen::Index> order = DescendingOrder(norms);
  Eigen::VectorXd sigma(norms.size());
  for (Eigen::Index k = 0; k < sigma.size(); ++k)
    sigma(k) = norms(order[static_cast<std::size_t>(k)]);
  return sigma;
}

}  // namespace gearpath
