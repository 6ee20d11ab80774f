// Reading a sampled signal on a precomputed grid of fractional positions with 4-point cubic
// Lagrange stencils (cubic_interpolation.h): the synchronous average's angular resampling, the
// largest single cost of a block (docs/performance.md). The grid is computed once per block and
// shaft; every signal of the block is then read on it.
#pragma once

#include <cstddef>
#include <cstdint>

namespace gearpath {

// A grid of stencils as parallel arrays: point p reads x[first[p] .. first[p] + 3] with the
// weights w0[p] .. w3[p] (w2 subtracted), as CubicStencil holds one point. (Weights computed
// from the position as the points are read would stream 12 bytes per point instead of 36, but
// their ten products cost more than the loads: the reference block's averages took 0.4 ms
// longer.)
struct CubicGridView {
  const std::uint32_t* first = nullptr;
  const double* w0 = nullptr;
  const double* w1 = nullptr;
  const double* w2 = nullptr;
  const double* w3 = nullptr;
};

// out[m] = x read at grid point begin + m, for m < count (out[m] += it with `add`). x holds n
// samples and every stencil lies inside it. Each value has the bits of ApplyCubicStencil at that
// point, whichever instruction set runs it: the wide paths keep its terms and their order and
// fuse no multiply-add.
void ResampleOnGrid(const double* x, std::size_t n, const CubicGridView& grid, std::size_t begin,
                    std::size_t count, double* out, bool add) noexcept;

}  // namespace gearpath
