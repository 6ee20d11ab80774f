// FirstNonFinite (core/dsp/input_checks.h): the lane-summed fast path must find every NaN and
// infinity wherever it sits (inside the 8-wide lanes, in the tail, in either part of a
// complex), and pass every finite value, including the largest ones, whose v - v is still 0.
#include "core/dsp/input_checks.h"

#include <gtest/gtest.h>

#include <complex>
#include <limits>
#include <span>
#include <vector>

namespace gearpath::dsp_detail {
namespace {

constexpr double kNan = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

std::vector<double> FiniteValues(std::size_t n) {
  // Extremes of the finite range, signed zeros and subnormals among ordinary values.
  const double pool[] = {1.0, -0.0, 0.0, std::numeric_limits<double>::max(),
                         -std::numeric_limits<double>::max(), std::numeric_limits<double>::denorm_min(),
                         -2.5e-300, 3.75};
  std::vector<double> v(n);
  for (std::size_t i = 0; i < n; ++i) v[i] = pool[i % 8];
  return v;
}

TEST(FirstNonFinite, PassesEveryFiniteValueIncludingTheExtremes) {
  for (std::size_t n = 0; n <= 40; ++n) {
    const std::vector<double> v = FiniteValues(n);
    EXPECT_EQ(FirstNonFinite(std::span<const double>(v)), n) << "n " << n;
  }
}

TEST(FirstNonFinite, FindsTheFirstNanOrInfinityAtEveryPosition) {
  for (std::size_t n = 1; n <= 40; ++n) {
    for (std::size_t at = 0; at < n; ++at) {
      for (double bad : {kNan, kInf, -kInf}) {
        std::vector<double> v = FiniteValues(n);
        v[at] = bad;
        if (at + 3 < n) v[at + 3] = kNan;  // a later one does not hide the first
        EXPECT_EQ(FirstNonFinite(std::span<const double>(v)), at) << "n " << n << " at " << at;
      }
    }
  }
}

TEST(FirstNonFinite, FindsANonFiniteRealOrImaginaryPartOfAComplexValue) {
  for (std::size_t n = 1; n <= 20; ++n) {
    for (std::size_t at = 0; at < n; ++at) {
      for (bool imaginary : {false, true}) {
        std::vector<std::complex<double>> v(n, {1.0, -std::numeric_limits<double>::max()});
        v[at] = imaginary ? std::complex<double>(1.0, kInf) : std::complex<double>(kNan, 1.0);
        EXPECT_EQ(FirstNonFinite(std::span<const std::complex<double>>(v)), at)
            << "n " << n << " at " << at << (imaginary ? " imaginary" : " real");
      }
    }
    const std::vector<std::complex<double>> fine(n, {-0.0, 2.0});
    EXPECT_EQ(FirstNonFinite(std::span<const std::complex<double>>(fine)), n);
  }
}

}  // namespace
}  // namespace gearpath::dsp_detail
