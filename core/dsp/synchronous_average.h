// SynchronousAverage: the time-synchronous average (TSA) of one shaft over one block, and its
// order spectrum (Lebold et al. 2000, Sect. 3; Samuel & Pines 2005, Sect. 3.1; Randall 2011,
// Sect. 5.2).
//
// Method. For a shaft turning at the constant rate f (Hz) in a block of N samples at fs:
//   - M points per revolution: the smallest power of two >= fs / f (so the angular grid holds
//     every order up to the Nyquist order fs / (2 f)), at least 4, capped at the configured
//     maximum. When the cap binds (M < fs / f), orders above M / 2 present in the signal alias
//     onto lower orders: choose the cap >= fs / f of the slowest shaft, or low-pass first.
//   - R = floor((N - 1) f / fs) whole revolutions, starting at the block's first sample (angle
//     zero is the first sample: without a once-per-rev tachometer the angle origin is the
//     block's, so the TSA's phase moves from block to block; every indicator built on it is
//     phase-free).
//   - The signal is read at the times t = (r M + m) / (M f), r < R, m < M, by 4-point cubic
//     Lagrange interpolation (the stencil moves inwards at the block ends), and the R
//     revolutions are averaged point by point.
//   - Orders above the Nyquist order fs / (2 f) can only hold interpolation images, not
//     measurement: they are zeroed in the order spectrum and the TSA is rebuilt from the kept
//     orders (one inverse FFT, skipped when M / 2 <= fs / (2 f)).
//   - Order spectrum: orders 0..M/2 of the TSA, amplitude-scaled as in spectrum.h (a cosine of
//     amplitude a at order k reads a e^{j phi} at k; DC and order M/2 are real).
//
// What survives the average: components synchronous with the shaft keep their amplitude (less
// the interpolation droop below); a tone at a non-integer order k + delta is scaled by
// |sin(pi delta R) / (R sin(pi delta))| (1/R at delta = 1/2 and odd R), and broadband noise
// falls by about 1/sqrt(R) in amplitude. A slow shaft in a short block gives few revolutions,
// so the gain over noise is small (R = 20 buys only ~13 dB).
//
// Interpolation accuracy (4-point cubic Lagrange, coherent gain averaged over the fractional
// positions, tests/core/dsp/synchronous_average_test.cc): a synchronous tone at a time
// frequency of 0.05 fs loses < 0.02 %, 0.1 fs 0.2 %, 0.15 fs 1.1 %, 0.2 fs 3.3 %, 0.25 fs 7 %,
// 0.4 fs 33 %. Orders whose frequency is above ~0.15 fs are therefore under-read; the
// anti-alias filter of most acquisition chains already attenuates the top of the band.
//
// Without a warp, assumes the rate is constant over the block (speed drift smears the high
// orders first; order_tracker.h measures the drift and Process() takes its warp) and that f is
// the true rate (an error of e in f moves order k by k e R over the block).
//
// Speed (issue 9): the resampling is the cost of a block's averages (R M four-point stencils
// per signal). On a CPU with AVX-512 eight consecutive points are read from one window of 16
// samples with two loads and four permutes (at M >= fs / f consecutive points are at most one
// sample apart), instead of 32 scalar loads; the arithmetic is the scalar one, term by term, so
// both paths give the same bits.
//
// Process() is noexcept and allocation-free: the plans, buffers and outputs are made by
// Create() / MakeRecord(). One SynchronousAverage serves any number of shafts (one record each);
// it must not be run by two threads at once (it owns its scratch buffers and plans).
#pragma once

#include <complex>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "core/common/result.h"
#include "core/dsp/fft_plan.h"
#include "core/dsp/grid_resampler.h"

namespace gearpath {

// One shaft's TSA and order spectrum. Holds the storage for the largest M; Process() fills the
// first M (TSA) and M/2 + 1 (orders) values and sets the counts. Made by
// SynchronousAverage::MakeRecord() (the one allocation), reused block after block.
struct SynchronousAverageRecord {
  std::size_t points_per_revolution = 0;  // M (a power of two); 0 until the first Process()
  std::size_t revolutions = 0;            // R, whole revolutions averaged
  double shaft_hz = 0.0;                  // the rate the block was averaged at
  double nyquist_order = 0.0;             // fs / (2 f): highest order the block can hold
  std::vector<double> tsa_storage;        // capacity: max M
  std::vector<std::complex<double>> order_storage;  // capacity: max M / 2 + 1

