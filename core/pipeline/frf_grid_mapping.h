// FRF grid mapping: the decoupled FRF matrix brought onto a block's FFT bin grid, once per FRF
// set and block shape (DESIGN.md: everything that depends only on the FRFs is computed when the
// set is loaded or the block shape is first seen, never per block).
//
// Block bin k sits at f_k = k fs / N, k = 0..N/2. Interpolation: per matrix entry, linear in
// the real and the imaginary parts between the two FRF frequencies that bracket f_k (exact, a
// copy, when f_k coincides with an FRF frequency to within 1e-9 of a bin). Linear real/imag
// interpolation is what measured FRFs support (their own resolution is the hammer test's);
// it is exact for an FRF that is linear in f and its error is O(df^2 |H''|).
// Bins outside [f_first, f_last] of the FRF set are OUTSIDE: no extrapolation; the pipeline
// sets their forces to zero, excludes them from contributions and shares, and counts them in
// every result (BlockRegularisation::bins_outside_frf). They form at most two runs, below and
// above the FRF range, so the in-range bins are one contiguous run [first_bin, first_bin+bins).
#pragma once

#include <cstddef>
#include <memory>
#include <span>

#include "core/common/frf_matrix.h"
#include "core/common/result.h"

namespace gearpath {

// FrfMatrix's read interface over per-bin matrices that another object owns.
struct FrfMatrixView {
  std::span<const Eigen::MatrixXcd> at;
  Eigen::Index bins() const noexcept { return static_cast<Eigen::Index>(at.size()); }
};

// A copy is cheap and shares the mapped matrices, which are never written after the mapping:
// every machine on one FRF set and block shape can hold the same ones (SharedFrfOperators).
struct FrfGridMapping {
  std::size_t block_length = 0;
  double sample_rate_hz = 0.0;
  std::size_t block_bins = 0;    // N/2 + 1
  std::size_t first_bin = 0;     // first in-range block bin
  std::shared_ptr<const FrfMatrix> in_range;  // the FRF on the in-range bins, their frequencies
  FrfMatrixView frf;             // views *in_range: frf.at[i] is block bin first_bin + i
  std::size_t bins_outside = 0;  // block_bins - frf.bins()

  bool InRange(std::size_t bin) const noexcept {
    return bin >= first_bin && bin < first_bin + static_cast<std::size_t>(frf.bins());
  }
};

// Errors: empty or inconsistent FRF (matrix count vs frequencies, unequal shapes, frequencies
// not strictly increasing, non-finite), block_length < 2, sample rate not > 0, and no block bin
// inside the FRF range (the message gives both ranges).
Result<FrfGridMapping> MapFrfToBlockGrid(const FrfMatrix& frf, std::size_t block_length,
                                         double sample_rate_hz);

}  // namespace gearpath
