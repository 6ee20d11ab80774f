// Analytic signal and squared envelope by FFT (the Hilbert demodulation of Algorithm 2 step 6,
// seed Sect. 4.3).
//
// The analytic signal z = x + j H{x} is formed in the frequency domain: DFT of the real block,
// positive-frequency bins doubled, DC (and the Nyquist bin of an even length) kept once,
// negative frequencies zeroed, inverse DFT. Re z = x exactly. The block is one period of a
// periodic signal: a carrier on an exact bin gives an exact envelope; one off a bin leaks.
// The squared envelope |z|^2 is what the squared envelope spectrum analyses.
#pragma once

#include <complex>
#include <cstddef>
#include <span>
#include <utility>

#include "core/common/result.h"
#include "core/dsp/fft_plan.h"

namespace gearpath {

class Envelope {
 public:
  static Result<Envelope> Create(std::size_t block_length);

  // analytic: block_length complex samples. Rejects wrong lengths and non-finite input.
  Status ProcessAnalytic(std::span<const double> input,
                         std::span<std::complex<double>> analytic) noexcept;
  // squared_envelope: block_length samples of |analytic|^2.
  Status ProcessSquared(std::span<const double> input, std::span<double> squared_envelope) noexcept;

  std::size_t block_length() const noexcept { return block_length_; }

 private:
  Envelope(FftPlan forward, FftPlan backward)
      : forward_(std::move(forward)), backward_(std::move(backward)) {}
  Status Run(std::span<const double> input) noexcept;  // leaves z in backward_.complex_out()

  FftPlan forward_;   // r2c
  FftPlan backward_;  // c2c backward
  std::size_t block_length_ = 0;
};

}  // namespace gearpath