  // The TSA, M points over one revolution (point m at angle 2 pi m / M).
  std::span<const double> tsa() const noexcept {
    return {tsa_storage.data(), points_per_revolution};
  }
  // Its order spectrum, orders 0..M/2 (amplitude-scaled; zero above nyquist_order).
  std::span<const std::complex<double>> orders() const noexcept {
    return {order_storage.data(), points_per_revolution == 0 ? 0 : points_per_revolution / 2 + 1};
  }
};

// One shaft's angular grid over one block: per point of the R M averaged, where and how to read
// the signal (cubic_interpolation.h's stencil: the first of the four samples and their
// weights), one array per field so that eight consecutive points' weights are one vector load.
// It depends only on the rate and the warp, so one plan serves every signal averaged at that
// rate in a block. Made by SynchronousAverage::MakePlan() (the one allocation), filled by Plan().
struct SynchronousAveragePlan {
  std::size_t points_per_revolution = 0;  // M; 0 until Plan() succeeds
  std::size_t revolutions = 0;            // R
  double shaft_hz = 0.0;
  double nyquist_order = 0.0;
  // Capacity 2 N > R M points (36 B per point: 1.2 MB at N = 16 000).
  CubicGrid grid;
};

// A block signal that SynchronousAverage::Check() found the right length and finite: averaging
// one signal at several rates scans it once, not once per rate. Only the stage makes one, and it
// views the caller's samples, which must not change while it is used.
class CheckedSignal {
 public:
  std::span<const double> values() const noexcept { return values_; }

 private:
  friend class SynchronousAverage;
  explicit CheckedSignal(std::span<const double> values) noexcept : values_(values) {}
  std::span<const double> values_;
};

class SynchronousAverage {
 public:
  // Whether the stage keeps a grid of its own for the one-step Process(signal, shaft_hz, ...):
  // 40 B x 2 N (0.65 MB at N = 8192). A caller that holds its own plans (MakePlan) and uses only
  // the two-step form passes kNone; the one-step Process() then refuses, as for a foreign plan.
  enum class OneStepPlan : bool { kNone, kOwn };

  // Blocks of `block_length` samples (>= 4) at `sample_rate_hz` (finite, > 0);
  // `max_points_per_revolution` is the cap on M (a power of two, 4..2^20). Plans one r2c and
  // one c2r FFT per power of two from 4 to the cap.
  static Result<SynchronousAverage> Create(std::size_t block_length, double sample_rate_hz,
                                           std::size_t max_points_per_revolution,
                                           OneStepPlan one_step = OneStepPlan::kOwn);

  std::size_t block_length() const noexcept { return block_length_; }
  double sample_rate_hz() const noexcept { return sample_rate_hz_; }
  std::size_t max_points_per_revolution() const noexcept { return max_points_; }

  // M for a shaft rate (0 for a rate that is not finite and positive).
  std::size_t PointsPerRevolution(double shaft_hz) const noexcept;
  // A record sized for this stage's cap (allocates; call at configuration).
  SynchronousAverageRecord MakeRecord() const;

  // Averages `signal` (block_length samples) over the revolutions of a shaft at `shaft_hz`.
  // `warp` (empty, or block_length increasing values from order_tracker.h) maps uniform angle to
  // time: the point at nominal sample position s is read at WarpAt(warp, s), so a speed that
  // moves within the block is averaged at true angle; revolutions whose last point the warp
  // puts past the block are dropped. Rejects a wrong length, non-finite samples, a rate that is
  // not finite and positive, a block shorter than one revolution and a record not made for this
  // stage's cap; `out` is then untouched. noexcept, no allocation on success.
  Status Process(std::span<const double> signal, double shaft_hz, SynchronousAverageRecord& out,
                 std::span<const double> warp = {}) noexcept;

  // The same in two steps, for many signals at one rate: Plan() computes the grid of a shaft
  // at `shaft_hz` (and `warp`) once, Process(signal, plan, out) averages one signal on it
  // (bit-identical to the one-step Process). Plan() rejects what Process() rejects about the
  // rate and the warp, and a plan not made by MakePlan(); noexcept, no allocation.
  SynchronousAveragePlan MakePlan() const;
  Status Plan(double shaft_hz, SynchronousAveragePlan& plan,
              std::span<const double> warp = {}) const noexcept;
  Status Process(std::span<const double> signal, const SynchronousAveragePlan& plan,
                 SynchronousAverageRecord& out) noexcept;

