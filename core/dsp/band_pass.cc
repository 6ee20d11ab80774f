#include "core/dsp/band_pass.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <utility>

#include "core/dsp/input_checks.h"

namespace gearpath {
namespace {

constexpr const char* kStage = "band-pass";

// Raised-cosine roll-off from 1 (distance 0) to 0 (distance >= width).
double RollOff(double distance, double width) noexcept {
  if (distance <= 0.0) return 1.0;
  if (distance >= width) return 0.0;
  return 0.5 * (1.0 + std::cos(std::numbers::pi * distance / width));
}

}  // namespace

Result<BandPass> BandPass::Create(std::size_t block_length, double sample_rate_hz,
                                  double transition_hz) {
  const std::string stage = kStage;
  if (Status s = dsp_detail::CheckBlockShape(kStage, block_length, 2, sample_rate_hz); !s) {
    return Error{s.error()};
  }
  if (!std::isfinite(transition_hz) || transition_hz < 0.0) {
    return Error{stage + ": transition_hz " + std::to_string(transition_hz) +
                 " must be finite and non-negative"};
  }
  Result<FftPlan> forward = FftPlan::Create(FftKind::kRealToComplex, block_length);
  if (!forward) return Error{stage + ": " + forward.error()};
  Result<FftPlan> backward = FftPlan::Create(FftKind::kComplexToReal, block_length);
  if (!backward) return Error{stage + ": " + backward.error()};
  BandPass band_pass(std::move(forward).value(), std::move(backward).value());
  band_pass.block_length_ = block_length;
  band_pass.sample_rate_hz_ = sample_rate_hz;
  band_pass.transition_hz_ = transition_hz;
  return band_pass;
}

double BandPass::Gain(double f_hz, double low_hz, double high_hz) const noexcept {
  if (f_hz >= low_hz && f_hz <= high_hz) return 1.0;
  if (transition_hz_ <= 0.0) return 0.0;
  return f_hz < low_hz ? RollOff(low_hz - f_hz, transition_hz_)
                       : RollOff(f_hz - high_hz, transition_hz_);
}

Status BandPass::Process(std::span<const double> input, double low_hz, double high_hz,
                         std::span<double> output) noexcept {
  if (Status s = dsp_detail::CheckLength(kStage, "input block", input, block_length_); !s) {
    return s;
  }
  if (Status s = dsp_detail::CheckLength(kStage, "output block", output, block_length_); !s) {
    return s;
  }
  const double nyquist = sample_rate_hz_ / 2.0;
  if (!std::isfinite(low_hz) || !std::isfinite(high_hz) || low_hz < 0.0 || high_hz > nyquist ||
      !(low_hz < high_hz)) {
    return Error{std::string(kStage) + ": band [" + std::to_string(low_hz) + ", " +
                 std::to_string(high_hz) +
                 "] Hz must satisfy 0 <= low < high <= fs/2 = " + std::to_string(nyquist) + " Hz"};
  }
  if (Status s = dsp_detail::CheckFinite(kStage, "input block", input); !s) return s;

  std::copy(input.begin(), input.end(), forward_.real_in().begin());
  forward_.Execute();
  const std::span<const std::complex<double>> x = forward_.complex_out();
  std::span<std::complex<double>> y = backward_.complex_in();
  const double n = static_cast<double>(block_length_);
  for (std::size_t k = 0; k < x.size(); ++k) {
    const double f = static_cast<double>(k) * sample_rate_hz_ / n;
    y[k] = x[k] * (Gain(f, low_hz, high_hz) / n);  // 1/N: FFTW's round trip multiplies by N
  }
  backward_.Execute();
  std::copy(backward_.real_out().begin(), backward_.real_out().end(), output.begin());
  return Status::Ok();
}

}  // namespace gearpath
