#include "core/diagnosis/robust_baseline.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

namespace gearpath {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Acklam's rational approximation of the inverse normal CDF: a ratio of polynomials in
// (p - 1/2)^2 in the central region, in sqrt(-2 log p) in the tails.
constexpr double kA[] = {-3.969683028665376e+01, 2.209460984245205e+02,  -2.759285104469687e+02,
                         1.383577518672690e+02,  -3.066479806614716e+01, 2.506628277459239e+00};
constexpr double kB[] = {-5.447609879822406e+01, 1.615858368580409e+02, -1.556989798598866e+02,
                         6.680131188771972e+01, -1.328068155288572e+01};
constexpr double kC[] = {-7.784894002430293e-03, -3.223964580411365e-01, -2.400758277161838e+00,
                         -2.549732539343734e+00, 4.374664141464968e+00,  2.938163982698783e+00};
constexpr double kD[] = {7.784695709041462e-03, 3.224671290700398e-01, 2.445134137142996e+00,
                         3.754408661907416e+00};
constexpr double kCentral = 0.02425;  // the central formula is used for p in [this, 1 - this]

double AcklamTail(double p) {  // p < kCentral; returns a negative quantile
  const double q = std::sqrt(-2.0 * std::log(p));
  return (((((kC[0] * q + kC[1]) * q + kC[2]) * q + kC[3]) * q + kC[4]) * q + kC[5]) /
         ((((kD[0] * q + kD[1]) * q + kD[2]) * q + kD[3]) * q + 1.0);
}

// Regularised incomplete beta I_x(a, b) by its continued fraction (modified Lentz), used on
// the side where it converges fast: x < (a + 1) / (a + b + 2), else through the symmetry
// I_x(a, b) = 1 - I_{1-x}(b, a).
double BetaContinuedFraction(double a, double b, double x) {
  constexpr double kTiny = 1e-300;
  auto guard = [](double v) { return std::fabs(v) < kTiny ? kTiny : v; };
  double c = 1.0;
  double d = 1.0 / guard(1.0 - (a + b) * x / (a + 1.0));
  double h = d;
  for (int m = 1; m <= 10000; ++m) {
    const double m2 = 2.0 * m;
    double num = m * (b - m) * x / ((a + m2 - 1.0) * (a + m2));  // even step
    d = 1.0 / guard(1.0 + num * d);
    c = guard(1.0 + num / c);
    h *= d * c;
    num = -(a + m) * (a + b + m) * x / ((a + m2) * (a + m2 + 1.0));  // odd step
    d = 1.0 / guard(1.0 + num * d);
    c = guard(1.0 + num / c);
    const double step = d * c;
    h *= step;
    if (std::fabs(step - 1.0) < 1e-15) break;
  }
  return h;
}

double RegularisedBeta(double a, double b, double x) {
  if (x <= 0.0) return 0.0;
  if (x >= 1.0) return 1.0;
  const double log_front =
      std::lgamma(a + b) - std::lgamma(a) - std::lgamma(b) + a * std::log(x) + b * std::log1p(-x);
  if (x < (a + 1.0) / (a + b + 2.0)) {
    return std::exp(log_front) * BetaContinuedFraction(a, b, x) / a;
  }
  return 1.0 - std::exp(log_front) * BetaContinuedFraction(b, a, 1.0 - x) / b;
}

// P(T > t) for t >= 0, T ~ Student t with nu degrees of freedom.
double StudentUpperTail(double t, double nu) {
  return 0.5 * RegularisedBeta(0.5 * nu, 0.5, nu / (nu + t * t));
}

// Median of v (reorders v; no allocation). Even size: mean of the two middle values.
double MedianInPlace(std::span<double> v) noexcept {
  const std::size_t n = v.size();
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(n / 2);
  std::nth_element(v.begin(), mid, v.end());
  const double upper = *mid;
  if (n % 2 == 1) return upper;
  const double lower = *std::max_element(v.begin(), mid);  // everything left of mid is <= it
  return 0.5 * (lower + upper);
}

// Degrees of freedom of a standard deviation as noisy as the scale estimate from n blocks
// (header comment: asymptotic efficiency x n, small-sample corrected by simulation).
double ScaleDegreesOfFreedom(double n) noexcept {
  return ScaleIsQn(static_cast<int>(n)) ? 0.8227 * n - 2.5 : 0.3675 * (n + 2.0);
}

bool FiniteAndNonNegative(double v) { return std::isfinite(v) && v >= 0.0; }
bool FiniteAndPositive(double v) { return std::isfinite(v) && v > 0.0; }

std::string ValidateCommon(int blocks, std::size_t indicators, double relative_floor,
                           double absolute_floor, double log_value_floor) {
  if (indicators == 0) return "robust baseline: indicators must be >= 1, got 0";
  if (blocks < 3) {
    return "robust baseline: blocks must be >= 3 so a median resists an outlier, got " +
           std::to_string(blocks);
  }
  if (!FiniteAndNonNegative(relative_floor)) {
    return "robust baseline: relative_floor must be finite and >= 0, got " +
           std::to_string(relative_floor);
  }
  if (!FiniteAndPositive(absolute_floor)) {
    return "robust baseline: absolute_floor must be finite and > 0, got " +
           std::to_string(absolute_floor);
  }
  if (!FiniteAndPositive(log_value_floor)) {
    return "robust baseline: log_value_floor must be finite and > 0, got " +
           std::to_string(log_value_floor);
  }
  return {};
}

}  // namespace

