// Overall statistics of a vibration time signal, as an analyst reads them off a waveform.
//
// All are taken about the signal's mean (an accelerometer's DC is a sensor offset, not
// vibration): RMS = sqrt(mean (x - m)^2); peak = max |x - m|; crest factor = peak / RMS;
// kurtosis = mean (x - m)^4 / RMS^4 (not the excess: 3 for Gaussian noise, 1.5 for a sine;
// impacts from a damaged tooth raise it).
#pragma once

#include <span>

namespace gearpath::tools {

struct SignalStatistics {
  double rms = 0.0;
  double peak = 0.0;
  double crest_factor = 0.0;  // 0 for a constant signal
  double kurtosis = 0.0;      // 0 for a constant signal
};

// Statistics of `x` (empty: all zero). Non-finite samples are skipped.
SignalStatistics ComputeSignalStatistics(std::span<const double> x);

}  // namespace gearpath::tools
