// 4-point cubic Lagrange interpolation of a sampled signal at a fractional position: the
// resampler of the synchronous average and of order tracking. Its gain on a tone is measured in
// synchronous_average.h (under 1 % loss below 0.145 fs).
#pragma once

#include <cstddef>

namespace gearpath {

// x read at the fractional sample position u, 0 <= u <= n - 1, n >= 4. The stencil is the four
// samples around u, moved inwards at the block ends.
inline double InterpolateCubic(const double* x, std::size_t n, double u) noexcept {
  const auto i = static_cast<std::size_t>(u);  // floor, u >= 0
  std::size_t first = i == 0 ? 0 : i - 1;
  if (first + 3 >= n) first = n - 4;
  const double t = u - static_cast<double>(first);  // position in stencil units, 0..3
  const double a = t - 1.0;
  const double b = t - 2.0;
  const double c = t - 3.0;
  const double* s = x + first;
  return -a * b * c / 6.0 * s[0] + t * b * c / 2.0 * s[1] - t * a * c / 2.0 * s[2] +
         t * a * b / 6.0 * s[3];
}

}  // namespace gearpath
