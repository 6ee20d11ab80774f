#include "core/dsp/envelope_spectrum.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "core/dsp/input_checks.h"

namespace gearpath {
namespace {

constexpr const char* kStage = "envelope spectrum";

}  // namespace

Result<EnvelopeSpectrum> EnvelopeSpectrum::Create(std::size_t block_length, double sample_rate_hz) {
  if (!std::isfinite(sample_rate_hz) || sample_rate_hz <= 0.0) {
    return Error{std::string(kStage) + ": sample rate " + std::to_string(sample_rate_hz) +
                 " Hz must be finite and positive"};
  }
  Result<Envelope> envelope = Envelope::Create(block_length);
  if (!envelope) return Error{std::string(kStage) + ": " + envelope.error()};
  Result<FftPlan> forward = FftPlan::Create(FftKind::kRealToComplex, block_length);
  if (!forward) return Error{std::string(kStage) + ": " + forward.error()};
  EnvelopeSpectrum ses(std::move(envelope).value(), std::move(forward).value());
  ses.block_length_ = block_length;
  ses.sample_rate_hz_ = sample_rate_hz;
  return ses;
}

Status EnvelopeSpectrum::Process(std::span<const double> input, std::span<double> ses) noexcept {
  if (Status s = dsp_detail::CheckLength(kStage, "SES output", ses, bin_count()); !s) return s;
  std::span<double> e2 = forward_.real_in();
  if (Status s = envelope_.ProcessSquared(input, e2); !s) {
    return Error{std::string(kStage) + ": " + s.error()};
  }
  double mean = 0.0;
  for (double v : e2) mean += v;
  mean /= static_cast<double>(block_length_);
  mean_squared_envelope_ = mean;
  if (!(mean > 0.0)) {  // silent block: no modulation to show
    std::fill(ses.begin(), ses.end(), 0.0);
    return Status::Ok();
  }
  for (double& v : e2) v -= mean;
  forward_.Execute();
  const std::span<const std::complex<double>> x = forward_.complex_out();
  // One-sided amplitude scaling (spectrum.h): 2/N inside, 1/N at DC and Nyquist; then / <e^2>.
  const double n = static_cast<double>(block_length_);
  const double interior = 2.0 / (n * mean);
  // Scaled before squaring, |X_k| / (n <e^2>) <= 2, so sqrt(re^2 + im^2) cannot overflow and
  // std::abs's hypot (a library call per bin, guarding against that) is not needed.
  for (std::size_t k = 0; k < x.size(); ++k) {
    const double re = x[k].real() * interior;
    const double im = x[k].imag() * interior;
    ses[k] = std::sqrt(re * re + im * im);
  }
  ses[0] *= 0.5;
  if (block_length_ % 2 == 0) ses.back() *= 0.5;
  return Status::Ok();
}

}  // namespace gearpath
