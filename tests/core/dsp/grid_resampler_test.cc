#include "core/dsp/grid_resampler.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/dsp/cubic_interpolation.h"
#include "tests/core/dsp/test_signals.h"

namespace gearpath {
namespace {

// A grid as the synchronous average's plan holds it, built from positions.
struct Grid {
  std::vector<std::uint32_t> first;
  std::vector<double> w0, w1, w2, w3;
  std::vector<CubicStencil> stencils;

  Grid(std::size_t n, const std::vector<double>& positions) {
    for (double u : positions) {
      const CubicStencil s = MakeCubicStencil(n, u);
      stencils.push_back(s);
      first.push_back(static_cast<std::uint32_t>(s.first));
      w0.push_back(s.w0);
      w1.push_back(s.w1);
      w2.push_back(s.w2);
      w3.push_back(s.w3);
    }
  }
  CubicGridView View() const { return {first.data(), w0.data(), w1.data(), w2.data(), w3.data()}; }
};

// Whatever instruction set this CPU gives the resampler (AVX-512, AVX2 or none), every value
// must carry the bits of the scalar stencil: the synchronous average's results may not depend
// on the machine. The grids cover what the wide paths must hand back to the scalar one: a warp
// that stretches points more than a sample apart, a point behind its group's first, the block's
// last samples, and group boundaries that do not start at a multiple of the vector width.
TEST(GridResampler, EveryPointHasTheBitsOfTheScalarStencil) {
  constexpr std::size_t kN = 3000;
  const std::vector<double> x = dsp_test::WhiteNoise(kN, 1.0, 7);
  std::vector<std::vector<double>> grids;
  // Upsampling at constant speed, as the average reads a shaft: 0.78 samples per point, to the
  // last sample.
  std::vector<double> uniform;
  for (double u = 0.0; u <= static_cast<double>(kN - 1); u += 0.78) uniform.push_back(u);
  grids.push_back(uniform);
  // A warp: steps from 0.2 to 1.9 samples, and back.
  std::vector<double> warped;
  for (std::size_t p = 0; p < 2400; ++p) {
    warped.push_back(static_cast<double>(p) * 1.05 +
                     180.0 * std::sin(static_cast<double>(p) * 6.283185307179586 / 2400.0));
  }
  grids.push_back(warped);
  // Points that step back (a point before its group's first) and repeat.
  std::vector<double> jitter;
  for (std::size_t p = 0; p < 1000; ++p) {
    jitter.push_back(10.0 + static_cast<double>(p) * 0.9 + ((p % 3 == 1) ? -2.5 : 0.0));
  }
  grids.push_back(jitter);

  for (std::size_t g = 0; g < grids.size(); ++g) {
    const Grid grid(kN, grids[g]);
    const std::size_t points = grid.first.size();
    for (const std::size_t begin : {std::size_t{0}, std::size_t{3}, std::size_t{5}}) {
      const std::size_t count = points - begin - 1;  // an odd tail as well
      std::vector<double> out(count, -1.0);
      ResampleOnGrid(x.data(), kN, grid.View(), begin, count, out.data(), /*add=*/false);
      std::vector<double> sum(count, 0.25);
      ResampleOnGrid(x.data(), kN, grid.View(), begin, count, sum.data(), /*add=*/true);
      for (std::size_t m = 0; m < count; ++m) {
        const double expected = ApplyCubicStencil(x.data(), grid.stencils[begin + m]);
        ASSERT_EQ(out[m], expected) << "grid " << g << ", begin " << begin << ", point " << m;
        ASSERT_EQ(sum[m], 0.25 + expected)
            << "grid " << g << ", begin " << begin << ", point " << m;
      }
    }
  }
}

// SetCubicStencils (vectorised, 32-bit indices) against MakeCubicStencil point by point, bit
// for bit: positions across the block, on whole samples, at both ends (where the stencil moves
// inwards), outside it (clamped first, as its callers clamped), and at counts and offsets that
// leave every clone a tail.
TEST(GridResampler, SetStencilsHasTheBitsOfMakeCubicStencil) {
  for (const std::size_t n : {std::size_t{4}, std::size_t{5}, std::size_t{3001}}) {
    const double last = static_cast<double>(n - 1);
    std::vector<double> positions = {0.0, -0.0, 1.0, 0.5, last, last - 0.25, last - 1.0,
                                     last - 2.0, -3.5, last + 0.75, 1e9, -1e9};
    const std::vector<double> noise = dsp_test::WhiteNoise(997, 1.0, 5);
    for (std::size_t k = 0; k < noise.size(); ++k) {
      positions.push_back(std::fmod(std::abs(noise[k]) * 1000.0 + static_cast<double>(k), last));
    }
    for (const std::size_t begin : {std::size_t{0}, std::size_t{3}}) {
      const std::size_t count = positions.size() - begin;
      CubicGrid grid;
      grid.Resize(begin + count + 1);
      grid.first[begin + count] = 1;  // past the count: must stay as it is
      grid.w3[begin + count] = 5.0;
      SetCubicStencils(n, positions.data() + begin, count, grid, begin);
      for (std::size_t k = 0; k < count; ++k) {
        const CubicStencil s = MakeCubicStencil(n, std::clamp(positions[begin + k], 0.0, last));
        const std::size_t p = begin + k;
        ASSERT_EQ(grid.first[p], s.first) << "n " << n << ", position " << positions[p];
        ASSERT_EQ(grid.w0[p], s.w0) << "n " << n << ", position " << positions[p];
        ASSERT_EQ(grid.w1[p], s.w1) << "n " << n << ", position " << positions[p];
        ASSERT_EQ(grid.w2[p], s.w2) << "n " << n << ", position " << positions[p];
        ASSERT_EQ(grid.w3[p], s.w3) << "n " << n << ", position " << positions[p];
      }
      EXPECT_EQ(grid.first[begin + count], 1u);
      EXPECT_EQ(grid.w3[begin + count], 5.0);
    }
  }
}

// On the sample grid the stencil is the sample itself, so the resampled signal is the signal:
// a check against the signal, not only against the scalar formula.
TEST(GridResampler, OnTheSampleGridItReturnsTheSamples) {
  constexpr std::size_t kN = 513;
  const std::vector<double> x = dsp_test::WhiteNoise(kN, 2.0, 11);
  std::vector<double> positions;
  for (std::size_t i = 0; i < kN; ++i) positions.push_back(static_cast<double>(i));
  const Grid grid(kN, positions);
  std::vector<double> out(kN);
  ResampleOnGrid(x.data(), kN, grid.View(), 0, kN, out.data(), false);
  // Exactly: the order tracker's first iteration copies the signal instead of reading it at
  // the identity warp, on the strength of this.
  for (std::size_t i = 0; i < kN; ++i) ASSERT_EQ(out[i], x[i]) << "sample " << i;
}

}  // namespace
}  // namespace gearpath
