// OrderTracker: tacho-less order tracking of one block from a mesh tone (Bonnardot, Antoni,
// Randall & El Badaoui 2005, "Use of the acceleration signal of a gearbox in order to perform
// angular resampling"; Randall 2011, Sect. 3.6.2).
//
// Why. A block's speed_hz is its MEAN speed. A speed that moves by a fraction e within the block
// shifts the angle of a shaft by up to ~e x revolutions / (2 pi); at a mesh of z teeth the mesh
// phase moves z times as much, so a drift of 0.3 % over 20 revolutions of a 30-tooth gear (about
// 1 rad of mesh phase) already smears the mesh harmonics of a synchronous average, and with them
// every indicator that separates regular from residual orders.
//
// Method. The output is a WARP: warp[i] = the (fractional) sample position at which the
// machine has turned as far as it turns in i samples at the mean speed, so reading a signal at
// warp[i] gives it at uniform shaft angle (every shaft of a rigid train at once). Starting from
// warp = identity, each iteration
//   1. reads the reference signal at the warp (cubic Lagrange, cubic_interpolation.h),
//   2. keeps the bins of the carrier (a mesh tone at its nominal frequency f_c) within
//      +/- half_band_hz, shifted down to 0 Hz: the complex envelope of the carrier,
//   3. unwraps its phase, the carrier's phase error delta(i) (rad) against uniform rotation,
//   4. fits it with a polynomial of degree `degree` (weighted by the envelope's power, the
//      first and last `edge_fraction` of the block left out: a narrow band's edges ring), and
//   5. moves the warp by the fitted angle error: warp(i) <- warp(i - delta(i) fs / (2 pi f_c)).
// The band decides what is tracked: with half_band_hz below the slowest shaft rate, the
// shaft-rate sidebands of a tooth fault (its modulation) stay outside, so the tracker follows
// the speed, not the fault. A narrow band also under-reads a wide frequency modulation, which
// the iterations correct: each one leaves a smaller residual modulation for the next.
// The constant phase is dropped (angle zero stays at sample 0). By default (keep_mean_speed)
// the fit is constrained to end where it starts, so the tracked mean speed is the nominal one:
// a block's speed_hz is its mean speed, and a band narrow enough to keep a fault's sidebands
// out also cuts off part of a drift's FM sidebands, unevenly where the transfer adds AM, which
// a free fit reads as a mean speed off by up to 0.2 % (17 samples over an 8192-sample block
// on the evaluation's lumped plants, docs/diagnosis.md section 9a).
//
// Accuracy (tests/core/dsp/order_tracker_test.cc, 1-s blocks at 8 kHz, 300 Hz carrier): a
// +/- 0.3 % sinusoidal drift (+/- 4 samples of angle) is tracked to within 0.06 samples of the
// analytic warp with 5 % noise; at constant speed with 30 % noise the warp stays within 0.15
// samples of the identity (0.1 rad at a 900 Hz harmonic). It does not check that the carrier
// is the only line in its band: another line there beats with it and is tracked as speed, so
// the caller should keep a warp only when it makes the synchronous average more coherent, or
// compare several carriers' phase residuals (TryTrack).
//
// Track() is noexcept and allocation-free (plans and buffers are made by Create()); one tracker
// must not be run by two threads at once.
#pragma once

#include <complex>
#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "core/common/result.h"
#include "core/dsp/fft_plan.h"
#include "core/dsp/grid_resampler.h"

namespace gearpath {

// Raised whenever the warps the tracker makes change (2: the mean speed kept, 2026-11-28), so
// that a baseline averaged at another revision's angle is not judged against this one's
// (core/pipeline/learned_state.cc puts it in the fingerprint of a tracking machine).
inline constexpr int kOrderTrackerRevision = 2;

struct OrderTrackerOptions {
  int iterations = 3;           // 1..8
  int degree = 6;               // polynomial degree of the phase error, 1..kMaxDegree
  double edge_fraction = 0.05;  // each end of the block left out of the fit, [0, 0.3]
  // The tracked mean speed is the nominal one (the carrier's mean frequency is carrier_hz);
  // false lets the fit correct a nominal speed that is slightly off.
  bool keep_mean_speed = true;
  // Tracking fails (the caller keeps constant speed) when the band's mean power per bin is
  // under this multiple of the median power per bin beside the band (no carrier), ...
  double min_carrier_to_floor = 10.0;
  // ... or when the weighted RMS of the phase about
  // its fit exceeds this (rad): the carrier is too weak or not a single tone.
  double max_phase_residual_rad = 0.5;
};

struct OrderTrackResult {
  double phase_residual_rad = 0.0;  // weighted RMS of the last iteration's phase about its fit
  double max_shift_samples = 0.0;   // largest |warp[i] - i|
  double mean_speed_ratio = 1.0;    // tracked mean speed / nominal
};

class OrderTracker {
 public:
  static constexpr int kMaxDegree = 8;

