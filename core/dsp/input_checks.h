// Small shared checks for the process steps of core/dsp: finite samples and block lengths.
// Inline, noexcept on the success path; the error messages name the stage and the problem.
#pragma once

#include <cmath>
#include <complex>
#include <cstddef>
#include <span>
#include <string>

#include "core/common/result.h"

namespace gearpath::dsp_detail {

// True when none of the n doubles at `v` is infinite or NaN. v - v is exactly 0 for a finite
// value and NaN otherwise, and a sum of zeros stays exactly 0 while a NaN stays NaN: summed in
// 8 independent lanes, element-wise work the compiler vectorises, so the check every
// process step makes of its input costs about a memory pass, not a branch per value (issue 9).
// (It relies on IEEE arithmetic: the project never builds with -ffast-math.)
// The lanes are named locals, not an array: GCC kept an array of lanes on the stack, a store
// and reload per step (a memory-latency chain), where locals stay in vector registers.
inline bool AllFinite(const double* v, std::size_t n) noexcept {
  double l0 = 0.0, l1 = 0.0, l2 = 0.0, l3 = 0.0, l4 = 0.0, l5 = 0.0, l6 = 0.0, l7 = 0.0;
  std::size_t i = 0;
  for (; i + 8 <= n; i += 8) {
    l0 += v[i] - v[i];
    l1 += v[i + 1] - v[i + 1];
    l2 += v[i + 2] - v[i + 2];
    l3 += v[i + 3] - v[i + 3];
    l4 += v[i + 4] - v[i + 4];
    l5 += v[i + 5] - v[i + 5];
    l6 += v[i + 6] - v[i + 6];
    l7 += v[i + 7] - v[i + 7];
  }
  bool finite = ((l0 + l1) + (l2 + l3)) + ((l4 + l5) + (l6 + l7)) == 0.0;
  for (; i < n; ++i) finite = finite && std::isfinite(v[i]);
  return finite;
}

// Index of the first non-finite value, or values.size() when all are finite.
inline std::size_t FirstNonFinite(std::span<const double> values) noexcept {
  if (AllFinite(values.data(), values.size())) return values.size();
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (!std::isfinite(values[i])) return i;
  }
  return values.size();
}

inline std::size_t FirstNonFinite(std::span<const std::complex<double>> values) noexcept {
  // A std::complex<double> is two doubles (real, imaginary), contiguous.
  if (AllFinite(reinterpret_cast<const double*>(values.data()), 2 * values.size())) {
    return values.size();
  }
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (!std::isfinite(values[i].real()) || !std::isfinite(values[i].imag())) return i;
  }
  return values.size();
}

// The shape a stage is created for: at least `min_length` samples, at a finite positive rate.
inline Status CheckBlockShape(const char* stage, std::size_t block_length, std::size_t min_length,
                              double sample_rate_hz) {
  if (block_length < min_length) {
    return Error{std::string(stage) + ": block length " + std::to_string(block_length) +
                 " is too short (need at least " + std::to_string(min_length) + " samples)"};
  }
  if (!std::isfinite(sample_rate_hz) || sample_rate_hz <= 0.0) {
    return Error{std::string(stage) + ": sample rate " + std::to_string(sample_rate_hz) +
                 " Hz must be finite and positive"};
  }
  return Status::Ok();
}

// Checks that `what` holds `expected` values. Allocates a message only on failure.
template <typename T>
Status CheckLength(const char* stage, const char* what, std::span<T> values,
                   std::size_t expected) noexcept {
  if (values.size() == expected) return Status::Ok();
  if (values.empty()) return Error{std::string(stage) + ": " + what + " is empty"};
  return Error{std::string(stage) + ": " + what + " has " + std::to_string(values.size()) +
               " values, configured for " + std::to_string(expected)};
}

template <typename T>
Status CheckFinite(const char* stage, const char* what, std::span<T> values) noexcept {
  const std::size_t bad = FirstNonFinite(std::span<const std::remove_const_t<T>>(values));
  if (bad == values.size()) return Status::Ok();
  return Error{std::string(stage) + ": " + what + " has a non-finite value at index " +
               std::to_string(bad)};
}

}  // namespace gearpath::dsp_detail
