#include "core/frf/frac.h"

#include <fmt/format.h>

#include <cmath>
#include <complex>

namespace gearpath {

Result<double> Frac(const Eigen::VectorXd& frequency_hz, const Eigen::VectorXcd& a,
                    const Eigen::VectorXcd& b, double f_lo_hz, double f_hi_hz) {
  if (a.size() != frequency_hz.size() || b.size() != frequency_hz.size()) {
    return Error{
        fmt::format("FRAC: size mismatch: frequency axis has {} bins, first FRF {}, "
                    "second FRF {}",
                    frequency_hz.size(), a.size(), b.size())};
  }
  if (!std::isfinite(f_lo_hz) || !std::isfinite(f_hi_hz) || f_lo_hz > f_hi_hz) {
    return Error{fmt::format("FRAC: band [{}, {}] Hz is not a finite interval with f_lo <= f_hi",
                             f_lo_hz, f_hi_hz)};
  }
  std::complex<double> cross(0.0, 0.0);
  double energy_a = 0.0;
  double energy_b = 0.0;
  Eigen::Index count = 0;
  for (Eigen::Index j = 0; j < frequency_hz.size(); ++j) {
    const double f = frequency_hz[j];
    if (!(f >= f_lo_hz && f <= f_hi_hz)) continue;
    if (!std::isfinite(a[j].real()) || !std::isfinite(a[j].imag()) || !std::isfinite(b[j].real()) ||
        !std::isfinite(b[j].imag())) {
      return Error{fmt::format("FRAC: non-finite FRF value at {} Hz (bin {})", f, j)};
    }
    cross += std::conj(a[j]) * b[j];
    energy_a += std::norm(a[j]);
    energy_b += std::norm(b[j]);
    ++count;
  }
  if (count == 0) {
    return Error{
        fmt::format("FRAC: no frequency bin lies in the band [{}, {}] Hz", f_lo_hz, f_hi_hz)};
  }
  if (energy_a == 0.0 || energy_b == 0.0) {
    return Error{fmt::format("FRAC: the {} FRF is zero over [{}, {}] Hz, so its shape is undefined",
                             energy_a == 0.0 ? "first" : "second", f_lo_hz, f_hi_hz)};
  }
  return std::norm(cross) / (energy_a * energy_b);
}

Result<Eigen::MatrixXd> FracPerEntry(const FrfMatrix& a, const FrfMatrix& b, double f_lo_hz,
                                     double f_hi_hz) {
  if (a.bins() != b.bins() || a.bins() != static_cast<Eigen::Index>(a.at.size()) ||
      b.bins() != static_cast<Eigen::Index>(b.at.size())) {
    return Error{fmt::format("FRAC: the FRF matrices have {} and {} bins ({} and {} matrices)",
                             a.bins(), b.bins(), a.at.size(), b.at.size())};
  }
  if (a.bins() == 0) return Error{"FRAC: the FRF matrices have no bins"};
  if (a.frequency_hz != b.frequency_hz) {
    return Error{"FRAC: the two FRF matrices are on different frequency axes"};
  }
  const Eigen::Index rows = a.outputs();
  const Eigen::Index cols = a.inputs();
  for (Eigen::Index k = 0; k < a.bins(); ++k) {
    for (const FrfMatrix* m : {&a, &b}) {
      if (m->at[k].rows() != rows || m->at[k].cols() != cols) {
        return Error{fmt::format("FRAC: matrix at bin {} is {} x {}, expected {} x {}", k,
                                 m->at[k].rows(), m->at[k].cols(), rows, cols)};
      }
    }
  }
  Eigen::MatrixXd out(rows, cols);
  Eigen::VectorXcd ea(a.bins());
  Eigen::VectorXcd eb(a.bins());
  for (Eigen::Index i = 0; i < rows; ++i) {
    for (Eigen::Index j = 0; j < cols; ++j) {
      for (Eigen::Index k = 0; k < a.bins(); ++k) {
        ea[k] = a.at[k](i, j);
        eb[k] = b.at[k](i, j);
      }
      Result<double> frac = Frac(a.frequency_hz, ea, eb, f_lo_hz, f_hi_hz);
      if (!frac) return Error{fmt::format("entry ({}, {}): {}", i, j, frac.error())};
      out(i, j) = *frac;
    }
  }
  return out;
}

}  // namespace gearpath
