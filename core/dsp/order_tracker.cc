#include "core/dsp/order_tracker.h"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <string>
#include <utility>

#include "core/common/simd_clones.h"
#include "core/dsp/input_checks.h"
#include "core/dsp/phase_angles.h"

namespace gearpath {
namespace {

constexpr const char* kStage = "order tracker";
constexpr double kTwoPi = 2.0 * std::numbers::pi;
constexpr int kBasis = OrderTracker::kMaxDegree + 1;
constexpr std::size_t kFloorBins = 64;
using Normal = Eigen::Matrix<double, kBasis, kBasis>;
using Vector = Eigen::Matrix<double, kBasis, 1>;

// Legendre polynomials P_0..P_degree at sample i of a block whose last sample is `last`, at
// x = 2 i / last - 1 in [-1, 1] (well conditioned normal equations), by their three-term
// recurrence: p[k] = P_k.
void Legendre(std::size_t i, double last, int degree, double* p) noexcept {
  p[0] = 1.0;
  if (degree < 1) return;
  p[1] = 2.0 * static_cast<double>(i) / last - 1.0;
  for (int k = 1; k < degree; ++k) {
    p[k + 1] = ((2.0 * k + 1.0) * p[1] * p[k] - k * p[k - 1]) / (k + 1.0);
  }
}

// The weighted fit's sums over a block, sample by sample in the block's order, for the samples
// whose weight is not zero: column b < terms of `normal` (kBasis x kBasis, column-major) gains
// (w P_b) P_a in every row a, `rhs` gains (w y) P_a, and the weights' sum is returned.
// `legendre` holds P_0..P_8 of each sample (kBasis values, zeros past `terms`). Each entry adds
// its terms in the order of a scalar loop over the samples; the rows a >= b of those columns
// are the ones the fit reads (the others hold the same products in the other order, or zeros).
// Why a kernel: within one sample the rows of a column are independent, which the wide-vector
// clones take eight at a time, and every clone rounds as the baseline one (simd_clones.h);
// entry by entry this loop was a third of a Track().
GEARPATH_SIMD_CLONES
double AccumulateFit(const double* __restrict legendre, const double* __restrict weight,
                     const double* __restrict phase, std::size_t n, int terms,
                     double* __restrict normal, double* __restrict rhs) noexcept {
  static_assert(kBasis == 9, "rows 0..7 as one vector, row 8 on its own");
  const auto rows = static_cast<std::size_t>(terms);
  double weight_sum = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double w = weight[i];
    if (w == 0.0) continue;
    const double* q = legendre + i * kBasis;
    for (std::size_t b = 0; b < rows; ++b) {
      const double wb = w * q[b];
      double* column = normal + b * kBasis;
      for (std::size_t a = 0; a < 8; ++a) column[a] += wb * q[a];
      column[8] += wb * q[8];
    }
    const double wy = w * phase[i];
    for (std::size_t a = 0; a < 8; ++a) rhs[a] += wy * q[a];
    rhs[8] += wy * q[8];
    weight_sum += w;
  }
  return weight_sum;
}

std::string Hz(double v) { return std::to_string(v) + " Hz"; }

}  // namespace

double WarpAt(std::span<const double> warp, double u) noexcept {
  const std::size_t n = warp.size();
  if (n < 2) return u;
  if (u <= 0.0) return warp[0] + u * (warp[1] - warp[0]);
  const double last = static_cast<double>(n - 1);
  if (u >= last) return warp[n - 1] + (u - last) * (warp[n - 1] - warp[n - 2]);
  const auto i = static_cast<std::size_t>(u);
  const double f = u - static_cast<double>(i);
  return warp[i] + f * (warp[i + 1] - warp[i]);
}

void InvertWarp(std::span<const double> warp, std::span<double> nominal) noexcept {
  const std::size_t n = std::min(warp.size(), nominal.size());
  if (n < 2) {
    for (std::size_t i = 0; i < n; ++i) nominal[i] = static_cast<double>(i);
    return;
  }
  std::size_t s = 0;  // warp[s] <= i < warp[s + 1] inside the warp's range
  for (std::size_t i = 0; i < n; ++i) {
    const double x = static_cast<double>(i);
    while (s + 2 < n && warp[s + 1] <= x) ++s;
    const double lo = warp[s];
    const double hi = warp[s + 1];
    nominal[i] = hi > lo ? static_cast<double>(s) + (x - lo) / (hi - lo) : static_cast<double>(s);
  }
}

