// Reading a sampled signal on a precomputed grid of fractional positions with 4-point cubic
// Lagrange stencils (cubic_interpolation.h): the synchronous average's angular resampling, the
// largest single cost of a block (docs/performance.md). The grid is computed once per block and
// shaft; every signal of the block is then read on it.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/dsp/cubic_interpolation.h"

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

// The arrays behind a CubicGridView, made once (Resize) and filled by SetCubicStencils.
struct CubicGrid {
  std::vector<std::uint32_t> first;
  std::vector<double> w0, w1, w2, w3;

  void Resize(std::size_t points) {
    first.assign(points, 0);
    w0.assign(points, 0.0);
    w1.assign(points, 0.0);
    w2.assign(points, 0.0);
    w3.assign(points, 0.0);
  }
  // Points every array holds.
  std::size_t size() const noexcept {
    return std::min({first.size(), w0.size(), w1.size(), w2.size(), w3.size()});
  }
  CubicGridView View() const noexcept {
    return {first.data(), w0.data(), w1.data(), w2.data(), w3.data()};
  }
};

// Grid points begin .. begin + count - 1 read a signal of n samples (4 <= n < 2^31) at
// position[k] clamped to [0, n - 1] (finite positions): the stencils of MakeCubicStencil, bit
// for bit, many at a time (vectorised; one point at a time, filling a grid was 1-2 % of a
// reference block in each of its three users). The grid holds at least begin + count points.
void SetCubicStencils(std::size_t n, const double* position, std::size_t count, CubicGrid& grid,
                      std::size_t begin = 0) noexcept;

// SetCubicStencils for grid points 0 .. count - 1 at the positions position_at(p) (a callable
// of the point index returning a double), gathered 256 at a time on the stack: for the plans
// that compute each point's position as they go.
template <typename PositionAt>
void SetCubicStencilsAt(std::size_t n, std::size_t count, CubicGrid& grid,
                        PositionAt&& position_at) noexcept {
  constexpr std::size_t kChunk = 256;
  std::array<double, kChunk> position;
  for (std::size_t p0 = 0; p0 < count; p0 += kChunk) {
    const std::size_t m = std::min(kChunk, count - p0);
    for (std::size_t k = 0; k < m; ++k) position[k] = position_at(p0 + k);
    SetCubicStencils(n, position.data(), m, grid, p0);
  }
}

// out[m] = x read at grid point begin + m, for m < count (out[m] += it with `add`). x holds n
// samples and every stencil lies inside it. Each value has the bits of ApplyCubicStencil at that
// point, whichever instruction set runs it: the wide paths keep its terms and their order and
// fuse no multiply-add.
void ResampleOnGrid(const double* x, std::size_t n, const CubicGridView& grid, std::size_t begin,
                    std::size_t count, double* out, bool add) noexcept;

}  // namespace gearpath
