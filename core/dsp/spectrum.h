// One-sided amplitude spectra of real blocks and their inverse (the "spectra (FFTW)" and the
// "time signal of that path's contribution (inverse FFT)" stages of the DESIGN.md data flow).
//
// Scaling (the "amplitude" convention): for a block of N samples x[n] = A cos(2 pi k0 n / N + phi)
// with an integer bin k0,
//   - 0 < k0 < N/2:            S[k0] = A e^{j phi}  (S[k] = (2/N) X[k], X the unnormalised DFT)
//   - k0 = 0 (DC):             S[0] = A cos(phi)    (S[0] = X[0] / N, always real)
//   - k0 = N/2 (Nyquist, N even): S[N/2] = A cos(phi) (S[N/2] = X[N/2] / N, always real);
//     a Nyquist-frequency sinusoid's phase cannot be told from its amplitude.
// The spectrum has N/2 + 1 bins for both parities (integer division); an odd N has no Nyquist
// bin, so its last bin (N-1)/2 is an interior bin scaled by 2/N. Bin k is at k fs / N Hz.
// No window is applied: the block is taken as one period (a sinusoid off a bin leaks).
//
// The inverse maps such a spectrum back to the real block it came from (exactly, up to
// rounding): x = IDFT of the Hermitian extension of X, with the imaginary parts of DC and
// Nyquist ignored (a real signal has none).
//
// Layout: channel-major ("planar"): all N samples of channel 0, then of channel 1, ...; the
// spectrum likewise holds N/2+1 bins of channel 0, then channel 1, ...
#pragma once

#include <complex>
#include <cstddef>
#include <span>
#include <utility>
#include <vector>

#include "core/common/result.h"
#include "core/dsp/fft_plan.h"

namespace gearpath {

// Number of one-sided bins of an N-sample real block: N/2 + 1.
constexpr std::size_t OneSidedBinCount(std::size_t block_length) noexcept {
  return block_length / 2 + 1;
}

class Spectrum {
 public:
  // Configures for blocks of `channels` x `block_length` samples at `sample_rate_hz`.
  static Result<Spectrum> Create(std::size_t block_length, std::size_t channels,
                                 double sample_rate_hz);

  std::size_t block_length() const noexcept { return block_length_; }
  std::size_t channels() const noexcept { return channels_; }
  std::size_t bin_count() const noexcept { return OneSidedBinCount(block_length_); }
  double sample_rate_hz() const noexcept { return sample_rate_hz_; }
  // Frequency of each bin, k fs / N [Hz].
  std::span<const double> frequencies_hz() const noexcept { return frequencies_hz_; }

  // planar_samples: channels x block_length; planar_spectrum: channels x bin_count.
  // Rejects wrong sizes and non-finite samples (the output is then untouched).
  Status Process(std::span<const double> planar_samples,
                 std::span<std::complex<double>> planar_spectrum) noexcept;

 private:
  explicit Spectrum(FftPlan plan) : plan_(std::move(plan)) {}
  FftPlan plan_;
  std::size_t block_length_ = 0;
  std::size_t channels_ = 0;
  double sample_rate_hz_ = 0.0;
  std::vector<double> frequencies_hz_;
};

class InverseSpectrum {
 public:
  // Configures for one-sided spectra of `channels` blocks of `block_length` samples (the
  // block length cannot be inferred from N/2+1 bins: N = 2(B-1) and 2(B-1)+1 share it).
  static Result<InverseSpectrum> Create(std::size_t block_length, std::size_t channels);

  std::size_t block_length() const noexcept { return block_length_; }
  std::size_t channels() const noexcept { return channels_; }
  std::size_t bin_count() const noexcept { return OneSidedBinCount(block_length_); }

  // planar_spectrum: channels x bin_count (amplitude-scaled as Spectrum makes it);
  // planar_samples: channels x block_length. Rejects wrong sizes and non-finite bins.
  Status Process(std::span<const std::complex<double>> planar_spectrum,
                 std::span<double> planar_samples) noexcept;

 private:
  explicit InverseSpectrum(FftPlan plan) : plan_(std::move(plan)) {}
  FftPlan plan_;
  std::size_t block_length_ = 0;
  std::size_t channels_ = 0;
};

}  // namespace gearpath
