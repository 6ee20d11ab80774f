// AntiAliasDecimator: streaming decimation by 2^K (the time-domain simulator's 64 kHz -> 8 kHz)
// with a cascade of K linear-phase FIR low-passes, each followed by taking every second sample.
//
// Stage k (input rate f_k) passes [0, f_pass] and stops [f_k / 2 - f_out / 2, f_k / 2] for the
// intermediate stages (what would fold onto the final band), [f_out / 2, f_k / 2] for the last
// one (f_out the output rate): Kaiser-windowed sinc (J. F. Kaiser, "Nonrecursive digital filter
// design using the I0-sinh window function", 1974), length from Kaiser's formula
// N = (A - 7.95) / (2.285 dw) + 1 (odd), beta = 0.1102 (A - 8.7) for A > 50, unit DC gain.
//
// Zero phase: output m of a stage is centred on its input 2m (the symmetric filter's middle
// tap), so output n of the cascade is the filtered signal at input sample 2^K n exactly: no
// delay to compensate. The price is a look-ahead: output n is ready once input
// 2^K n + lookahead() has been pushed. The inputs before the first are taken as zeros (the
// simulator's run-in absorbs that start).
#pragma once

#include <Eigen/Dense>
#include <vector>

#include "core/common/result.h"

namespace gearpath {

// Symmetric low-pass FIR of odd length, Kaiser window, unit gain at DC. cutoff in cycles per
// sample (0, 0.5).
std::vector<double> KaiserLowPass(int length, double cutoff, double beta);
// Kaiser's length (odd) and beta for attenuation_db over a transition of width_cycles
// (cycles per sample).
int KaiserLength(double attenuation_db, double width_cycles) noexcept;
double KaiserBeta(double attenuation_db) noexcept;

class AntiAliasDecimator {
 public:
  AntiAliasDecimator() = default;
  // input_rate_hz / output_rate_hz must be 2^K, K in 1..6; 0 < pass_hz < output_rate_hz / 2;
  // attenuation_db in [40, 160]; channels >= 1.
  static Result<AntiAliasDecimator> Create(double input_rate_hz, double output_rate_hz,
                                           double pass_hz, double attenuation_db, int channels);

  int factor() const noexcept { return factor_; }
  int lookahead() const noexcept { return lookahead_; }  // input samples
  int channels() const noexcept { return channels_; }
  const std::vector<double>& taps(int stage) const { return stages_[stage].taps; }
  int stage_count() const noexcept { return static_cast<int>(stages_.size()); }

  // Pushes one input frame (channels() values). Returns true when it completes an output
  // frame, written to out (channels() values). Allocation-free.
  bool Push(const double* frame, double* out) noexcept;

 private:
  struct Stage {
    std::vector<double> taps;  // odd length L, symmetric
    int half = 0;              // (L - 1) / 2
    // Per channel, the last L inputs twice (ring of length L mirrored at +L), so a window is
    // contiguous: x[pos .. pos + L) oldest first.
    std::vector<double> ring;
    int pos = 0;
    long long count = 0;  // inputs pushed
  };
  bool PushStage(int k, const double* frame, double* out) noexcept;

  int factor_ = 1;
  int channels_ = 1;
  int lookahead_ = 0;
  std::vector<Stage> stages_;
  std::vector<double> scratch_;  // per stage: channels values
};

}  // namespace gearpath