double InverseNormalCdf(double p) noexcept {
  if (!(p > 0.0 && p < 1.0)) return kNaN;
  double x;
  if (p < kCentral) {
    x = AcklamTail(p);
  } else if (p > 1.0 - kCentral) {
    x = -AcklamTail(1.0 - p);
  } else {
    const double q = p - 0.5;
    const double r = q * q;
    x = (((((kA[0] * r + kA[1]) * r + kA[2]) * r + kA[3]) * r + kA[4]) * r + kA[5]) * q /
        (((((kB[0] * r + kB[1]) * r + kB[2]) * r + kB[3]) * r + kB[4]) * r + 1.0);
  }
  // One Halley step on e(x) = F(x) - p, F(x) = erfc(-x / sqrt 2) / 2, takes the 1e-9 relative
  // error of the approximation to near machine precision. In the upper tail the same residual
  // is written as (1 - p) - (1 - F(x)), so F(x) near 1 does not cancel.
  const double e = x > 0.0 ? (1.0 - p) - 0.5 * std::erfc(x / std::numbers::sqrt2)
                           : 0.5 * std::erfc(-x / std::numbers::sqrt2) - p;
  const double u = e * std::sqrt(2.0 * std::numbers::pi) * std::exp(0.5 * x * x);  // e / pdf
  return x - u / (1.0 + 0.5 * x * u);
}

double StudentTQuantile(double p, double dof) noexcept {
  if (!(p > 0.0 && p < 1.0) || !(dof > 0.0) || std::isnan(dof)) return kNaN;
  if (p == 0.5) return 0.0;
  if (dof > 1e7) return InverseNormalCdf(p);  // |t - z| < 1e-6 for the tails used here
  const double tail = p > 0.5 ? 1.0 - p : p;
  // The t quantile lies beyond the normal one; bracket it, then bisect to full precision.
  double lo = std::max(0.0, -InverseNormalCdf(tail) * 0.999);
  double hi = std::max(1.0, 2.0 * lo);
  while (StudentUpperTail(hi, dof) > tail && hi < 1e300) hi *= 2.0;
  for (int i = 0; i < 200 && hi - lo > 1e-15 * hi; ++i) {
    const double mid = 0.5 * (lo + hi);
    if (StudentUpperTail(mid, dof) > tail) {
      lo = mid;
    } else {
      hi = mid;
    }
  }
  const double t = 0.5 * (lo + hi);
  return p > 0.5 ? t : -t;
}

double QnScale(std::span<const double> v, std::span<double> pairs) noexcept {
  const std::size_t n = v.size();
  if (n < 2 || pairs.size() < n * (n - 1) / 2) return 0.0;
  std::size_t p = 0;
  for (std::size_t i = 0; i + 1 < n; ++i) {
    for (std::size_t j = i + 1; j < n; ++j) pairs[p++] = std::fabs(v[i] - v[j]);
  }
  const std::size_t h = n / 2 + 1;
  const std::size_t k = h * (h - 1) / 2;  // 1-based rank of the order statistic
  const auto kth = pairs.begin() + static_cast<std::ptrdiff_t>(k - 1);
  std::nth_element(pairs.begin(), kth, pairs.begin() + static_cast<std::ptrdiff_t>(p));
  const double nd = static_cast<double>(n);
  const double small_sample = n % 2 == 0 ? nd / (nd + 3.8) : nd / (nd + 1.4);
  return kQnToSigma * small_sample * *kth;
}

