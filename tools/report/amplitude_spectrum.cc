#include "tools/report/amplitude_spectrum.h"

#include <cmath>
#include <complex>
#include <numbers>

#include "core/dsp/spectrum.h"

namespace gearpath::tools {

Result<AmplitudeSpectrum> HannAmplitudeSpectrum(std::span<const double> signal,
                                                double sample_rate_hz) {
  const std::size_t n = signal.size();
  if (n < 4) return Error{"amplitude spectrum: fewer than 4 samples"};
  if (!(sample_rate_hz > 0.0) || !std::isfinite(sample_rate_hz)) {
    return Error{"amplitude spectrum: the sample rate must be finite and positive"};
  }
  auto plan = Spectrum::Create(n, 1, sample_rate_hz);
  if (!plan) return Error{"amplitude spectrum: " + plan.error()};
  // Periodic Hann window: coherent gain exactly 0.5 over the block.
  std::vector<double> windowed(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double w =
        0.5 - 0.5 * std::cos(2.0 * std::numbers::pi * static_cast<double>(i) / static_cast<double>(n));
    windowed[i] = w * signal[i];
  }
  std::vector<std::complex<double>> bins(plan->bin_count());
  if (auto st = plan->Process(windowed, bins); !st.ok()) {
    return Error{"amplitude spectrum: " + st.error()};
  }
  AmplitudeSpectrum out;
  out.bin_hz = sample_rate_hz / static_cast<double>(n);
  out.amplitude.resize(bins.size());
  for (std::size_t k = 0; k < bins.size(); ++k) out.amplitude[k] = std::abs(bins[k]) / 0.5;
  return out;
}

}  // namespace gearpath::tools
