#include "core/dsp/fft_plan.h"

#include <fftw3.h>

#include <climits>
#include <mutex>
#include <string>
#include <utility>

namespace gearpath {
namespace {

// FFTW's planner keeps process-wide state (the wisdom tables, the trigonometric caches): every
// fftw_plan_* and fftw_destroy_plan call must be serialised (FFTW manual, "Thread safety").
// This mutex guards that global planner and nothing else; it is the one piece of shared state
// in core/dsp and it is never taken on the per-block path (fftw_execute needs no lock).
std::mutex& PlannerMutex() {
  static std::mutex mutex;
  return mutex;
}

const char* KindName(FftKind kind) {
  switch (kind) {
    case FftKind::kRealToComplex:
      return "real-to-complex";
    case FftKind::kComplexToReal:
      return "complex-to-real";
    case FftKind::kComplexForward:
      return "complex forward";
    case FftKind::kComplexBackward:
      return "complex backward";
  }
  return "unknown";
}

}  // namespace

Result<FftPlan> FftPlan::Create(FftKind kind, std::size_t length) {
  const std::string what =
      std::string("FFT plan (") + KindName(kind) + ", " + std::to_string(length) + " points): ";
  if (length == 0) return Error{what + "length must be at least 1"};
  if (length > static_cast<std::size_t>(INT_MAX)) return Error{what + "length exceeds INT_MAX"};

  FftPlan plan;
  plan.kind_ = kind;
  plan.length_ = length;
  const std::size_t half = length / 2 + 1;
  const std::size_t in_bytes = kind == FftKind::kRealToComplex   ? length * sizeof(double)
                               : kind == FftKind::kComplexToReal ? half * sizeof(fftw_complex)
                                                                 : length * sizeof(fftw_complex);
  const std::size_t out_bytes = kind == FftKind::kRealToComplex   ? half * sizeof(fftw_complex)
                                : kind == FftKind::kComplexToReal ? length * sizeof(double)
                                                                  : length * sizeof(fftw_complex);
  const int n = static_cast<int>(length);
  {
    std::lock_guard<std::mutex> lock(PlannerMutex());
    plan.in_ = fftw_malloc(in_bytes);
    plan.out_ = fftw_malloc(out_bytes);
    if (plan.in_ == nullptr || plan.out_ == nullptr) {
      return Error{what + "could not allocate the aligned buffers"};  // plan's dtor frees
    }
    fftw_plan p = nullptr;
    // FFTW_ESTIMATE: see the header. It never overwrites the buffers while planning.
    switch (kind) {
      case FftKind::kRealToComplex:
        p = fftw_plan_dft_r2c_1d(n, static_cast<double*>(plan.in_),
                                 static_cast<fftw_complex*>(plan.out_), FFTW_ESTIMATE);
        break;
      case FftKind::kComplexToReal:
        p = fftw_plan_dft_c2r_1d(n, static_cast<fftw_complex*>(plan.in_),
                                 static_cast<double*>(plan.out_), FFTW_ESTIMATE);
        break;
      case FftKind::kComplexForward:
      case FftKind::kComplexBackward:
        p = fftw_plan_dft_1d(
            n, static_cast<fftw_complex*>(plan.in_), static_cast<fftw_complex*>(plan.out_),
            kind == FftKind::kComplexForward ? FFTW_FORWARD : FFTW_BACKWARD, FFTW_ESTIMATE);
        break;
    }
    if (p == nullptr) return Error{what + "FFTW could not create the plan"};
    plan.plan_ = p;
  }
  // Start from zeros so a plan never exposes uninitialised memory. The output too: writing it
  // here faults its pages in now, at configuration, instead of in the plan's first Execute() on
  // the processing path (a fresh machine's first block paid ~500 page faults for them).
  for (std::complex<double>& c : plan.complex_in()) c = 0.0;
  for (double& r : plan.real_in()) r = 0.0;
  for (std::complex<double>& c : plan.complex_out()) c = 0.0;
  for (double& r : plan.real_out()) r = 0.0;
  return plan;
}

FftPlan::FftPlan(FftPlan&& other) noexcept
    : kind_(other.kind_),
      length_(std::exchange(other.length_, 0)),
      in_(std::exchange(other.in_, nullptr)),
      out_(std::exchange(other.out_, nullptr)),
      plan_(std::exchange(other.plan_, nullptr)) {}

FftPlan& FftPlan::operator=(FftPlan&& other) noexcept {
  if (this != &other) {
    Release();
    kind_ = other.kind_;
    length_ = std::exchange(other.length_, 0);
    in_ = std::exchange(other.in_, nullptr);
    out_ = std::exchange(other.out_, nullptr);
    plan_ = std::exchange(other.plan_, nullptr);
  }
  return *this;
}

FftPlan::~FftPlan() { Release(); }

void FftPlan::Release() noexcept {
  if (plan_ == nullptr && in_ == nullptr && out_ == nullptr) return;
  std::lock_guard<std::mutex> lock(PlannerMutex());
  if (plan_ != nullptr) fftw_destroy_plan(static_cast<fftw_plan>(plan_));
  fftw_free(in_);
  fftw_free(out_);
  plan_ = in_ = out_ = nullptr;
}

// fftw_complex is double[2], layout-compatible with std::complex<double> ([complex.numbers]),
// which is what FFTW's manual recommends for C++.
std::span<double> FftPlan::real_in() noexcept {
  if (kind_ != FftKind::kRealToComplex || in_ == nullptr) return {};
  return {static_cast<double*>(in_), length_};
}

std::span<std::complex<double>> FftPlan::complex_in() noexcept {
  if (kind_ == FftKind::kRealToComplex || in_ == nullptr) return {};
  return {static_cast<std::complex<double>*>(in_),
          kind_ == FftKind::kComplexToReal ? length_ / 2 + 1 : length_};
}

std::span<double> FftPlan::real_out() noexcept {
  if (kind_ != FftKind::kComplexToReal || out_ == nullptr) return {};
  return {static_cast<double*>(out_), length_};
}

std::span<std::complex<double>> FftPlan::complex_out() noexcept {
  if (kind_ == FftKind::kComplexToReal || out_ == nullptr) return {};
  return {static_cast<std::complex<double>*>(out_),
          kind_ == FftKind::kRealToComplex ? length_ / 2 + 1 : length_};
}

void FftPlan::Execute() noexcept {
  if (plan_ != nullptr) fftw_execute(static_cast<fftw_plan>(plan_));
}

}  // namespace gearpath
