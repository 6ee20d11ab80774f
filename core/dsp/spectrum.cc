#include "core/dsp/spectrum.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "core/dsp/input_checks.h"

namespace gearpath {
namespace {

constexpr const char* kForward = "spectrum";
constexpr const char* kInverse = "inverse spectrum";

}  // namespace

Result<Spectrum> Spectrum::Create(std::size_t block_length, std::size_t channels,
                                  double sample_rate_hz) {
  if (block_length < 2) {
    return Error{std::string(kForward) + ": block length " + std::to_string(block_length) +
                 " is too short (need at least 2 samples)"};
  }
  if (channels == 0) return Error{std::string(kForward) + ": channel count must be at least 1"};
  if (!std::isfinite(sample_rate_hz) || sample_rate_hz <= 0.0) {
    return Error{std::string(kForward) + ": sample rate " + std::to_string(sample_rate_hz) +
                 " Hz must be finite and positive"};
  }
  Result<FftPlan> plan = FftPlan::Create(FftKind::kRealToComplex, block_length);
  if (!plan) return Error{std::string(kForward) + ": " + plan.error()};
  Spectrum spectrum(std::move(plan).value());
  spectrum.block_length_ = block_length;
  spectrum.channels_ = channels;
  spectrum.sample_rate_hz_ = sample_rate_hz;
  spectrum.frequencies_hz_.resize(OneSidedBinCount(block_length));
  for (std::size_t k = 0; k < spectrum.frequencies_hz_.size(); ++k) {
    spectrum.frequencies_hz_[k] =
        static_cast<double>(k) * sample_rate_hz / static_cast<double>(block_length);
  }
  return spectrum;
}

Status Spectrum::Process(std::span<const double> planar_samples,
                         std::span<std::complex<double>> planar_spectrum) noexcept {
  const std::size_t n = block_length_;
  const std::size_t bins = bin_count();
  if (Status s = dsp_detail::CheckLength(kForward, "sample block", planar_samples, n * channels_);
      !s) {
    return s;
  }
  if (Status s =
          dsp_detail::CheckLength(kForward, "spectrum output", planar_spectrum, bins * channels_);
      !s) {
    return s;
  }
  if (Status s = dsp_detail::CheckFinite(kForward, "sample block", planar_samples); !s) return s;

  const double interior = 2.0 / static_cast<double>(n);
  const double edge = 1.0 / static_cast<double>(n);
  const bool has_nyquist = n % 2 == 0;
  std::span<double> in = plan_.real_in();
  std::span<const std::complex<double>> out = plan_.complex_out();
  for (std::size_t c = 0; c < channels_; ++c) {
    const std::span<const double> x = planar_samples.subspan(c * n, n);
    std::copy(x.begin(), x.end(), in.begin());
    plan_.Execute();
    std::span<std::complex<double>> s = planar_spectrum.subspan(c * bins, bins);
    for (std::size_t k = 0; k < bins; ++k) s[k] = out[k] * interior;
    // DC and Nyquist appear once in the two-sided DFT, not twice: scale by 1/N.
    s[0] = out[0].real() * edge;
    if (has_nyquist) s[bins - 1] = out[bins - 1].real() * edge;
  }
  return Status::Ok();
}

Result<InverseSpectrum> InverseSpectrum::Create(std::size_t block_length, std::size_t channels) {
  if (block_length < 2) {
    return Error{std::string(kInverse) + ": block length " + std::to_string(block_length) +
                 " is too short (need at least 2 samples)"};
  }
  if (channels == 0) return Error{std::string(kInverse) + ": channel count must be at least 1"};
  Result<FftPlan> plan = FftPlan::Create(FftKind::kComplexToReal, block_length);
  if (!plan) return Error{std::string(kInverse) + ": " + plan.error()};
  InverseSpectrum inverse(std::move(plan).value());
  inverse.block_length_ = block_length;
  inverse.channels_ = channels;
  return inverse;
}

Status InverseSpectrum::Process(std::span<const std::complex<double>> planar_spectrum,
                                std::span<double> planar_samples) noexcept {
  const std::size_t n = block_length_;
  const std::size_t bins = bin_count();
  if (Status s = dsp_detail::CheckLength(kInverse, "spectrum", planar_spectrum, bins * channels_);
      !s) {
    return s;
  }
  if (Status s = dsp_detail::CheckLength(kInverse, "sample output", planar_samples, n * channels_);
      !s) {
    return s;
  }
  if (Status s = dsp_detail::CheckFinite(kInverse, "spectrum", planar_spectrum); !s) return s;

  // x[n] = (1/N) sum_k X[k] e^{+j...} over the Hermitian extension, which is what FFTW's c2r
  // computes without the 1/N. With S = (2/N) X inside and S = X/N at DC and Nyquist, the c2r
  // input is X/N = S/2 inside and S at DC and Nyquist.
  const bool has_nyquist = n % 2 == 0;
  std::span<std::complex<double>> in = plan_.complex_in();
  std::span<const double> out = plan_.real_out();
  for (std::size_t c = 0; c < channels_; ++c) {
    const std::span<const std::complex<double>> s = planar_spectrum.subspan(c * bins, bins);
    for (std::size_t k = 0; k < bins; ++k) in[k] = 0.5 * s[k];
    in[0] = s[0].real();
    if (has_nyquist) in[bins - 1] = s[bins - 1].real();
    plan_.Execute();  // overwrites `in`, which is refilled for every channel
    std::copy(out.begin(), out.end(), planar_samples.subspan(c * n, n).begin());
  }
  return Status::Ok();
}

}  // namespace gearpath
