#include "core/dsp/harmonic_indicator.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/dsp/input_checks.h"

namespace gearpath {
namespace {

constexpr const char* kStage = "harmonic indicator";

}  // namespace

Result<HarmonicIndicator> ComputeHarmonicIndicator(std::span<const double> ses, double bin_hz,
                                                   double characteristic_hz,
                                                   const HarmonicSearch& search) noexcept {
  // Strings are built only on the error paths: the success path allocates nothing.
  const auto stage = [] { return std::string(kStage); };
  if (ses.empty()) return Error{stage() + ": SES is empty"};
  if (Status s = dsp_detail::CheckFinite(kStage, "SES", ses); !s) return Error{s.error()};
  if (!std::isfinite(bin_hz) || bin_hz <= 0.0) {
    return Error{stage() + ": bin width " + std::to_string(bin_hz) +
                 " Hz must be finite and positive"};
  }
  if (!std::isfinite(characteristic_hz) || characteristic_hz <= 0.0) {
    return Error{stage() + ": characteristic frequency " + std::to_string(characteristic_hz) +
                 " Hz must be finite and positive"};
  }
  if (!std::isfinite(search.relative_tolerance) || search.relative_tolerance < 0.0) {
    return Error{stage() + ": relative tolerance " + std::to_string(search.relative_tolerance) +
                 " must be finite and non-negative"};
  }
  const double top_hz = static_cast<double>(ses.size() - 1) * bin_hz;
  if (kIndicatorHarmonics * characteristic_hz > top_hz) {
    return Error{stage() + ": characteristic frequency " + std::to_string(characteristic_hz) +
                 " Hz puts harmonic 5 above the SES's top frequency " + std::to_string(top_hz) +
                 " Hz (f_c must be at most Nyquist/5)"};
  }

  HarmonicIndicator result;
  result.characteristic_hz = characteristic_hz;
  const double last_bin = static_cast<double>(ses.size() - 1);
  for (int h = 1; h <= kIndicatorHarmonics; ++h) {
    const double target = h * characteristic_hz;
    const double half_width =
        std::max(bin_hz, search.relative_tolerance * target);  // at least one bin either side
    // Bins whose frequency lies within [target - w, target + w] (a tiny slack absorbs the
    // rounding of w / bin_hz when w is a whole number of bins).
    const double lo = std::clamp(std::ceil((target - half_width) / bin_hz - 1e-9), 0.0, last_bin);
    const double hi = std::clamp(std::floor((target + half_width) / bin_hz + 1e-9), 0.0, last_bin);
    auto first = static_cast<std::size_t>(lo);
    const auto last = static_cast<std::size_t>(hi);
    std::size_t best = first;
    for (std::size_t k = first; k <= last; ++k) {
      if (ses[k] > ses[best]) best = k;
    }
    HarmonicPeak& peak = result.harmonics[static_cast<std::size_t>(h - 1)];
    peak.frequency_hz = static_cast<double>(best) * bin_hz;
    peak.amplitude = ses[best];
    result.sum += peak.amplitude;
  }
  return result;
}

Result<double> EnhancementPercent(double reconstructed_indicator, double raw_indicator) noexcept {
  if (!std::isfinite(raw_indicator) || raw_indicator <= 0.0) {
    return Error{std::string(kStage) + ": raw indicator " + std::to_string(raw_indicator) +
                 " must be finite and positive to compare against"};
  }
  if (!std::isfinite(reconstructed_indicator) || reconstructed_indicator < 0.0) {
    return Error{std::string(kStage) + ": reconstructed indicator " +
                 std::to_string(reconstructed_indicator) + " must be finite and non-negative"};
  }
  return 100.0 * reconstructed_indicator / raw_indicator;
}

}  // namespace gearpath