Result<RobustBaseline> RobustBaseline::Create(std::size_t indicators,
                                              const RobustBaselineOptions& options) {
  if (std::string e = ValidateCommon(options.blocks, indicators, options.relative_floor,
                                     options.absolute_floor, options.log_value_floor);
      !e.empty()) {
    return Error{std::move(e)};
  }
  if (!options.log_transform.empty() && options.log_transform.size() != indicators) {
    return Error{"robust baseline: log_transform must be empty or have one flag per indicator (" +
                 std::to_string(indicators) + "), got " +
                 std::to_string(options.log_transform.size())};
  }
  if (!options.floor_power.empty() && options.floor_power.size() != indicators) {
    return Error{"robust baseline: floor_power must be empty or have one power per indicator (" +
                 std::to_string(indicators) + "), got " +
                 std::to_string(options.floor_power.size())};
  }
  for (double power : options.floor_power) {
    if (!(power >= 1.0) || !std::isfinite(power)) {
      return Error{"robust baseline: floor_power values must be finite and >= 1, got " +
                   std::to_string(power)};
    }
  }
  if (!(options.tail_z >= 0.0) || !std::isfinite(options.tail_z)) {
    return Error{"robust baseline: tail_z must be finite and >= 0 (0 = off), got " +
                 std::to_string(options.tail_z)};
  }
  RobustBaseline b;
  b.indicators_ = indicators;
  b.blocks_ = options.blocks;
  b.tail_z_ = options.tail_z;
  b.relative_floor_ = options.relative_floor;
  b.floor_power_ = options.floor_power;
  b.absolute_floor_ = options.absolute_floor;
  b.log_value_floor_ = options.log_value_floor;
  b.log_.assign(indicators, 0);
  for (std::size_t i = 0; i < options.log_transform.size(); ++i) {
    b.log_[i] = options.log_transform[i] ? 1 : 0;
  }
  b.samples_.assign(static_cast<std::size_t>(options.blocks) * indicators, 0.0);
  b.scratch_.assign(static_cast<std::size_t>(options.blocks), 0.0);
  if (ScaleIsQn(options.blocks)) {
    const auto n = static_cast<std::size_t>(options.blocks);
    b.pairs_.assign(n * (n - 1) / 2, 0.0);
  }
  b.median_.assign(indicators, 0.0);
  b.scale_.assign(indicators, 0.0);
  return b;
}

Result<RobustBaseline> RobustBaseline::FromState(const RobustBaselineState& state) {
  if (state.indicators < 0) {
    return Error{"robust baseline state: indicators must be >= 1, got " +
                 std::to_string(state.indicators)};
  }
  const auto k = static_cast<std::size_t>(state.indicators);
  if (std::string e = ValidateCommon(state.blocks, k, state.relative_floor, state.absolute_floor,
                                     state.log_value_floor);
      !e.empty()) {
    return Error{"robust baseline state: " + e.substr(std::string("robust baseline: ").size())};
  }
  auto size_error = [&](const char* field, std::size_t want, std::size_t got) {
    return Error{std::string("robust baseline state: ") + field + " must have " +
                 std::to_string(want) + " entries, got " + std::to_string(got)};
  };
  if (state.count < 0 || state.count > state.blocks) {
    return Error{"robust baseline state: count must be in [0, blocks = " +
                 std::to_string(state.blocks) + "], got " + std::to_string(state.count)};
  }
  if (state.skipped < 0) {
    return Error{"robust baseline state: skipped must be >= 0, got " +
                 std::to_string(state.skipped)};
  }
  if (state.median.size() != k) return size_error("median", k, state.median.size());
  if (state.scale.size() != k) return size_error("scale", k, state.scale.size());
  if (state.log_transform.size() != k) {
    return size_error("log_transform", k, state.log_transform.size());
  }
  const bool learned = state.count == state.blocks;
  const std::size_t want_samples = learned ? 0 : static_cast<std::size_t>(state.count) * k;
  if (state.samples.size() != want_samples) {
    return size_error("samples (count x indicators while learning, none once learned)",
                      want_samples, state.samples.size());
  }
  for (std::size_t i = 0; i < state.samples.size(); ++i) {
    if (!std::isfinite(state.samples[i])) {
      return Error{"robust baseline state: samples[" + std::to_string(i) + "] is not finite"};
    }
  }
  if (learned) {
    for (std::size_t i = 0; i < k; ++i) {
      if (!std::isfinite(state.median[i])) {
        return Error{"robust baseline state: median[" + std::to_string(i) + "] is not finite"};
      }
      if (!FiniteAndPositive(state.scale[i])) {
        return Error{"robust baseline state: scale[" + std::to_string(i) +
                     "] must be finite and > 0, got " + std::to_string(state.scale[i])};
      }
    }
  }
  RobustBaselineOptions options;
  options.blocks = state.blocks;
  options.relative_floor = state.relative_floor;
  options.absolute_floor = state.absolute_floor;
  options.log_value_floor = state.log_value_floor;
  options.log_transform = state.log_transform;
  Result<RobustBaseline> made = Create(k, options);
  if (!made.ok()) return made;
  RobustBaseline& b = made.value();
  b.count_ = state.count;
  b.skipped_ = state.skipped;
  std::copy(state.samples.begin(), state.samples.end(), b.samples_.begin());
  if (learned) {
    std::copy(state.median.begin(), state.median.end(), b.median_.begin());
    std::copy(state.scale.begin(), state.scale.end(), b.scale_.begin());
  }
  return made;
}

