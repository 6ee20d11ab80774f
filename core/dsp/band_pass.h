// Zero-phase frequency-domain band-pass: Algorithm 2 step 5's filter (seed Sect. 4.3), applied
// to the kurtogram's band before demodulation.
//
// Why frequency domain: the band chosen by the kurtogram may touch 0 Hz or Nyquist, where an
// IIR band-pass design degenerates (DESIGN.md); a real gain G(f) applied to the block's DFT is
// zero-phase, exact at every frequency and needs no design step.
//
// Gain: G = 1 on [low_hz, high_hz] (edges included), a raised-cosine (Tukey) roll-off to 0 over
// `transition_hz` outside each edge, 0 beyond. The roll-off lies outside the nominal band so a
// tone inside passes with gain exactly 1; an edge at 0 Hz or at fs/2 has no roll-off. The block
// is filtered circularly (one period of a periodic signal); a smooth roll-off keeps the
// circular ringing of transients short (about 1/transition_hz). Same length in and out.
#pragma once

#include <cstddef>
#include <span>
#include <utility>

#include "core/common/result.h"
#include "core/dsp/fft_plan.h"

namespace gearpath {

class BandPass {
 public:
  // transition_hz >= 0 (0 = brick wall). Errors name the argument.
  static Result<BandPass> Create(std::size_t block_length, double sample_rate_hz,
                                 double transition_hz);

  // Filters `input` into `output` (both block_length; may not alias). Rejects wrong lengths,
  // non-finite samples and a band outside 0 <= low_hz < high_hz <= fs/2.
  Status Process(std::span<const double> input, double low_hz, double high_hz,
                 std::span<double> output) noexcept;

  // The gain applied at frequency f [Hz].
  double Gain(double f_hz, double low_hz, double high_hz) const noexcept;

  std::size_t block_length() const noexcept { return block_length_; }
  double sample_rate_hz() const noexcept { return sample_rate_hz_; }
  double transition_hz() const noexcept { return transition_hz_; }

 private:
  BandPass(FftPlan forward, FftPlan backward)
      : forward_(std::move(forward)), backward_(std::move(backward)) {}
  FftPlan forward_;
  FftPlan backward_;
  std::size_t block_length_ = 0;
  double sample_rate_hz_ = 0.0;
  double transition_hz_ = 0.0;
};

}  // namespace gearpath