Result<OrderTracker> OrderTracker::Create(std::size_t block_length, double sample_rate_hz,
                                          OrderTrackerOptions options) {
  const std::string what = std::string(kStage) + ": ";
  if (Status s = dsp_detail::CheckBlockShape(kStage, block_length, 64, sample_rate_hz); !s) {
    return Error{s.error()};
  }
  if (options.iterations < 1 || options.iterations > 8) {
    return Error{what + "iterations " + std::to_string(options.iterations) + " must be 1..8"};
  }
  if (options.degree < 1 || options.degree > kMaxDegree) {
    return Error{what + "degree " + std::to_string(options.degree) + " must be 1.." +
                 std::to_string(kMaxDegree)};
  }
  if (!(options.edge_fraction >= 0.0 && options.edge_fraction <= 0.3)) {
    return Error{what + "edge fraction " + std::to_string(options.edge_fraction) +
                 " must be in [0, 0.3]"};
  }
  if (!(options.min_carrier_to_floor >= 1.0)) {
    return Error{what + "min carrier to floor ratio must be at least 1"};
  }
  if (!(options.max_phase_residual_rad > 0.0)) {
    return Error{what + "max phase residual must be positive"};
  }
  OrderTracker t;
  t.n_ = block_length;
  t.fs_ = sample_rate_hz;
  t.options_ = options;
  Result<FftPlan> forward = FftPlan::Create(FftKind::kRealToComplex, block_length);
  if (!forward) return Error{what + forward.error()};
  Result<FftPlan> backward = FftPlan::Create(FftKind::kComplexBackward, block_length);
  if (!backward) return Error{what + backward.error()};
  t.forward_.emplace(std::move(forward).value());
  t.backward_.emplace(std::move(backward).value());
  t.grid_.Resize(block_length);
  t.phase_.assign(block_length, 0.0);
  t.weight_.assign(block_length, 0.0);
  t.next_.assign(block_length, 0.0);
  t.legendre_.assign(block_length * kBasis, 0.0);
  for (std::size_t i = 0; i < block_length; ++i) {
    Legendre(i, static_cast<double>(block_length - 1), options.degree,
             t.legendre_.data() + i * kBasis);
  }
  return t;
}

Result<OrderTrackResult> OrderTracker::Track(std::span<const double> signal, double carrier_hz,
                                             double half_band_hz, std::span<double> warp) noexcept {
  return Run(signal, carrier_hz, half_band_hz, warp, /*messages=*/true);
}

std::optional<OrderTrackResult> OrderTracker::TryTrack(std::span<const double> signal,
                                                       double carrier_hz, double half_band_hz,
                                                       std::span<double> warp) noexcept {
  Result<OrderTrackResult> r = Run(signal, carrier_hz, half_band_hz, warp, /*messages=*/false);
  if (!r) return std::nullopt;
  return r.value();
}

