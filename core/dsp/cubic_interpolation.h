// 4-point cubic Lagrange interpolation of a sampled signal at a fractional position: the one
// definition of the stencil that the synchronous average, the transient gate's periodic read
// and order tracking resample with (grid_resampler.h fills and applies grids of them, many
// points at a time, with these terms in this order). Its gain on a tone is measured in
// synchronous_average.h (under 1 % loss below 0.145 fs).
#pragma once

#include <cstddef>

namespace gearpath {

// Where and how to read a signal of n samples at one fractional position: the first of the four
// samples around it (moved inwards at the block ends) and their Lagrange weights (the third one
// is subtracted). Computed once, it reads any number of signals at that position.
struct CubicStencil {
  std::size_t first = 0;
  double w0 = 0.0, w1 = 0.0, w2 = 0.0, w3 = 0.0;
};

// The stencil at u, 0 <= u <= n - 1, n >= 4.
inline CubicStencil MakeCubicStencil(std::size_t n, double u) noexcept {
  const auto i = static_cast<std::size_t>(u);  // floor, u >= 0
  std::size_t first = i == 0 ? 0 : i - 1;
  if (first + 3 >= n) first = n - 4;
  const double t = u - static_cast<double>(first);  // position in stencil units, 0..3
  const double a = t - 1.0;
  const double b = t - 2.0;
  const double c = t - 3.0;
  return {first, -a * b * c / 6.0, t * b * c / 2.0, t * a * c / 2.0, t * a * b / 6.0};
}

inline double ApplyCubicStencil(const double* x, const CubicStencil& s) noexcept {
  const double* p = x + s.first;
  return s.w0 * p[0] + s.w1 * p[1] - s.w2 * p[2] + s.w3 * p[3];
}

}  // namespace gearpath
