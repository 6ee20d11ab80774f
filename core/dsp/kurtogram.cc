#include "core/dsp/kurtogram.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <utility>

#include "core/common/simd_clones.h"
#include "core/dsp/input_checks.h"

namespace gearpath {
namespace {

constexpr const char* kStage = "kurtogram";
constexpr int kMaxDepth = 12;

// The smallest 2^a or 3 x 2^a >= n. A band's moments are exact at any length of at least twice
// its bins (kurtogram.h), so the length is free; a power of two alone would be up to twice as
// long, and the ternary rows' bands (a third of the bins) are where that bites: 5334 -> 6144
// points, not 8192.
std::size_t NextFftLength(std::size_t n) {
  std::size_t two = 1;
  while (two < n) two <<= 1;
  std::size_t three = 3;
  while (three < n) three <<= 1;
  return std::min(two, three);
}

// Lags handled together by Autocorrelation (one vector of doubles on AVX-512).
constexpr std::size_t kLagGroup = 8;

// sum[lag] = sum_{i = lag}^{n-1} h[i] h[i - lag] for lag = 0..max_lag, with rev[k] = h[n-1-k].
// kLagGroup lags at a time: for each i, h[i] times kLagGroup consecutive values of rev, so the
// compiler vectorises across lags while every lag's sum still runs over i in increasing order
// (the same rounding as one lag at a time).
GEARPATH_SIMD_CLONES
void Autocorrelation(const double* __restrict h, const double* __restrict rev, std::size_t n,
                     std::size_t max_lag, double* __restrict sum) noexcept {
  for (std::size_t lag0 = 0; lag0 <= max_lag; lag0 += kLagGroup) {
    const std::size_t lags = std::min(kLagGroup, max_lag + 1 - lag0);
    double acc[kLagGroup] = {};
    // The first kLagGroup - 1 samples, where the larger lags of the group have no partner yet.
    const std::size_t head = std::min(n, lag0 + kLagGroup - 1);
    for (std::size_t i = lag0; i < head; ++i) {
      for (std::size_t l = 0; l < lags && lag0 + l <= i; ++l) acc[l] += h[i] * h[i - lag0 - l];
    }
    for (std::size_t i = head; i < n; ++i) {
      const double hi = h[i];
      const double* partner = rev + (n - 1 - i + lag0);  // partner[l] = h[i - lag0 - l]
      for (std::size_t l = 0; l < kLagGroup; ++l) acc[l] += hi * partner[l];
    }
    for (std::size_t l = 0; l < lags; ++l) sum[lag0 + l] = acc[l];
  }
}

// Lanes of PowerMoments' partial sums.
constexpr std::size_t kMomentLanes = 8;

// m2 = sum |c|^2 and m4 = sum |c|^4 over n complex values c (interleaved re, im), in
// kMomentLanes interleaved partial sums added at the end: element-wise work the compiler
// vectorises (the order of the sum differs from one running sum by rounding only).
GEARPATH_SIMD_CLONES
void PowerMoments(const double* __restrict c, std::size_t n, double* m2, double* m4) noexcept {
  double s2[kMomentLanes] = {};
  double s4[kMomentLanes] = {};
  std::size_t i = 0;
  for (; i + kMomentLanes <= n; i += kMomentLanes) {
    for (std::size_t l = 0; l < kMomentLanes; ++l) {
      const double re = c[2 * (i + l)];
      const double im = c[2 * (i + l) + 1];
      const double p = re * re + im * im;
      s2[l] += p;
      s4[l] += p * p;
    }
  }
  double a2 = 0.0;
  double a4 = 0.0;
  for (std::size_t l = 0; l < kMomentLanes; ++l) {
    a2 += s2[l];
    a4 += s4[l];
  }
  for (; i < n; ++i) {
    const double p = c[2 * i] * c[2 * i] + c[2 * i + 1] * c[2 * i + 1];
    a2 += p;
    a4 += p * p;
  }
  *m2 = a2;
  *m4 = a4;
}

// Samples the FIR filter handles together (two kB, in L1).
constexpr std::size_t kFirBlock = 256;

// out[i] = sum_{j=0}^{order} a[j] h[first + i - j] for i < count (first >= order): coefficient
// by coefficient over a block of outputs, so the compiler vectorises across outputs while each
// output still sums j = 0, 1, ..., order in that order.
GEARPATH_SIMD_CLONES
void PredictionError(const double* __restrict a, std::size_t order, const double* __restrict h,
                     std::size_t first, std::size_t count, double* __restrict out) noexcept {
  std::size_t i0 = 0;
  for (; i0 + kFirBlock <= count; i0 += kFirBlock) {
    double* o = out + i0;
    for (std::size_t t = 0; t < kFirBlock; ++t) o[t] = 0.0;
    for (std::size_t j = 0; j <= order; ++j) {
      const double aj = a[j];
      const double* src = h + first + i0 - j;
      for (std::size_t t = 0; t < kFirBlock; ++t) o[t] += aj * src[t];
    }
  }
  for (std::size_t i = i0; i < count; ++i) {
    double e = 0.0;
    for (std::size_t j = 0; j <= order; ++j) e += a[j] * h[first + i - j];
    out[i] = e;
  }
}

}  // namespace

double KurtogramNode::DisplayLevel() const noexcept {
  return ternary ? level + std::log2(3.0) - 1.0 : static_cast<double>(level);
}

Result<Kurtogram> Kurtogram::Create(std::size_t block_length, double sample_rate_hz,
                                    const KurtogramOptions& options) {
  const std::string stage = kStage;
  if (!std::isfinite(sample_rate_hz) || sample_rate_hz <= 0.0) {
    return Error{stage + ": sample rate " + std::to_string(sample_rate_hz) +
                 " Hz must be finite and positive"};
  }
  if (options.depth < 0 || options.depth > kMaxDepth) {
    return Error{stage + ": depth " + std::to_string(options.depth) + " is outside 0.." +
                 std::to_string(kMaxDepth)};
  }
  if (!std::isfinite(options.min_bandwidth_hz) || options.min_bandwidth_hz < 0.0 ||
      options.min_bandwidth_hz > sample_rate_hz / 2.0) {
    return Error{stage + ": min_bandwidth_hz " + std::to_string(options.min_bandwidth_hz) +
                 " must be in [0, fs/2 = " + std::to_string(sample_rate_hz / 2.0) + "] Hz"};
  }
  if (!std::isfinite(options.significance_sigmas) || options.significance_sigmas < 0.0) {
    return Error{stage + ": significance_sigmas " + std::to_string(options.significance_sigmas) +
                 " must be finite and non-negative"};
  }
  if (options.whitening == KurtogramWhitening::kAutoregressive &&
      (options.ar_order < 1 || static_cast<std::size_t>(options.ar_order) > block_length / 4)) {
    return Error{stage + ": ar_order " + std::to_string(options.ar_order) +
                 " must be in 1..block_length/4 = " + std::to_string(block_length / 4)};
  }
  if (!std::isfinite(options.taper_fraction) || options.taper_fraction < 0.0 ||
      options.taper_fraction > 1.0) {
    return Error{stage + ": taper_fraction " + std::to_string(options.taper_fraction) +
                 " must be in [0, 1]"};
  }
  const std::size_t positive_bins = block_length / 2;  // bins 1..N/2 (floor)
  if (positive_bins < kMinBinsPerBand) {
    return Error{stage + ": block length " + std::to_string(block_length) +
                 " is too short (level 0 needs at least " + std::to_string(kMinBinsPerBand) +
                 " positive-frequency bins)"};
  }

  Result<FftPlan> forward = FftPlan::Create(FftKind::kRealToComplex, block_length);
  if (!forward) return Error{stage + ": " + forward.error()};
  Kurtogram k(std::move(forward).value());
  k.block_length_ = block_length;
  k.sample_rate_hz_ = sample_rate_hz;
  k.options_ = options;

  // Rows in order of decreasing bandwidth: 0, 1, 1.6, 2, 2.6, ..., depth.
  std::vector<KurtogramNode> candidates{{0, false, 0}};
  for (int level = 1; level <= options.depth; ++level) {
    candidates.push_back({level, false, 0});
    if (level < options.depth) candidates.push_back({level, true, 0});
  }
  std::vector<std::size_t> plan_sizes;
  for (const KurtogramNode& node : candidates) {
    const int bands = node.BandCount();
    const double bandwidth = sample_rate_hz / (2.0 * bands);
    std::size_t narrowest = positive_bins;
    std::size_t widest = 0;
    for (int i = 0; i < bands; ++i) {
      const std::size_t first = k.BandFirstBin(bands, i);
      const std::size_t end = k.BandFirstBin(bands, i + 1);
      narrowest = std::min(narrowest, end - first);
      widest = std::max(widest, end - first);
    }
    // Rows only get narrower: the first row that fails ends the tree.
    if (bandwidth < options.min_bandwidth_hz || narrowest < kMinBinsPerBand) break;
    const std::size_t size = NextFftLength(2 * widest);
    auto found = std::find(plan_sizes.begin(), plan_sizes.end(), size);
    Row row{node, static_cast<std::size_t>(found - plan_sizes.begin())};
    if (found == plan_sizes.end()) {
      Result<FftPlan> plan = FftPlan::Create(FftKind::kComplexBackward, size);
      if (!plan) return Error{stage + ": " + plan.error()};
      k.envelope_plans_.push_back(std::move(plan).value());
      plan_sizes.push_back(size);
    }
    k.rows_.push_back(row);
    k.max_bands_ = std::max(k.max_bands_, static_cast<std::size_t>(bands));
  }
  // The plans' input buffers are uninitialised: all of each may hold anything.
  for (const FftPlan& plan : k.envelope_plans_) k.plan_written_.push_back(plan.length());
  if (k.rows_.empty()) {
    return Error{stage + ": min_bandwidth_hz " + std::to_string(options.min_bandwidth_hz) +
                 " leaves no level (level 0 is " + std::to_string(sample_rate_hz / 2.0) + " Hz)"};
  }
  // Tukey window: cosine tapers over taper_fraction * N / 2 samples at each end.
  k.taper_.assign(block_length, 1.0);
  const auto taper_length =
      static_cast<std::size_t>(options.taper_fraction * static_cast<double>(block_length) / 2.0);
  for (std::size_t i = 0; i < taper_length; ++i) {
    const double w = 0.5 * (1.0 - std::cos(std::numbers::pi * (static_cast<double>(i) + 0.5) /
                                           static_cast<double>(taper_length)));
    k.taper_[i] = w;
    k.taper_[block_length - 1 - i] = w;
  }
  double w2 = 0.0;
  double w4 = 0.0;
  for (double w : k.taper_) {
    w2 += w * w;
    w4 += w * w * w * w;
  }
  const double nb = static_cast<double>(block_length);
  k.taper_ratio_ = (w4 / nb) / ((w2 / nb) * (w2 / nb));
  if (options.whitening == KurtogramWhitening::kAutoregressive) {
    k.ar_work_.assign(3 * (static_cast<std::size_t>(options.ar_order) + 1), 0.0);
    k.history_.assign(2 * block_length, 0.0);  // the block, then reversed
  }
  k.map_.assign(k.rows_.size() * k.max_bands_, std::numeric_limits<double>::quiet_NaN());
  for (std::size_t r = 0; r < k.rows_.size(); ++r) {
    const std::size_t bands = static_cast<std::size_t>(k.rows_[r].node.BandCount());
    std::fill_n(k.map_.begin() + static_cast<std::ptrdiff_t>(r * k.max_bands_), bands, 0.0);
  }
  return k;
}

// First bin of band `index` of `bands`: the smallest k >= 1 with floor(2 bands k / N) >= index;
// for index == bands, one past the last positive-frequency bin.
std::size_t Kurtogram::BandFirstBin(int bands, int index) const noexcept {
  const std::size_t last = block_length_ / 2;
  if (index >= bands) return last + 1;
  const std::size_t l2 = 2 * static_cast<std::size_t>(bands);
  const std::size_t k = (static_cast<std::size_t>(index) * block_length_ + l2 - 1) / l2;
  return std::max<std::size_t>(k, 1);
}

double Kurtogram::BandKurtosis(std::size_t plan_index, std::size_t first_bin,
                               std::size_t end_bin) noexcept {
  FftPlan& plan = envelope_plans_[plan_index];
  std::span<std::complex<double>> in = plan.complex_in();
  const std::span<const std::complex<double>> spectrum = forward_.complex_out();
  // Baseband shift: bin first_bin goes to 0. A frequency shift multiplies c(t) by a unit
  // phasor, so |c| and the kurtosis are unchanged. The zero padding: an out-of-place complex
  // FFT keeps its input, so only what the previous band wrote past this one's bins is zeroed.
  const std::size_t count = end_bin - first_bin;
  std::copy_n(spectrum.begin() + static_cast<std::ptrdiff_t>(first_bin), count, in.begin());
  std::size_t& written = plan_written_[plan_index];
  if (written > count) {
    std::fill(in.begin() + static_cast<std::ptrdiff_t>(count),
              in.begin() + static_cast<std::ptrdiff_t>(written), 0.0);
  }
  written = count;
  plan.Execute();
  const std::span<const std::complex<double>> out = plan.complex_out();
  double m2 = 0.0;
  double m4 = 0.0;
  PowerMoments(reinterpret_cast<const double*>(out.data()), out.size(), &m2, &m4);
  if (!(m2 > 0.0)) return 0.0;  // a silent band: no evidence either way
  const double m = static_cast<double>(in.size());
  const double tapered = (m4 / m) / ((m2 / m) * (m2 / m));  // SK + 2 of the tapered block
  return tapered / taper_ratio_ - 2.0;                      // undo the taper (see header)
}

void Kurtogram::Whiten() noexcept {
  std::span<double> x = forward_.real_in();
  const std::size_t n = block_length_;
  // history_: the block, then the block reversed (Autocorrelation's partner reads).
  double* h = history_.data();
  double* rev = h + n;
  std::copy(x.begin(), x.end(), h);
  std::reverse_copy(x.begin(), x.end(), rev);
  const auto p = static_cast<std::size_t>(options_.ar_order);
  double* r = ar_work_.data();
  double* a = r + (p + 1);
  double* scratch = a + (p + 1);
  // Biased autocorrelation: its Toeplitz matrix is positive semi-definite, so Levinson-Durbin
  // yields a minimum-phase (stable) predictor.
  Autocorrelation(h, rev, n, p, r);
  for (std::size_t lag = 0; lag <= p; ++lag) r[lag] /= static_cast<double>(n);
  if (!(r[0] > 0.0)) return;  // silent block: nothing to whiten
  // A 1e-9 diagonal load keeps the recursion regular for noise-free tones.
  double error = r[0] * (1.0 + 1e-9);
  std::fill(a, a + p + 1, 0.0);
  a[0] = 1.0;
  for (std::size_t i = 1; i <= p; ++i) {
    double acc = r[i];
    for (std::size_t j = 1; j < i; ++j) acc += a[j] * r[i - j];
    const double reflection = -acc / error;
    for (std::size_t j = 1; j < i; ++j) scratch[j] = a[j] + reflection * a[i - j];
    std::copy(scratch + 1, scratch + i, a + 1);
    a[i] = reflection;
    error *= 1.0 - reflection * reflection;
    if (!(error > 0.0)) break;  // perfectly predictable: keep the predictor found so far
  }
  // Prediction error e[i] = sum_j a[j] x[i - j]; the first p samples lack history.
  std::fill(x.begin(), x.begin() + static_cast<std::ptrdiff_t>(p), 0.0);
  PredictionError(a, p, h, p, n - p, x.data() + p);
}

Result<KurtogramBand> Kurtogram::Process(std::span<const double> block) noexcept {
  if (Status s = dsp_detail::CheckLength(kStage, "block", block, block_length_); !s) {
    return Error{s.error()};
  }
  if (Status s = dsp_detail::CheckFinite(kStage, "block", block); !s) return Error{s.error()};

  std::span<double> x = forward_.real_in();
  double mean = 0.0;
  for (double v : block) mean += v;
  mean /= static_cast<double>(block_length_);
  for (std::size_t i = 0; i < block_length_; ++i) x[i] = block[i] - mean;
  if (options_.whitening == KurtogramWhitening::kAutoregressive) Whiten();
  for (std::size_t i = 0; i < block_length_; ++i) x[i] *= taper_[i];
  forward_.Execute();
  forward_.complex_out()[0] = 0.0;  // the (tapered) mean carries no transient

  KurtogramNode best{0, false, 0};
  double best_kurtosis = -std::numeric_limits<double>::infinity();
  for (std::size_t r = 0; r < rows_.size(); ++r) {
    const KurtogramNode row = rows_[r].node;
    const int bands = row.BandCount();
    double* out = map_.data() + r * max_bands_;
    for (int i = 0; i < bands; ++i) {
      const double sk =
          BandKurtosis(rows_[r].plan, BandFirstBin(bands, i), BandFirstBin(bands, i + 1));
      out[i] = sk;
      if (sk > best_kurtosis) {  // strict: ties keep the wider (earlier) band
        best_kurtosis = sk;
        best = {row.level, row.ternary, i};
      }
    }
  }
  return Band(best);
}

double Kurtogram::row_bandwidth_hz(std::size_t row) const noexcept {
  return sample_rate_hz_ / (2.0 * rows_[row].node.BandCount());
}

std::span<const double> Kurtogram::map_row(std::size_t row) const noexcept {
  return {map_.data() + row * max_bands_, static_cast<std::size_t>(rows_[row].node.BandCount())};
}

KurtogramBand Kurtogram::Band(const KurtogramNode& node) const noexcept {
  KurtogramBand band;
  band.node = node;
  const int bands = node.BandCount();
  band.bandwidth_hz = sample_rate_hz_ / (2.0 * bands);
  band.low_hz = node.index * band.bandwidth_hz;
  band.high_hz = band.low_hz + band.bandwidth_hz;
  band.centre_hz = band.low_hz + 0.5 * band.bandwidth_hz;
  const std::size_t bins = BandFirstBin(bands, node.index + 1) - BandFirstBin(bands, node.index);
  band.sigma = 2.0 / std::sqrt(static_cast<double>(bins));
  for (std::size_t r = 0; r < rows_.size(); ++r) {
    if (rows_[r].node.level == node.level && rows_[r].node.ternary == node.ternary &&
        node.index >= 0 && node.index < bands) {
      band.kurtosis = map_[r * max_bands_ + static_cast<std::size_t>(node.index)];
    }
  }
  band.significant = band.kurtosis > options_.significance_sigmas * band.sigma;
  return band;
}

}  // namespace gearpath