RobustBaselineState RobustBaseline::State() const {
  RobustBaselineState s;
  s.blocks = blocks_;
  s.indicators = static_cast<int>(indicators_);
  s.count = count_;
  s.skipped = skipped_;
  s.relative_floor = relative_floor_;
  s.absolute_floor = absolute_floor_;
  s.log_value_floor = log_value_floor_;
  s.median = median_;
  s.scale = scale_;
  s.log_transform.assign(indicators_, false);
  for (std::size_t i = 0; i < indicators_; ++i) s.log_transform[i] = log_[i] != 0;
  if (!learned()) {
    s.samples.assign(samples_.begin(),
                     samples_.begin() + static_cast<std::ptrdiff_t>(count_ * indicators_));
  }
  return s;
}

bool RobustBaseline::Add(std::span<const double> values) noexcept {
  if (learned()) return false;
  if (values.size() != indicators_) {
    ++skipped_;
    return false;
  }
  for (double v : values) {
    if (!std::isfinite(v)) {
      ++skipped_;
      return false;
    }
  }
  std::copy(values.begin(), values.end(),
            samples_.begin() + static_cast<std::ptrdiff_t>(count_ * indicators_));
  ++count_;
  if (learned()) Finalise();
  return true;
}

double RobustBaseline::Transform(std::size_t i, double x) const noexcept {
  return log_[i] != 0 ? std::log(std::max(x, log_value_floor_)) : x;
}

void RobustBaseline::Finalise() noexcept {
  const auto n = static_cast<std::size_t>(blocks_);
  for (std::size_t i = 0; i < indicators_; ++i) {
    for (std::size_t b = 0; b < n; ++b) scratch_[b] = Transform(i, samples_[b * indicators_ + i]);
    // Qn first: MedianInPlace reorders the values, which Qn does not mind.
    const double qn = pairs_.empty() ? 0.0 : QnScale(scratch_, pairs_);
    const double median = MedianInPlace(scratch_);
    double largest = 0.0;
    for (double& v : scratch_) {
      v = std::fabs(v - median);
      largest = std::max(largest, v);
    }
    const double sigma = pairs_.empty() ? kMadToSigma * MedianInPlace(scratch_) : qn;
    const double tail = tail_z_ > 0.0 ? largest / tail_z_ : 0.0;
    const double power = floor_power_.empty() ? 1.0 : floor_power_[i];
    const double relative = log_[i] != 0 ? power * std::log1p(relative_floor_)  // x (1 + r)^power
                                         : relative_floor_ * std::fabs(median);
    median_[i] = median;
    scale_[i] = std::max({sigma, relative, absolute_floor_, tail});
  }
}

int RobustBaseline::ZScores(std::span<const double> values, std::span<double> z) const noexcept {
  if (!learned() || values.size() != indicators_ || z.size() != indicators_) {
    std::fill(z.begin(), z.end(), 0.0);
    return -1;
  }
  int non_finite = 0;
  for (std::size_t i = 0; i < indicators_; ++i) {
    if (!std::isfinite(values[i])) {
      z[i] = 0.0;
      ++non_finite;
      continue;
    }
    z[i] = (Transform(i, values[i]) - median_[i]) / scale_[i];
  }
  return non_finite;
}

double RobustBaseline::ZForFalseAlarmRate(double per_block_rate, int tests, int baseline_blocks,
                                          int window_blocks) noexcept {
  if (!(per_block_rate > 0.0 && per_block_rate < 1.0) || tests < 1 || baseline_blocks < 0 ||
      baseline_blocks == 1 || baseline_blocks == 2 || window_blocks < 1) {
    return kNaN;
  }
  const double alpha = per_block_rate / tests;  // per-test two-sided tail (Bonferroni)
  const double p = 1.0 - 0.5 * alpha;
  if (baseline_blocks == 0) return InverseNormalCdf(p);
  const double n = baseline_blocks;
  return std::sqrt(1.0 + window_blocks * std::numbers::pi / (2.0 * n)) *
         StudentTQuantile(p, ScaleDegreesOfFreedom(n));
}

double RobustBaseline::ValueAtZ(std::size_t i, double z) const noexcept {
  if (i >= indicators_ || !learned()) return kNaN;
  const double y = median_[i] + z * scale_[i];
  return log_[i] != 0 ? std::exp(y) : y;
}

void RobustBaseline::Reset() noexcept {
  count_ = 0;
  skipped_ = 0;
  std::fill(samples_.begin(), samples_.end(), 0.0);
  std::fill(median_.begin(), median_.end(), 0.0);
  std::fill(scale_.begin(), scale_.end(), 0.0);
}

}  // namespace gearpath
