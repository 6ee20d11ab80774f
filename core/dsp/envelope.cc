#include "core/dsp/envelope.h"

#include <algorithm>
#include <string>
#include <utility>

#include "core/dsp/input_checks.h"

namespace gearpath {
namespace {

constexpr const char* kStage = "envelope";

}  // namespace

Result<Envelope> Envelope::Create(std::size_t block_length) {
  if (block_length < 2) {
    return Error{std::string(kStage) + ": block length " + std::to_string(block_length) +
                 " is too short (need at least 2 samples)"};
  }
  Result<FftPlan> forward = FftPlan::Create(FftKind::kRealToComplex, block_length);
  if (!forward) return Error{std::string(kStage) + ": " + forward.error()};
  Result<FftPlan> backward = FftPlan::Create(FftKind::kComplexBackward, block_length);
  if (!backward) return Error{std::string(kStage) + ": " + backward.error()};
  Envelope envelope(std::move(forward).value(), std::move(backward).value());
  envelope.block_length_ = block_length;
  return envelope;
}

Status Envelope::Run(std::span<const double> input) noexcept {
  if (Status s = dsp_detail::CheckLength(kStage, "input block", input, block_length_); !s) {
    return s;
  }
  if (Status s = dsp_detail::CheckFinite(kStage, "input block", input); !s) return s;
  std::copy(input.begin(), input.end(), forward_.real_in().begin());
  forward_.Execute();
  const std::span<const std::complex<double>> x = forward_.complex_out();
  std::span<std::complex<double>> z = backward_.complex_in();
  const std::size_t n = block_length_;
  const double scale = 1.0 / static_cast<double>(n);  // FFTW's round trip multiplies by N
  std::fill(z.begin(), z.end(), 0.0);
  z[0] = x[0] * scale;
  const std::size_t last_positive = (n - 1) / 2;  // bins 1..(N-1)/2 have a negative twin
  for (std::size_t k = 1; k <= last_positive; ++k) z[k] = x[k] * (2.0 * scale);
  if (n % 2 == 0) z[n / 2] = x[n / 2] * scale;  // Nyquist is its own twin
  backward_.Execute();
  return Status::Ok();
}

Status Envelope::ProcessAnalytic(std::span<const double> input,
                                 std::span<std::complex<double>> analytic) noexcept {
  if (Status s = dsp_detail::CheckLength(kStage, "analytic output", analytic, block_length_); !s) {
    return s;
  }
  if (Status s = Run(input); !s) return s;
  std::copy(backward_.complex_out().begin(), backward_.complex_out().end(), analytic.begin());
  return Status::Ok();
}

Status Envelope::ProcessSquared(std::span<const double> input,
                                std::span<double> squared_envelope) noexcept {
  if (Status s = dsp_detail::CheckLength(kStage, "squared-envelope output", squared_envelope,
                                         block_length_);
      !s) {
    return s;
  }
  if (Status s = Run(input); !s) return s;
  const std::span<const std::complex<double>> z = backward_.complex_out();
  for (std::size_t i = 0; i < block_length_; ++i) squared_envelope[i] = std::norm(z[i]);
  return Status::Ok();
}

}  // namespace gearpath
