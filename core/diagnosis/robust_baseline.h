// RobustBaseline: a per-machine healthy baseline of K indicators judged by robust z-scores,
// with the threshold chosen from a stated false-alarm rate per block.
//
// Learning. The first N accepted blocks are assumed healthy (the daemon says so and offers a
// reset). Per indicator k the location and scale are
//   m_k = median(x_k),   s_k = max(sigma_hat(x_k), relative_floor |m_k|, absolute_floor),
// both with a breakdown point of 50 %: a minority of outlying blocks cannot drag them, where
// the mean and standard deviation are dragged by one bad block. sigma_hat is
//  - for kQnMinBlocks <= N <= kQnMaxBlocks: Rousseeuw and Croux's Qn, d_N x 2.2219 x the
//    C(h, 2)-th smallest of the N (N - 1) / 2 pairwise distances |x_i - x_j|, h = N/2 + 1
//    (integer division), d_N = N / (N + 3.8) for even N and N / (N + 1.4) for odd N (their
//    small-sample factors; Monte Carlo here: mean within 1 % of sigma at N = 20 and 50). Its
//    Gaussian efficiency is 82 % (asymptotic; ~70 % at N = 20) against the MAD's 37 %: the
//    same robustness with half the scale noise, which is a z limit ~25 % lower for the same
//    false-alarm rate at N = 20 (8.1 -> 6.1 for K = 200 indicators);
//  - otherwise 1.4826 MAD, MAD = median |x - m| (1.4826 = 1/Phi^-1(3/4) makes it estimate
//    sigma for Gaussian data): Qn's small-sample factors are tabulated only from N = 10, and
//    its N^2 / 2 pairs are not worth their memory where N is large and the MAD's noise small.
// The floors keep a near-constant indicator (a deterministic simulation, a quantised feature)
// from getting a scale near zero and therefore huge scores for tiny changes.
// Positive, scale-like indicators (energies, RMS, line amplitudes) vary multiplicatively; with
// the per-indicator log flag the indicator is judged on y = log(max(x, log_value_floor)). On
// that scale a relative change of r is an absolute change of log(1 + r), so the relative floor
// becomes s_k >= log(1 + relative_floor) (the absolute floor still applies).
//
// Score: z_k = (y_k - m_k) / s_k, signed (y = x, or log x for log indicators).
//
// Threshold from a target false-alarm rate. A healthy block raises an alarm if any of the K
// tests has |z| > Z, so with a per-block rate R the per-test two-sided tail is alpha = R / K
// (Bonferroni: P(any) <= sum of P(each), exact to first order for small R, conservative for
// correlated indicators). For known location and scale Z = Phi^-1(1 - alpha/2). With m and s
// estimated from N blocks the score is wider than N(0, 1):
//  - the median's own variance: Var(m) ~ (pi/2) sigma^2 / N, so y - m has variance
//    sigma^2 (1 + pi / (2N));
//  - the scale is itself noisy, as noisy as a standard deviation from nu degrees of freedom,
//    and divides the score like the chi in a Student-t, so the quantile is a t quantile.
// Hence
//   Z = sqrt(1 + pi / (2N)) * t_nu^-1(1 - alpha/2),
//   nu = 0.8227 N - 2.5 (Qn)   or   nu = 0.3675 (N + 2) (MAD).
// 0.8227 and 0.3675 are the estimators' asymptotic Gaussian efficiencies; the offsets are
// small-sample corrections fitted by simulation (Gaussian indicators, N = 20 and 50, K = 20 to
// 80; Qn reproduced the 1 % rate with nu = 14.0 at N = 20 and nu = 39 at N = 50, i.e. 0.70 N
// and 0.78 N, while the MAD's fitted nu was 0.40 N and 0.38 N). Realised rates for a 1 % target
// (the Monte Carlo test below; 20 000 baselines each for the MAD): Qn with its nu 0.98-1.07 %;
// the MAD with its nu 0.99-1.05 %, with nu = 0.3675 N alone 0.60-0.93 %; a Student t with N - 1
// dof 3.2-13 %; the plain normal quantile 5.6 % (N = 50, K = 20) to 40 % (N = 20, K = 80). The
// stated rate is the average over healthy baselines: a given machine's rate depends on how its
// N blocks fell.
// The Student-t quantile is computed from the regularised incomplete beta function (continued
// fraction) and the inverse normal from Acklam's rational approximation refined by one Halley
// step (within 1e-10 of the exact quantile wherever p itself is representable to that level).
#pragma once

