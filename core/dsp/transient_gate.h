// TransientGate: finds the short transients in a block that no shaft explains (a knock, a burst
// from other machinery, an electrical spike) and estimates them, so that the synchronous
// averages can be taken without them.
//
// Why: an average of R revolutions keeps 1/R of a transient that hit one revolution, and the
// peak-sensitive indicators of its difference signal (FM4, M6A, M8A) read that remnant like a
// damaged tooth; in the healthy baseline the same remnants widen every limit and hide shallow
// faults (docs/diagnosis.md, section 13: the transient gate).
//
// Method, on the RESIDUAL of a block: the block less every shaft's periodic part
// (SubtractPeriodicPart, with each shaft's revolution-by-revolution median, which a transient in
// one revolution does not move). What is left is noise, tones of other machines, whatever
// changes from one revolution to the next, and the transients.
//   1. The residual's spectrum is whitened (unit magnitude, phase kept; Hann ramps of 16 ms at
//      the block's ends against its wrap-around): a stationary tone spreads over the block, a
//      transient stays sharp.
//   2. Windows of 2 ms whose whitened energy exceeds 12 times the median window are marked, with
//      one window before and four after; marks within the ramps are dropped.
//   3. The residual's broadband part: every bin above 3 times the median magnitude of its
//      32-bin neighbourhood (a line) clipped to that level. A marked stretch goes on while this
//      part's next window holds more than half its median window: the transient's tail, until
//      it has died into the noise.
//   4. The estimate is the broadband part on the marked stretches, ramped in and out over one
//      window (raised cosine), zero elsewhere. The caller subtracts it from the block: the
//      shafts' signals and the lines stay, the transient goes.
//
// Estimate() is noexcept and allocation-free (plans and buffers are made by Create()); one gate
// serves one thread.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "core/common/result.h"
#include "core/dsp/fft_plan.h"
#include "core/dsp/grid_resampler.h"

namespace gearpath {

class TransientGate {
 public:
  // Blocks of `block_length` samples (>= 64) at `sample_rate_hz` (finite, > 0). Plans one r2c
  // and one c2r FFT of the block's length.
  static Result<TransientGate> Create(std::size_t block_length, double sample_rate_hz);

  std::size_t window() const noexcept { return window_; }

  // Writes into `transient` the estimate of the transients in `residual` (zero outside them);
  // returns the number of samples marked (0: `transient` is all zero). Both spans hold
  // block_length values; otherwise nothing is marked. The marks do not depend on the residual's
  // scale as long as its squares and their sums stay finite: |residual| < 1e100, which holds
  // for any block of float samples (|x| < 3.5e38).
  std::size_t Estimate(std::span<const double> residual, std::span<double> transient) noexcept;

 private:
  TransientGate() = default;
  // Step 2's marks from the whitened residual (mask_ rewritten) and their count; step 3's
  // extension of them through the broadband part's tails, and the final count.
  std::size_t MarkPeaks(std::span<const double> whitened) noexcept;
  std::size_t ExtendThroughTails(std::span<const double> broadband) noexcept;

  std::size_t block_length_ = 0;
  std::size_t window_ = 0;  // samples per window (2 ms)
  std::size_t edge_ = 0;    // samples of each end ramp
  std::optional<FftPlan> forward_;
  std::optional<FftPlan> inverse_;
  std::vector<double> energies_;        // 2 x windows
  std::vector<double> magnitude_;       // |bin| of the residual's spectrum
  std::vector<double> level_;           // per 32-bin neighbourhood
  std::vector<double> neighbourhoods_;  // 32 rows: row j holds bin j of every neighbourhood
  std::vector<std::uint8_t> mask_;
  std::vector<std::uint32_t> run_;  // marked samples in a row, from the left (then the right)
};

// Where each sample of a block reads one revolution of M points: the 4-point cubic Lagrange
// stencil (cubic_interpolation.h, wrapping around the revolution) at the sample's angle. It
// depends only on the shaft's rate and the block's warp, so one plan serves every channel.
struct PeriodicReadPlan {
  std::size_t points = 0;  // M; 0 until PlanPeriodicRead() succeeds
  CubicGrid grid;          // block_length points (MakePeriodicReadPlan)
};
PeriodicReadPlan MakePeriodicReadPlan(std::size_t block_length);

// Plans reading a revolution of `points` values (a power of two >= 4, as the synchronous
// average's M) at the angle of every sample: nominal[i] x revolutions_per_sample revolutions.
// `nominal` holds each sample's uniform-angle position (InvertWarp of the block's warp,
// order_tracker.h), or is empty for a constant speed (position i). False, and the plan emptied, for
// other points or a `nominal` whose length is not the plan's.
bool PlanPeriodicRead(std::size_t points, double revolutions_per_sample,
                      std::span<const double> nominal, PeriodicReadPlan& plan) noexcept;

// signal[i] -= `average` (one revolution of plan.points values) read as planned for sample i.
// `scratch` holds plan.points + 3 values. Does nothing for spans of other sizes.
void SubtractPeriodicPart(std::span<double> signal, std::span<const double> average,
                          const PeriodicReadPlan& plan, std::span<double> scratch) noexcept;

}  // namespace gearpath
