// The amplitude spectrum the report draws (mesh zooms, contribution spectra): a Hann window,
// then core/dsp/spectrum.h's one-sided amplitude scaling, divided by the window's coherent
// gain (0.5), so a sine of amplitude A on a bin reads A there, and one between bins reads at
// least 0.85 A (the window's scalloping) instead of leaking across the whole zoom as the
// unwindowed spectrum would. For pictures only: the pipeline's numbers do not use it.
#pragma once

#include <span>
#include <vector>

#include "core/common/result.h"

namespace gearpath::tools {

struct AmplitudeSpectrum {
  double bin_hz = 0.0;             // bin k at k * bin_hz
  std::vector<double> amplitude;   // N/2 + 1 bins, the signal's unit (peak amplitude)
};

// Fails on fewer than 4 samples, a sample rate that is not finite and positive, or
// non-finite samples.
Result<AmplitudeSpectrum> HannAmplitudeSpectrum(std::span<const double> signal,
                                                double sample_rate_hz);

}  // namespace gearpath::tools