  // Blocks of `block_length` (>= 64) samples at `sample_rate_hz` (finite, > 0).
  static Result<OrderTracker> Create(std::size_t block_length, double sample_rate_hz,
                                     OrderTrackerOptions options = {});

  std::size_t block_length() const noexcept { return n_; }
  const OrderTrackerOptions& options() const noexcept { return options_; }

  // Tracks the carrier at nominal frequency `carrier_hz` in `signal` (block_length samples)
  // within +/- `half_band_hz`, and writes the warp (block_length values, increasing, warp[0] =
  // 0). Fails with a message, leaving `warp` unspecified, when the band does not fit in
  // (0, fs/2) or holds fewer than 3 bins, the signal is not finite, the carrier is absent
  // (no power in the band) or too noisy (phase residual above the option), or the tracked
  // angle does not increase.
  Result<OrderTrackResult> Track(std::span<const double> signal, double carrier_hz,
                                 double half_band_hz, std::span<double> warp) noexcept;
  // Track() without the message, for a caller that tries several carriers in every block:
  // nullopt where Track() fails. For a signal of the block's length with finite samples (a
  // validated block), it allocates nothing, tracked or not.
  std::optional<OrderTrackResult> TryTrack(std::span<const double> signal, double carrier_hz,
                                           double half_band_hz, std::span<double> warp) noexcept;

 private:
  OrderTracker() = default;
  // Track() and TryTrack(): with `messages`, a failure says why (which allocates).
  Result<OrderTrackResult> Run(std::span<const double> signal, double carrier_hz,
                               double half_band_hz, std::span<double> warp, bool messages) noexcept;
  // A failure of Run(): the message `build()` makes, or none.
  template <typename Build>
  static Error Fail(bool messages, Build build) noexcept {
    return messages ? Error{build()} : Error{std::string()};
  }

  std::size_t n_ = 0;
  double fs_ = 0.0;
  OrderTrackerOptions options_;
  std::optional<FftPlan> forward_;   // r2c, n
  std::optional<FftPlan> backward_;  // c2c backward, n
  CubicGrid grid_;  // where each iteration reads the signal: the warp's stencils
  std::vector<double> phase_;
  std::vector<double> weight_;
  std::vector<double> next_;
  // P_0..P_degree at every sample, sample by sample (kMaxDegree + 1 values each, zeros past
  // the degree, so that the fit's sums load one sample's values as a vector): they depend only
  // on the block length and the degree, so they are computed once here instead of twice per
  // iteration of every Track (a chain of divisions per sample). 1.15 MB at N = 16 000.
  std::vector<double> legendre_;
};

// Most warps MedianOfWarps() combines.
inline constexpr std::size_t kMaxMedianWarps = 16;

// out[i] = the median of `count` warps at sample i (the mean of the middle two for an even
// count); `warps` holds them one after another, each out.size() long. 1 <= count <=
// kMaxMedianWarps (otherwise out is left as it is). Why: several carriers of one block each
// read the speed through their own stretch of the transfer and beside their own foreign lines,
// so each errs its own way; the median follows the ones that agree. It increases where every
// warp does. noexcept, no allocation.
void MedianOfWarps(std::span<const double> warps, std::size_t count,
                   std::span<double> out) noexcept;

// Reads a warp at a fractional position u (linear between its samples, extrapolated with the
// end slopes outside [0, n - 1]).
double WarpAt(std::span<const double> warp, double u) noexcept;

// The uniform-angle position of every sample: the inverse of a warp (warp[s] is the sample
// position of uniform position s, increasing), linear between its values and
// extrapolated with its end slopes. nominal.size() == warp.size().
void InvertWarp(std::span<const double> warp, std::span<double> nominal) noexcept;

}  // namespace gearpath