#include <cstddef>
#include <span>
#include <vector>

#include "core/common/result.h"

namespace gearpath {

// 1 / Phi^-1(0.75): MAD x this estimates sigma for Gaussian data.
inline constexpr double kMadToSigma = 1.4826;
// Qn's asymptotic consistency factor for Gaussian data (Rousseeuw and Croux 1993).
inline constexpr double kQnToSigma = 2.2219;
// Baseline sizes whose scale is Qn (else the MAD); see the header comment.
inline constexpr int kQnMinBlocks = 10;
inline constexpr int kQnMaxBlocks = 256;
constexpr bool ScaleIsQn(int blocks) noexcept {
  return blocks >= kQnMinBlocks && blocks <= kQnMaxBlocks;
}

// Qn scale estimate of v (sigma for Gaussian data, small-sample factor included), v.size() in
// [2, ...]; `pairs` must hold v.size() (v.size() - 1) / 2 values (overwritten). No allocation.
double QnScale(std::span<const double> v, std::span<double> pairs) noexcept;

// Inverse standard normal CDF, p in (0, 1); NaN outside. Acklam's rational approximation
// (relative error 1.15e-9) refined by one Halley step on erfc.
double InverseNormalCdf(double p) noexcept;
// Quantile of Student's t with `dof` > 0 degrees of freedom (not necessarily an integer),
// p in (0, 1); NaN outside. Bisection on the regularised incomplete beta function.
double StudentTQuantile(double p, double dof) noexcept;

struct RobustBaselineOptions {
  int blocks = 50;                // N healthy blocks to learn from (>= 3, so a median resists one)
  double relative_floor = 0.05;   // scale >= this x |median| (>= 0; log: >= log(1 + this))
  double absolute_floor = 1e-12;  // scale >= this (> 0)
  double log_value_floor = 1e-300;  // log indicators take log(max(x, this)) (> 0)
  // Per indicator: judge on log(x). Empty = no indicator on a log scale; else size K.
  std::vector<bool> log_transform;
  // Per indicator on a log scale: the power of the signal's amplitude it goes with (an energy
  // 2), so that its relative floor is the amplitude's: log(1 + relative_floor) x the power.
  // Empty = 1 for every indicator; else size K, each finite and >= 1.
  std::vector<double> floor_power;
  // Tail guard (0 = off): the scale is also at least max_b |y_b - m| / tail_z over the N
  // baseline blocks, so no healthy baseline block would have scored above tail_z. The MAD
  // ignores a minority of outlying blocks, which is right for the location and wrong for the
  // tail of an indicator that is heavy-tailed when healthy (a 6th or 8th moment in a plant
  // with broadband bursts); Gaussian indicators are untouched (their largest of N = 20
  // deviations is about 2 sigma).
  double tail_z = 0.0;
};

// Everything needed to resume a baseline after a restart (written to disk elsewhere).
struct RobustBaselineState {
  int blocks = 0;      // N
  int indicators = 0;  // K
  int count = 0;       // blocks accepted so far; == blocks once learned
  int skipped = 0;     // blocks skipped (non-finite value or wrong size)
  double relative_floor = 0.0;
  double absolute_floor = 0.0;
  double log_value_floor = 0.0;
  std::vector<double> median;       // K; on the log scale for log indicators; 0 while learning
  std::vector<double> scale;        // K; likewise
  std::vector<bool> log_transform;  // K
  // While learning: the count x K values as added (block-major). Empty once learned.
  std::vector<double> samples;
};

class RobustBaseline {
 public:
  static Result<RobustBaseline> Create(std::size_t indicators,
                                       const RobustBaselineOptions& options);
  // Validates sizes, ranges and finiteness; messages name the offending field.
  static Result<RobustBaseline> FromState(const RobustBaselineState& state);
  RobustBaselineState State() const;