Result<OrderTrackResult> OrderTracker::Run(std::span<const double> signal, double carrier_hz,
                                           double half_band_hz, std::span<double> warp,
                                           bool messages) noexcept {
  if (Status s = dsp_detail::CheckLength(kStage, "signal", signal, n_); !s) {
    return Fail(messages, [&] { return s.error(); });
  }
  if (warp.size() != n_) {
    return Fail(messages, [&] {
      return std::string(kStage) + ": warp has " + std::to_string(warp.size()) + " values, need " +
             std::to_string(n_);
    });
  }
  const double bin_hz = fs_ / static_cast<double>(n_);
  if (!std::isfinite(carrier_hz) || !std::isfinite(half_band_hz) || half_band_hz <= 0.0 ||
      carrier_hz - half_band_hz <= 0.0 || carrier_hz + half_band_hz >= 0.5 * fs_) {
    return Fail(messages, [&] {
      return std::string(kStage) + ": band " + Hz(carrier_hz) + " +/- " + Hz(half_band_hz) +
             " does not fit in (0, " + Hz(0.5 * fs_) + ")";
    });
  }
  const auto k_lo = static_cast<std::size_t>(std::ceil((carrier_hz - half_band_hz) / bin_hz));
  const auto k_hi = static_cast<std::size_t>(std::floor((carrier_hz + half_band_hz) / bin_hz));
  if (k_hi < k_lo + 2) {
    return Fail(messages, [&] {
      return std::string(kStage) + ": band +/- " + Hz(half_band_hz) + " holds " +
             std::to_string(k_hi + 1 - std::min(k_hi + 1, k_lo)) + " bins of " + Hz(bin_hz) +
             " (need at least 3: a longer block)";
    });
  }
  if (Status s = dsp_detail::CheckFinite(kStage, "signal", signal); !s) {
    return Fail(messages, [&] { return s.error(); });
  }

  const auto k_c = static_cast<std::size_t>(std::lround(carrier_hz / bin_hz));
  // Phase slope left by demodulating at bin k_c instead of at the carrier (rad per sample).
  const double offset_slope = kTwoPi * (carrier_hz - static_cast<double>(k_c) * bin_hz) / fs_;
  const double samples_per_rad = fs_ / (kTwoPi * carrier_hz);
  const auto edge = static_cast<std::size_t>(options_.edge_fraction * static_cast<double>(n_));
  const double last = static_cast<double>(n_ - 1);
  const int degree = options_.degree;

  for (std::size_t i = 0; i < n_; ++i) warp[i] = static_cast<double>(i);
  OrderTrackResult result;
  for (int it = 0; it < options_.iterations; ++it) {
    // 1. The signal at uniform angle (as far as the warp knows it).
    std::span<double> y = forward_->real_in();
    if (it == 0) {
      // The identity warp: a cubic stencil on a whole sample is that sample, bit for bit.
      std::copy(signal.begin(), signal.end(), y.begin());
    } else {
      SetCubicStencils(n_, warp.data(), n_, grid_);  // clamped to the block
      ResampleOnGrid(signal.data(), n_, grid_.View(), 0, n_, y.data(), /*add=*/false);
    }
    forward_->Execute();
    // 2. The carrier's complex envelope: its band shifted down by k_c bins.
    const std::span<const std::complex<double>> bins = forward_->complex_out();
    std::span<std::complex<double>> in = backward_->complex_in();
    std::fill(in.begin(), in.end(), std::complex<double>{});
    double band_power = 0.0;
    for (std::size_t k = k_lo; k <= k_hi; ++k) {
      const std::size_t shifted = k >= k_c ? k - k_c : n_ - (k_c - k);
      in[shifted] = bins[k];
      band_power += std::norm(bins[k]);
    }
    if (!(band_power > 0.0)) {
      return Fail(messages, [&] {
        return std::string(kStage) + ": no power within " + Hz(carrier_hz) + " +/- " +
               Hz(half_band_hz) + " (carrier absent)";
      });
    }
    if (it == 0) {
      // The carrier must stand out of the floor beside its band (median power per bin of up
      // to kFloorBins bins on each side): noise alone has a phase too, and a smooth one.
      std::array<double, 2 * kFloorBins> floor{};
      std::size_t count = 0;
      const std::size_t width = k_hi - k_lo + 1;
      for (std::size_t j = 1; j <= std::min(kFloorBins, 3 * width); ++j) {
        if (k_lo > j) floor[count++] = std::norm(bins[k_lo - j]);
        if (k_hi + j < n_ / 2) floor[count++] = std::norm(bins[k_hi + j]);
      }
      if (count > 0) {
        const auto mid = floor.begin() + static_cast<std::ptrdiff_t>(count / 2);
        std::nth_element(floor.begin(), mid, floor.begin() + static_cast<std::ptrdiff_t>(count));
        const double per_bin = band_power / static_cast<double>(width);
        if (!(per_bin > options_.min_carrier_to_floor * *mid)) {
          return Fail(messages, [&] {
            return std::string(kStage) + ": no carrier within " + Hz(carrier_hz) + " +/- " +
                   Hz(half_band_hz) + " (band power per bin " +
                   std::to_string(*mid > 0.0 ? per_bin / *mid : 0.0) +
                   " x the floor beside it, need " + std::to_string(options_.min_carrier_to_floor) +
                   ": carrier absent)";
          });
        }
      }
    }
    backward_->Execute();
    // 3. Unwrapped phase error and its weight (envelope power, edges left out).
    const std::span<const std::complex<double>> z = backward_->complex_out();
    // The last `edge` samples weigh nothing and their phase is overwritten by the fit unread:
    // no angle for them.
    const std::size_t weighted_end = n_ - edge;
    PhaseAngles(z.first(weighted_end), std::span<double>(phase_).first(weighted_end));
    double previous = phase_[0];
    double unwrapped = previous;
    for (std::size_t i = 0; i < weighted_end; ++i) {
      const double a = phase_[i];
      double d = a - previous;
      // Under half a turn round() is 0 and d stays as it is (bit for bit): std::round is a
      // library call on baseline x86-64, and nearly every step of a tracked carrier is small.
      // A step under 3.14 rad is under half a turn however d / 2 pi rounds: no division.
      if (std::abs(d) >= 3.14) {
        const double turns = d / kTwoPi;
        if (std::abs(turns) >= 0.5) d -= kTwoPi * std::round(turns);
      }
      unwrapped += i == 0 ? 0.0 : d;
      previous = a;
      phase_[i] = unwrapped - offset_slope * static_cast<double>(i);
      weight_[i] = i < edge ? 0.0 : std::norm(z[i]);
    }
    std::fill(weight_.begin() + static_cast<std::ptrdiff_t>(weighted_end), weight_.end(), 0.0);
    // 4. Weighted least-squares Legendre fit: the normal matrix (sum of w p p^T, its lower
    // triangle) and the right-hand side over the weighted samples, on the (degree + 1)
    // polynomials only.
    Normal normal = Normal::Zero();
    Vector rhs = Vector::Zero();
    const int terms = degree + 1;
    const double weight_sum = AccumulateFit(legendre_.data(), weight_.data(), phase_.data(), n_,
                                            terms, normal.data(), rhs.data());
    if (!(weight_sum > 0.0)) {
      return Fail(messages, [&] {
        return std::string(kStage) + ": the carrier's envelope is zero inside the block";
      });
    }
    for (int k = degree + 1; k < kBasis; ++k) normal(k, k) = 1.0;
    normal = normal.selfadjointView<Eigen::Lower>();
    const auto ldlt = normal.ldlt();
    Vector coef = ldlt.solve(rhs);
    if (options_.keep_mean_speed) {
      // The fit must end where it starts, p(1) = p(-1): the odd Legendre coefficients sum to
      // zero (P_k(1) = 1, P_k(-1) = (-1)^k). Least squares under that one constraint (a
      // Lagrange multiplier): c = c0 - N^-1 a (a^T c0) / (a^T N^-1 a).
      Vector odd = Vector::Zero();
      for (int k = 1; k < terms; k += 2) odd(k) = 1.0;
      const Vector n_odd = ldlt.solve(odd);
      coef -= n_odd * (odd.dot(coef) / odd.dot(n_odd));
    }
    double residual = 0.0;
    for (std::size_t i = 0; i < n_; ++i) {
      const double* q = legendre_.data() + i * kBasis;
      double fit = 0.0;
      for (int a = 0; a < terms; ++a) fit += coef(a) * q[a];
      const double w = weight_[i];
      if (w != 0.0) residual += w * (phase_[i] - fit) * (phase_[i] - fit);
      phase_[i] = fit;
    }
    result.phase_residual_rad = std::sqrt(residual / weight_sum);
    if (!std::isfinite(result.phase_residual_rad) ||
        result.phase_residual_rad > options_.max_phase_residual_rad) {
      return Fail(messages, [&] {
        return std::string(kStage) + ": the carrier at " + Hz(carrier_hz) +
               " is too noisy to track (phase residual " +
               std::to_string(result.phase_residual_rad) + " rad, limit " +
               std::to_string(options_.max_phase_residual_rad) + ")";
      });
    }
    // 5. Move the warp by the angle error (angle zero stays at sample 0).
    const double origin = phase_[0];
    for (std::size_t i = 0; i < n_; ++i) {
      next_[i] = WarpAt(warp, static_cast<double>(i) - (phase_[i] - origin) * samples_per_rad);
    }
    for (std::size_t i = 1; i < n_; ++i) {
      if (!(next_[i] > next_[i - 1])) {
        return Fail(messages, [&] {
          return std::string(kStage) + ": the tracked angle of " + Hz(carrier_hz) +
                 " does not increase at sample " + std::to_string(i);
        });
      }
    }
    std::copy(next_.begin(), next_.end(), warp.begin());
  }
  for (std::size_t i = 0; i < n_; ++i) {
    result.max_shift_samples =
        std::max(result.max_shift_samples, std::abs(warp[i] - static_cast<double>(i)));
  }
  result.mean_speed_ratio = last / warp[n_ - 1];
  return result;
}

void MedianOfWarps(std::span<const double> warps, std::size_t count,
                   std::span<double> out) noexcept {
  const std::size_t n = out.size();
  if (count == 0 || count > kMaxMedianWarps || warps.size() < count * n) return;
  std::array<double, kMaxMedianWarps> at{};
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t k = 0; k < count; ++k) {  // insertion sort of a handful of values
      const double v = warps[k * n + i];
      std::size_t j = k;
      for (; j > 0 && at[j - 1] > v; --j) at[j] = at[j - 1];
      at[j] = v;
    }
    out[i] = count % 2 == 1 ? at[count / 2] : 0.5 * (at[count / 2 - 1] + at[count / 2]);
  }
}

}  // namespace gearpath
