#include "core/dsp/transient_gate.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdint>
#include <numbers>
#include <string>
#include <utility>

#include "core/common/simd_clones.h"
#include "core/dsp/grid_resampler.h"
#include "core/dsp/input_checks.h"
#include "core/dsp/sorting_network.h"

namespace gearpath {
namespace {

constexpr const char* kStage = "transient gate";
constexpr double kWindowSeconds = 2e-3;
constexpr std::size_t kEdgeWindows = 8;    // end ramps (16 ms)
constexpr double kMarkRatio = 12.0;        // whitened window energy over the median window
constexpr std::size_t kWindowsBefore = 1;  // marked before a window over the ratio
constexpr std::size_t kWindowsAfter = 4;   // and after it
constexpr std::size_t kLineBins = 32;      // neighbourhood of the broadband part's median
constexpr double kLineRatio = 3.0;         // a bin above this x the median is a line
constexpr double kTailRatio = 0.5;         // a stretch ends below this x the median window

// Raised-cosine ramp value d + 1/2 samples into a ramp of `length`.
double Ramp(std::size_t d, std::size_t length) noexcept {
  return 0.5 - 0.5 * std::cos(std::numbers::pi * (static_cast<double>(d) + 0.5) /
                              static_cast<double>(length));
}

// Energy of each whole window of `x` into energies[0, windows) and a copy into
// energies[windows, 2 windows); returns the median window's.
double WindowEnergies(std::span<const double> x, std::size_t window, std::size_t windows,
                      double* energies) noexcept {
  for (std::size_t k = 0; k < windows; ++k) {
    double e = 0.0;
    for (std::size_t i = k * window; i < (k + 1) * window; ++i) e += x[i] * x[i];
    energies[k] = e;
    energies[windows + k] = e;
  }
  double* copy = energies + windows;
  std::nth_element(copy, copy + windows / 2, copy + windows);
  return copy[windows / 2];
}

// magnitude[k] = |bins[k]|, complex values as (re, im) pairs. sqrt(re^2 + im^2), not std::abs:
// abs is hypot, a library call per bin (~1 ms per reference block) whose guard against overflow
// this domain does not need (header: |residual| < 1e100).
GEARPATH_SIMD_CLONES
void Magnitudes(const double* __restrict bins, std::size_t count,
                double* __restrict magnitude) noexcept {
  for (std::size_t k = 0; k < count; ++k) {
    const double re = bins[2 * k];
    const double im = bins[2 * k + 1];
    magnitude[k] = std::sqrt(re * re + im * im);
  }
}

// out[k] = bins[k] / magnitude[k], 0 where the magnitude is 0; complex values as (re, im)
// pairs. Without a branch, so that it vectorises: the same divisions, bit for bit.
GEARPATH_SIMD_CLONES
void DivideByMagnitudes(const double* __restrict bins, const double* __restrict magnitude,
                        std::size_t count, double* __restrict out) noexcept {
  for (std::size_t k = 0; k < count; ++k) {
    const double m = magnitude[k];
    const bool zero = !(m > 0.0);
    const double d = zero ? 1.0 : m;
    const double re = bins[2 * k] / d;
    const double im = bins[2 * k + 1] / d;
    out[2 * k] = zero ? 0.0 : re;
    out[2 * k + 1] = zero ? 0.0 : im;
  }
}

}  // namespace

Result<TransientGate> TransientGate::Create(std::size_t block_length, double sample_rate_hz) {
  if (Status s = dsp_detail::CheckBlockShape(kStage, block_length, 64, sample_rate_hz); !s) {
    return Error{s.error()};
  }
  TransientGate gate;
  gate.block_length_ = block_length;
  gate.window_ = static_cast<std::size_t>(std::clamp(std::round(kWindowSeconds * sample_rate_hz),
                                                     4.0, static_cast<double>(block_length / 16)));
  gate.edge_ = std::min(block_length / 4, kEdgeWindows * gate.window_);
  auto forward = FftPlan::Create(FftKind::kRealToComplex, block_length);
  if (!forward) return Error{std::string(kStage) + ": " + forward.error()};
  auto inverse = FftPlan::Create(FftKind::kComplexToReal, block_length);
  if (!inverse) return Error{std::string(kStage) + ": " + inverse.error()};
  gate.forward_.emplace(std::move(forward).value());
  gate.inverse_.emplace(std::move(inverse).value());
  gate.energies_.assign(2 * (block_length / gate.window_), 0.0);
  gate.magnitude_.assign(block_length / 2 + 1, 0.0);
  gate.level_.assign(block_length / 2 / kLineBins + 1, 0.0);
  gate.neighbourhoods_.assign(kLineBins * gate.level_.size(), 0.0);
  gate.mask_.assign(block_length, 0);
  gate.run_.assign(block_length, 0);
  return gate;
}

std::size_t TransientGate::Estimate(std::span<const double> residual,
                                    std::span<double> transient) noexcept {
  const std::size_t n = block_length_;
  if (residual.size() != n || transient.size() != n) return 0;
  std::fill(transient.begin(), transient.end(), 0.0);

  // 1. The whitened residual, with ramps at the ends.
  const std::span<double> in = forward_->real_in();
  std::copy(residual.begin(), residual.end(), in.begin());
  for (std::size_t i = 0; i < edge_; ++i) {
    const double ramp = Ramp(i, edge_);
    in[i] *= ramp;
    in[n - 1 - i] *= ramp;
  }
  forward_->Execute();
  const std::span<const std::complex<double>> bins = forward_->complex_out();
  const std::span<std::complex<double>> out = inverse_->complex_in();
  const std::span<const double> time = inverse_->real_out();
  // std::complex<double> is an array of (re, im) (the standard guarantees the layout).
  const auto* bin_pairs = reinterpret_cast<const double*>(bins.data());
  Magnitudes(bin_pairs, bins.size(), magnitude_.data());
  DivideByMagnitudes(bin_pairs, magnitude_.data(), bins.size(),
                     reinterpret_cast<double*>(out.data()));
  out[0] = 0.0;
  inverse_->Execute();
  // Nothing far above the median window: nothing to estimate, and the broadband part below is
  // not needed (most blocks; the stretches of step 3 only grow from marks).
  if (MarkPeaks(time) == 0) return 0;

  // 3. The broadband part: lines clipped to their neighbourhood's median magnitude (the upper
  // one of 32, the value of rank 16). Every neighbourhood is whole (block_length >= 64: 33 bins
  // or more); all are sorted at once by a network over a table with one column each.
  const std::size_t blocks = bins.size() / kLineBins;
  double* table = neighbourhoods_.data();
  for (std::size_t b = 0; b < blocks; ++b) {
    for (std::size_t j = 0; j < kLineBins; ++j) {
      table[j * blocks + b] = magnitude_[b * kLineBins + j];
    }
  }
  SortColumns(table, kLineBins, blocks);
  std::copy(table + kLineBins / 2 * blocks, table + (kLineBins / 2 + 1) * blocks, level_.begin());
  const double half_block = 0.5 * static_cast<double>(kLineBins);
  const double last_block = static_cast<double>(blocks - 1);
  const auto length = static_cast<double>(n);  // FFTW's round trip gains n
  for (std::size_t k = 0; k < bins.size(); ++k) {
    const double at =
        std::clamp((static_cast<double>(k) - half_block) / kLineBins, 0.0, last_block);
    const auto b0 = static_cast<std::size_t>(at);
    const std::size_t b1 = std::min(b0 + 1, blocks - 1);
    const double f = at - static_cast<double>(b0);
    const double line = kLineRatio * ((1.0 - f) * level_[b0] + f * level_[b1]);
    const double magnitude = magnitude_[k];
    const double gain = magnitude > line ? line / magnitude : 1.0;
    out[k] = bins[k] * (gain / length);
  }
  out[0] = 0.0;
  inverse_->Execute();  // `time` holds the broadband part from here on
  const std::size_t marked = ExtendThroughTails(time);

  // 4. The estimate: the broadband part on the marks, ramped over one window at each edge of a
  // stretch (distance to the nearest unmarked sample, from both sides).
  std::uint32_t left = 0;
  for (std::size_t i = 0; i < n; ++i) {
    left = mask_[i] ? left + 1 : 0;
    run_[i] = left;
  }
  std::uint32_t right = 0;
  for (std::size_t i = n; i-- > 0;) {
    right = mask_[i] ? right + 1 : 0;
    if (!mask_[i]) continue;
    const std::size_t d = std::min<std::size_t>(std::min(run_[i], right) - 1, window_);
    transient[i] = (d >= window_ ? 1.0 : Ramp(d, window_)) * time[i];
  }
  return marked;
}

std::size_t TransientGate::MarkPeaks(std::span<const double> whitened) noexcept {
  const std::size_t n = block_length_;
  const std::size_t w = window_;
  const std::size_t windows = n / w;
  std::fill(mask_.begin(), mask_.end(), std::uint8_t{0});
  if (windows < 3) return 0;
  double* energies = energies_.data();

  // 2. Windows far above the whitened median, with their neighbours; none within the ramps.
  const double median = WindowEnergies(whitened, w, windows, energies);
  if (!(median > 0.0)) return 0;
  for (std::size_t k = 0; k < windows; ++k) {
    if (!(energies[k] > kMarkRatio * median)) continue;
    const std::size_t from = k >= kWindowsBefore ? k - kWindowsBefore : 0;
    const std::size_t to = std::min(windows, k + kWindowsAfter + 1);
    std::fill(mask_.begin() + static_cast<long>(from * w),
              mask_.begin() + static_cast<long>(to * w), std::uint8_t{1});
  }
  for (std::size_t i = 0; i < edge_; ++i) {
    mask_[i] = 0;
    mask_[n - 1 - i] = 0;
  }
  return static_cast<std::size_t>(std::count(mask_.begin(), mask_.end(), std::uint8_t{1}));
}

std::size_t TransientGate::ExtendThroughTails(std::span<const double> broadband) noexcept {
  const std::size_t w = window_;
  const std::size_t windows = block_length_ / w;
  double* energies = energies_.data();
  // 3. Each stretch goes on through the transient's tail.
  const double tail = kTailRatio * WindowEnergies(broadband, w, windows, energies);
  for (std::size_t k = 1; k < windows; ++k) {
    if (mask_[(k - 1) * w] && !mask_[k * w] && energies[k] > tail) {
      std::fill(mask_.begin() + static_cast<long>(k * w),
                mask_.begin() + static_cast<long>((k + 1) * w), std::uint8_t{1});
    }
  }
  return static_cast<std::size_t>(std::count(mask_.begin(), mask_.end(), std::uint8_t{1}));
}

PeriodicReadPlan MakePeriodicReadPlan(std::size_t block_length) {
  PeriodicReadPlan plan;
  plan.grid.Resize(block_length);
  return plan;
}

bool PlanPeriodicRead(std::size_t points, double revolutions_per_sample,
                      std::span<const double> nominal, PeriodicReadPlan& plan) noexcept {
  plan.points = 0;
  const std::size_t n = plan.grid.size();
  if (points < 4 || (points & (points - 1)) != 0 || (!nominal.empty() && nominal.size() != n)) {
    return false;
  }
  // M is a power of two: x - M floor(x / M) is then exact (the value of fmod, plus M below
  // zero).
  const double points_per_sample = revolutions_per_sample * static_cast<double>(points);
  const double revolution = static_cast<double>(points);
  const double inv_revolution = 1.0 / revolution;
  // The stencils on SubtractPeriodicPart's scratch, which holds the revolution from its last
  // value (position 0) to its second one again (position M + 2): position pos + 1.
  SetCubicStencilsAt(points + 3, n, plan.grid, [&](std::size_t i) {
    const double s = nominal.empty() ? static_cast<double>(i) : nominal[i];
    const double x = s * points_per_sample;
    const double pos = x - revolution * std::floor(x * inv_revolution);
    return pos + 1.0;
  });
  plan.points = points;
  return true;
}

void SubtractPeriodicPart(std::span<double> signal, std::span<const double> average,
                          const PeriodicReadPlan& plan, std::span<double> scratch) noexcept {
  const std::size_t m = plan.points;
  if (m == 0 || average.size() != m || scratch.size() < m + 3 ||
      signal.size() != plan.grid.size()) {
    return;
  }
  // The revolution negated and wrapped (its last value first, its first two again at the end),
  // so that the resampler's stencils read it without a wrap and add what is to be subtracted:
  // each value is the negated stencil's, bit for bit.
  scratch[0] = -average[m - 1];
  for (std::size_t k = 0; k < m; ++k) scratch[k + 1] = -average[k];
  scratch[m + 1] = -average[0];
  scratch[m + 2] = -average[1];
  ResampleOnGrid(scratch.data(), m + 3, plan.grid.View(), 0, signal.size(), signal.data(),
                 /*add=*/true);
}

}  // namespace gearpath
