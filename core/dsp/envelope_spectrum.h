// Squared envelope spectrum (SES): the output of Algorithm 2 (seed Sect. 4.3, Figs. 16-20),
// the spectrum in which the fault indicator is read.
//
//   SES[k] = |S_k{ e^2 - <e^2> }| / <e^2>,   e^2 = |x + j H{x}|^2 (envelope.h),
//
// with S_k the one-sided amplitude spectrum of spectrum.h (a line a cos(2 pi f t) in e^2 reads
// a at f) and <e^2> the block mean of the squared envelope (the DC line of the unnormalised
// SES). Why this normalisation: the SES is dimensionless and independent of the signal's gain,
// so indicators of the raw and of the reconstructed signal, or of two machines, compare
// directly. It reads as "modulation depth of the squared envelope at f": for a carrier
// (1 + m cos 2 pi fm t) cos 2 pi fc t, SES(fm) = 2m / (1 + m^2/2) and SES(2 fm) =
// (m^2/2) / (1 + m^2/2) (4/3 and 1/3 at m = 1); see envelope_spectrum_test.cc. SES[0] = 0.
// A silent block (<e^2> = 0) gives an all-zero SES.
//
// Input: the band-passed real block (the caller band-passes; this stage only demodulates).
#pragma once

#include <cstddef>
#include <span>
#include <utility>
#include <vector>

#include "core/common/result.h"
#include "core/dsp/envelope.h"
#include "core/dsp/fft_plan.h"

namespace gearpath {

class EnvelopeSpectrum {
 public:
  static Result<EnvelopeSpectrum> Create(std::size_t block_length, double sample_rate_hz);

  // ses: bin_count() = block_length/2 + 1 values at k fs / N. Rejects wrong lengths and
  // non-finite input.
  Status Process(std::span<const double> input, std::span<double> ses) noexcept;

  std::size_t block_length() const noexcept { return block_length_; }
  std::size_t bin_count() const noexcept { return block_length_ / 2 + 1; }
  double sample_rate_hz() const noexcept { return sample_rate_hz_; }
  double bin_hz() const noexcept { return sample_rate_hz_ / static_cast<double>(block_length_); }
  // <e^2> of the last processed block (the normaliser), in input units squared.
  double mean_squared_envelope() const noexcept { return mean_squared_envelope_; }

 private:
  EnvelopeSpectrum(Envelope envelope, FftPlan forward)
      : envelope_(std::move(envelope)), forward_(std::move(forward)) {}
  Envelope envelope_;
  FftPlan forward_;  // r2c of the squared envelope, written in place by envelope_
  std::size_t block_length_ = 0;
  double sample_rate_hz_ = 0.0;
  double mean_squared_envelope_ = 0.0;
};

}  // namespace gearpath