  // Adds one healthy block (size K). A block with a non-finite value or the wrong size is
  // skipped and counted; after N accepted blocks the location and scale are fixed and further
  // blocks are ignored. Returns true when the block was accepted. noexcept, no allocation.
  bool Add(std::span<const double> values) noexcept;

  // z_k = (y_k - median_k) / scale_k for each indicator (y = x or log x). A non-finite value
  // gets z = 0 and is counted in the return value. If not learned yet, or a size differs from
  // K, every z is set to 0 and -1 is returned. noexcept, no allocation.
  int ZScores(std::span<const double> values, std::span<double> z) const noexcept;

  // Threshold on |z| for a target rate of healthy blocks with any |z| > Z (header comment):
  // Z = sqrt(1 + pi/(2N)) t_nu^-1(1 - R/(2 K)), nu of the scale estimator used for N blocks
  // (0.8227 N - 2.5 for Qn, 0.3675 (N + 2) for the MAD); baseline_blocks = 0 means
  // location and scale known exactly (Z = Phi^-1(1 - R/(2K))). NaN for R outside (0, 1),
  // tests < 1 or baseline_blocks in {1, 2} or negative.
  // window_blocks = W > 1: the limit on a sum of W blocks' z divided by sqrt(W). The blocks'
  // own noise averages out, the baseline median's error does not (every block shares it), so
  // the factor becomes sqrt(1 + W pi/(2N)). NaN for W < 1.
  static double ZForFalseAlarmRate(double per_block_rate, int tests, int baseline_blocks,
                                   int window_blocks = 1) noexcept;

  // The indicator value at which indicator i scores z (in the indicator's own units, i.e.
  // exp(...) for log indicators): a threshold to publish next to the raw indicator.
  double ValueAtZ(std::size_t i, double z) const noexcept;

  bool learned() const noexcept { return count_ >= blocks_; }
  int blocks_seen() const noexcept { return count_; }
  int blocks_needed() const noexcept { return blocks_; }
  int skipped_blocks() const noexcept { return skipped_; }
  std::size_t indicators() const noexcept { return indicators_; }
  bool log_transform(std::size_t i) const noexcept { return i < log_.size() && log_[i] != 0; }
  // Location and scale per indicator (log scale for log indicators); zeros while learning.
  std::span<const double> median() const noexcept { return median_; }
  std::span<const double> scale() const noexcept { return scale_; }

  void Reset() noexcept;  // forgets everything learned and learns again from the next block

  // The tail guard (RobustBaselineOptions::tail_z) for a baseline resumed with FromState()
  // (it applies when learning completes; 0 = off).
  void set_tail_z(double tail_z) noexcept { tail_z_ = tail_z > 0.0 ? tail_z : 0.0; }
  double tail_z() const noexcept { return tail_z_; }
  // Likewise RobustBaselineOptions::floor_power (ignored unless empty or of size K; allocates).
  void set_floor_power(std::span<const double> power) {
    if (power.empty() || power.size() == indicators_) floor_power_.assign(power.begin(), power.end());
  }
  std::span<const double> floor_power() const noexcept { return floor_power_; }

 private:
  RobustBaseline() = default;
  double Transform(std::size_t i, double x) const noexcept;
  void Finalise() noexcept;

  std::size_t indicators_ = 0;
  int blocks_ = 0;
  int count_ = 0;
  int skipped_ = 0;
  double relative_floor_ = 0.0;
  std::vector<double> floor_power_;  // empty: 1 each
  double absolute_floor_ = 0.0;
  double log_value_floor_ = 0.0;
  double tail_z_ = 0.0;
  std::vector<unsigned char> log_;  // per indicator, 0/1
  std::vector<double> samples_;     // N x K, block-major
  std::vector<double> scratch_;     // N
  std::vector<double> pairs_;       // N (N - 1) / 2 when the scale is Qn, else empty
  std::vector<double> median_;      // K
  std::vector<double> scale_;       // K
};

}  // namespace gearpath
