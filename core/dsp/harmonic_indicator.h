// Harmonic fault indicator: the seed's fault indicator (Sect. 4.3, Table 5), the sum of the
// squared-envelope-spectrum amplitudes at the first five harmonics of a characteristic
// frequency f_c (a shaft rate, seed Table 6), and the enhancement ratio that compares the
// indicator of the reconstructed (dominant-path) signal with that of the raw measured signal.
//
// Speed drifts within a block and between the nominal and the true shaft rate, so each
// harmonic h is the largest SES value within +/- max(1 bin, rel_tol * h * f_c) of h * f_c
// (the tolerance grows with h because a rate error does). The reported frequency is that bin's.
// Assumes a one-sided SES on the grid k * bin_hz, k = 0..size-1 (envelope_spectrum.h).
#pragma once

#include <array>
#include <cstddef>
#include <span>

#include "core/common/result.h"

namespace gearpath {

inline constexpr int kIndicatorHarmonics = 5;

struct HarmonicSearch {
  double relative_tolerance = 0.01;  // half-width of the search window / (h f_c), >= 0
};

struct HarmonicPeak {
  double frequency_hz = 0.0;  // where the peak was found
  double amplitude = 0.0;     // SES value there
};

struct HarmonicIndicator {
  double characteristic_hz = 0.0;
  std::array<HarmonicPeak, kIndicatorHarmonics> harmonics;  // h = 1..5
  double sum = 0.0;                                         // the indicator
};

// Rejects an empty or non-finite SES, bin_hz <= 0, f_c <= 0 or non-finite, 5 f_c above the
// SES's top frequency ((size-1) bin_hz, Nyquist for an even block) and a negative tolerance.
Result<HarmonicIndicator> ComputeHarmonicIndicator(std::span<const double> ses, double bin_hz,
                                                   double characteristic_hz,
                                                   const HarmonicSearch& search = {}) noexcept;

// 100 * reconstructed / raw [%]: the seed's Table 5 figure (over 200 % for every fault type).
// Rejects a raw indicator that is not finite and positive, and a negative or non-finite
// reconstructed one.
Result<double> EnhancementPercent(double reconstructed_indicator, double raw_indicator) noexcept;

}  // namespace gearpath
