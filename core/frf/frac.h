// FRAC: the frequency response assurance criterion (seed Eq. 25), a 0..1 measure of how alike
// two FRFs are in shape over a frequency band.
//
//   FRAC = |sum_j conj(a_j) b_j|^2 / (sum_j |a_j|^2 * sum_j |b_j|^2),  j over the bins in band.
//
// 1 means b = c a for some complex c != 0 (same shape, any scale and phase), 0 means orthogonal;
// Cauchy-Schwarz keeps it in [0, 1] (up to rounding: it is not clamped). The band is inclusive
// by frequency: bins with f_lo <= f <= f_hi. Errors (Result) name the problem: size mismatch,
// empty or inverted band, zero energy of either FRF in the band, non-finite data.
#pragma once

#include <Eigen/Dense>

#include "core/common/frf_matrix.h"
#include "core/common/result.h"

namespace gearpath {

// FRAC of two FRFs sampled on the same frequency axis.
Result<double> Frac(const Eigen::VectorXd& frequency_hz, const Eigen::VectorXcd& a,
                    const Eigen::VectorXcd& b, double f_lo_hz, double f_hi_hz);

// FRAC entry by entry of two FRF matrices of equal shape on the same frequency axis
// (outputs x inputs result).
Result<Eigen::MatrixXd> FracPerEntry(const FrfMatrix& a, const FrfMatrix& b, double f_lo_hz,
                                     double f_hi_hz);

}  // namespace gearpath