  // The signal checks of Process(signal, plan, out), done once: the overloads below that take
  // the result skip them (and still check the plan, the record and the spans). No allocation on
  // success.
  Result<CheckedSignal> Check(std::span<const double> signal) const noexcept;
  Status Process(const CheckedSignal& signal, const SynchronousAveragePlan& plan,
                 SynchronousAverageRecord& out) noexcept;

  // The revolutions' median, point by point (for an even R the mean of the two middle values),
  // into `median` (M values): a transient that hit one revolution does not move it (R >= 3),
  // where it moves their mean by 1/R (transient_gate.h). The grid's values, not imaged out.
  // Rejects what Process() rejects about the plan and a span of another size; noexcept, no
  // allocation.
  Status RevolutionMedian(const CheckedSignal& signal, const SynchronousAveragePlan& plan,
                          std::span<double> median) noexcept;

  // How much of each order is locked to the shaft, from each revolution's own spectrum Y_{k,r}
  // (a Hann window over the revolution, so that strong lines that are not locked, such as
  // another shaft's mesh tones or a drifting one, do not leak across the low orders; amplitude-
  // scaled like the record's orders): locked[k] = |mean_r Y_{k,r}|^2 and
  // spread[k] = mean_r |Y_{k,r} - mean_r Y_{k,r}|^2 for orders k = 0..locked.size() - 1. Noise,
  // bursts and other shafts' lines land in both (locked ~ spread / (R - 1) on average); content
  // that returns every revolution lands in `locked` only. Costs R FFTs of M points. Rejects what
  // Process() rejects, spans of different sizes and more than M/2 + 1 orders; noexcept, no
  // allocation.
  Status RevolutionSpread(std::span<const double> signal, const SynchronousAveragePlan& plan,
                          std::span<double> locked, std::span<double> spread) noexcept;

  // Process(signal, plan, out) and RevolutionSpread(signal, plan, locked, spread) from one
  // angular resampling (each revolution, resampled once, is added to the average and
  // windowed for its spectrum): bit-identical to the two calls at about half the resampling.
  // Rejects what either rejects; noexcept, no allocation.
  Status ProcessWithSpread(std::span<const double> signal, const SynchronousAveragePlan& plan,
                           SynchronousAverageRecord& out, std::span<double> locked,
                           std::span<double> spread) noexcept;
  Status ProcessWithSpread(const CheckedSignal& signal, const SynchronousAveragePlan& plan,
                           SynchronousAverageRecord& out, std::span<double> locked,
                           std::span<double> spread) noexcept;

 private:
  SynchronousAverage() = default;

  std::size_t block_length_ = 0;
  double sample_rate_hz_ = 0.0;
  std::size_t max_points_ = 0;
  // forward_[i], inverse_[i]: plans of 4 << i points.
  std::vector<FftPlan> forward_;
  std::vector<FftPlan> inverse_;
  SynchronousAveragePlan plan_;  // the one-step Process()'s grid (empty with OneStepPlan::kNone)
  std::vector<double> hann_;     // periodic Hann windows of 4, 8, ..., max M points, end to end
  std::vector<std::complex<double>> mean_scratch_;  // max M / 2 + 1
  std::vector<double> average_scratch_;             // max M: ProcessWithSpread's sum
  std::vector<double> grid_scratch_;    // 2 N > R M: RevolutionMedian's resampled revolutions

  // Input checks shared by the two-step Process, RevolutionSpread and ProcessWithSpread (the
  // signal's are Check(): once per call, or once for all rates).
  static Status CheckPlan(const SynchronousAveragePlan& plan) noexcept;
  Status CheckRecord(const SynchronousAverageRecord& out) const noexcept;
  Status CheckSpreadSpans(const SynchronousAveragePlan& plan, std::span<const double> locked,
                          std::span<const double> spread) const noexcept;
  // The average (summed in the forward plan's input) scaled, transformed and imaged out.
  void FinishAverage(const SynchronousAveragePlan& plan, SynchronousAverageRecord& out) noexcept;
  void Spread(std::span<const double> signal, const SynchronousAveragePlan& plan,
              std::span<double> locked, std::span<double> spread, double* average) noexcept;
};

}  // namespace gearpath
