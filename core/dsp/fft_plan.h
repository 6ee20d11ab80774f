// FftPlan: an RAII owner of one FFTW3 (double) plan of a fixed length and of the aligned
// buffers it runs on.
//
// Every per-block transform in core/dsp goes through one of these: the plan and its buffers
// are made once at configuration (the only place FFTW's planner runs), and Execute() is
// noexcept and allocation-free, so a block costs one fftw_execute per channel.
//
// Assumptions and choices:
// - Planning uses FFTW_ESTIMATE: planning is fast and deterministic, never touches the
//   buffers, and needs no wisdom (global state) to be reproducible. FFTW_MEASURE would find
//   plans perhaps 10-30 % faster at the sizes gearpath uses, but its planning time grows to
//   seconds at large prime-factor lengths and its choice varies run to run.
// - FFTW's planner (plan creation and destruction) is not thread safe; fft_plan.cc guards it
//   with one internal mutex. fftw_execute on a plan's own buffers is thread safe (FFTW manual,
//   "Thread safety"), so plans owned by different threads execute concurrently; one plan must
//   not be executed by two threads at once (it has one set of buffers).
// - Unnormalised transforms, FFTW sign conventions: forward X[k] = sum x[n] e^{-2 pi j k n/N},
//   backward x[n] = sum X[k] e^{+2 pi j k n/N}. Scaling is the caller's business (spectrum.h).
// - The complex-to-real transform overwrites its input buffer (FFTW's default for c2r).
#pragma once

#include <complex>
#include <cstddef>
#include <span>

#include "core/common/result.h"

namespace gearpath {

enum class FftKind {
  kRealToComplex,    // real[n] -> complex[n/2 + 1], forward
  kComplexToReal,    // complex[n/2 + 1] -> real[n], backward (Hermitian input)
  kComplexForward,   // complex[n] -> complex[n], e^{-j...}
  kComplexBackward,  // complex[n] -> complex[n], e^{+j...}
};

class FftPlan {
 public:
  // Plans a transform of `length` points (length >= 1). Fails if FFTW cannot plan it or the
  // buffers cannot be allocated; the message names the kind and the length.
  static Result<FftPlan> Create(FftKind kind, std::size_t length);

  FftPlan(FftPlan&& other) noexcept;
  FftPlan& operator=(FftPlan&& other) noexcept;
  FftPlan(const FftPlan&) = delete;
  FftPlan& operator=(const FftPlan&) = delete;
  ~FftPlan();

  FftKind kind() const noexcept { return kind_; }
  std::size_t length() const noexcept { return length_; }

  // The plan's input and output buffers. Exactly one of the real/complex pair is non-empty
  // on each side: r2c reads real_in() (n) and writes complex_out() (n/2+1); c2r reads
  // complex_in() (n/2+1) and writes real_out() (n); c2c reads complex_in() (n) and writes
  // complex_out() (n). Input and output never alias.
  std::span<double> real_in() noexcept;
  std::span<std::complex<double>> complex_in() noexcept;
  std::span<double> real_out() noexcept;
  std::span<std::complex<double>> complex_out() noexcept;

  // Runs the transform on the plan's own buffers. Thread safe across distinct plans.
  void Execute() noexcept;

 private:
  FftPlan() = default;
  void Release() noexcept;

  FftKind kind_ = FftKind::kRealToComplex;
  std::size_t length_ = 0;
  void* in_ = nullptr;    // fftw_malloc'd
  void* out_ = nullptr;   // fftw_malloc'd
  void* plan_ = nullptr;  // fftw_plan (an opaque pointer), kept as void* to keep fftw3.h private
};

}  // namespace gearpath
