// FrfPowerTable: an FRF set on one block shape's in-range bins, laid out contiguous per
// (path, channel) over the bins, for the per-block passes that walk one path at one channel:
//  - |H_cj|^2 in float (energies need no more than 7 digits), so a path's contribution energy is
//    a dot product with |F_j|^2 (|H F|^2 = |H|^2 |F|^2), summed in double;
//  - H_cj itself (complex double), so a contribution spectrum C_cj = H_cj F_j (seed Eq. 45) is
//    one streaming product instead of a walk over 8001 per-bin matrices on the heap.
// It depends only on the FRF set and the block shape: machines on one shared set hold one table
// (SharedFrfOperators::Power); at the reference workload 12 x 12 x 8001 bins it holds
// 4.6 MB of |H|^2 and 18.4 MB of H.
#pragma once

#include <complex>
#include <cstddef>
#include <vector>

#include "core/pipeline/frf_grid_mapping.h"

namespace gearpath {

struct FrfPowerTable {
  std::size_t paths = 0;
  std::size_t channels = 0;
  std::size_t bins = 0;       // in-range bins of the mapping
  std::vector<float> power;   // (path * channels + channel) * bins + bin
  std::vector<std::complex<double>> response;  // the same layout: H_cj

  // |H|^2 of path p at FRF row c over the in-range bins.
  const float* Row(std::size_t p, std::size_t c) const noexcept {
    return power.data() + (p * channels + c) * bins;
  }
  // H of path p at FRF row c over the in-range bins.
  const std::complex<double>* Response(std::size_t p, std::size_t c) const noexcept {
    return response.data() + (p * channels + c) * bins;
  }

  // Lays out |H|^2 and H of `map`'s in-range FRF (channels x paths per bin).
  static FrfPowerTable Build(const FrfGridMapping& map);
};

}  // namespace gearpath
