#include "core/dsp/synchronous_average.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <numbers>
#include <string>
#include <utility>

#include "core/common/simd_clones.h"
#include "core/dsp/grid_resampler.h"
#include "core/dsp/input_checks.h"
#include "core/dsp/order_tracker.h"
#include "core/dsp/sorting_network.h"

namespace gearpath {
namespace {

constexpr const char* kStage = "synchronous average";
constexpr std::size_t kMinPoints = 4;
constexpr std::size_t kMaxPoints = std::size_t{1} << 20;

// Index of the plan of `points` (a power of two >= kMinPoints) in the plan vectors.
std::size_t PlanIndex(std::size_t points) noexcept {
  return static_cast<std::size_t>(std::countr_zero(points) - std::countr_zero(kMinPoints));
}

// The points [begin, begin + count) of `plan` read from x: out[m] = the point's value (or
// out[m] += it with `add`).
void Resample(const double* x, std::size_t n, const SynchronousAveragePlan& plan, std::size_t begin,
              std::size_t count, double* out, bool add) noexcept {
  ResampleOnGrid(x, n, plan.grid.View(), begin, count, out, add);
}

// mean[k] += Y_k and spread[k] += |Y_k|^2 for k < orders, Y_k = bins[k] x (edge at k = 0 and
// k = half, else interior); complex values as interleaved (re, im) doubles. Element-wise over
// the orders, which the compiler vectorises.
GEARPATH_SIMD_CLONES
void AccumulateOrders(const double* __restrict bins, std::size_t orders, std::size_t half,
                      double interior, double edge, double* __restrict mean,
                      double* __restrict spread) noexcept {
  for (std::size_t k = 0; k < orders; ++k) {
    const double scale = (k == 0 || k == half) ? edge : interior;
    const double re = bins[2 * k] * scale;
    const double im = bins[2 * k + 1] * scale;
    mean[2 * k] += re;
    mean[2 * k + 1] += im;
    spread[k] += re * re + im * im;
  }
}

}  // namespace

Result<SynchronousAverage> SynchronousAverage::Create(std::size_t block_length,
                                                      double sample_rate_hz,
                                                      std::size_t max_points_per_revolution,
                                                      OneStepPlan one_step) {
  const std::string what = std::string(kStage) + ": ";
  // Four samples: the cubic interpolator's stencil.
  if (Status s = dsp_detail::CheckBlockShape(kStage, block_length, 4, sample_rate_hz); !s) {
    return Error{s.error()};
  }
  if (max_points_per_revolution < kMinPoints || max_points_per_revolution > kMaxPoints ||
      !std::has_single_bit(max_points_per_revolution)) {
    return Error{what + "max points per revolution " + std::to_string(max_points_per_revolution) +
                 " must be a power of two between " + std::to_string(kMinPoints) + " and " +
                 std::to_string(kMaxPoints)};
  }
  SynchronousAverage stage;
  stage.block_length_ = block_length;
  stage.sample_rate_hz_ = sample_rate_hz;
  stage.max_points_ = max_points_per_revolution;
  if (one_step == OneStepPlan::kOwn) stage.plan_ = stage.MakePlan();
  // The window of M points at hann_[M - kMinPoints] (4 + 8 + ... + M / 2 = M - 4 before it).
  stage.hann_.resize(2 * max_points_per_revolution - kMinPoints);
  for (std::size_t points = kMinPoints; points <= max_points_per_revolution; points *= 2) {
    double* window = stage.hann_.data() + (points - kMinPoints);
    for (std::size_t m = 0; m < points; ++m) {
      window[m] = 0.5 - 0.5 * std::cos(2.0 * std::numbers::pi * static_cast<double>(m) /
                                       static_cast<double>(points));
    }
  }
  stage.mean_scratch_.assign(max_points_per_revolution / 2 + 1, {});
  stage.average_scratch_.assign(max_points_per_revolution, 0.0);
  stage.grid_scratch_.assign(2 * block_length, 0.0);
  for (std::size_t m = kMinPoints; m <= max_points_per_revolution; m *= 2) {
    Result<FftPlan> forward = FftPlan::Create(FftKind::kRealToComplex, m);
    if (!forward) return Error{what + forward.error()};
    Result<FftPlan> inverse = FftPlan::Create(FftKind::kComplexToReal, m);
    if (!inverse) return Error{what + inverse.error()};
    stage.forward_.push_back(std::move(forward).value());
    stage.inverse_.push_back(std::move(inverse).value());
  }
  return stage;
}

std::size_t SynchronousAverage::PointsPerRevolution(double shaft_hz) const noexcept {
  if (!std::isfinite(shaft_hz) || shaft_hz <= 0.0) return 0;
  const double samples_per_revolution = sample_rate_hz_ / shaft_hz;
  if (samples_per_revolution >= static_cast<double>(max_points_)) return max_points_;
  const auto at_least = static_cast<std::size_t>(std::ceil(samples_per_revolution));
  return std::max(kMinPoints, std::bit_ceil(at_least));
}

SynchronousAverageRecord SynchronousAverage::MakeRecord() const {
  SynchronousAverageRecord record;
  record.tsa_storage.assign(max_points_, 0.0);
  record.order_storage.assign(max_points_ / 2 + 1, 0.0);
  return record;
}

SynchronousAveragePlan SynchronousAverage::MakePlan() const {
  SynchronousAveragePlan plan;
  // R M < 2 N: M < 2 fs / f and R <= (N - 1) f / fs.
  plan.grid.Resize(2 * block_length_);
  return plan;
}

Status SynchronousAverage::Plan(double shaft_hz, SynchronousAveragePlan& plan,
                                std::span<const double> warp) const noexcept {
  plan.points_per_revolution = 0;
  if (!warp.empty() && warp.size() != block_length_) {
    return Error{std::string(kStage) + ": warp has " + std::to_string(warp.size()) +
                 " values, need " + std::to_string(block_length_) + " (or none)"};
  }
  if (!std::isfinite(shaft_hz) || shaft_hz <= 0.0) {
    return Error{std::string(kStage) + ": shaft_hz " + std::to_string(shaft_hz) +
                 " must be finite and positive"};
  }
  if (plan.grid.size() < 2 * block_length_) {
    return Error{std::string(kStage) + ": plan was not made by this stage's MakePlan()"};
  }
  const double fs = sample_rate_hz_;
  const double samples_per_revolution = fs / shaft_hz;
  // The last point read lies below R fs / f <= N - 1, inside the block.
  const double whole = std::floor(static_cast<double>(block_length_ - 1) / samples_per_revolution);
  if (whole < 1.0) {
    return Error{std::string(kStage) + ": shaft_hz " + std::to_string(shaft_hz) +
                 " gives less than one whole revolution in the block (" +
                 std::to_string(samples_per_revolution) + " samples per revolution, block of " +
                 std::to_string(block_length_) + ")"};
  }
  const std::size_t m_points = PointsPerRevolution(shaft_hz);
  const double step = samples_per_revolution / static_cast<double>(m_points);
  const double last = static_cast<double>(block_length_ - 1);
  auto revolutions = static_cast<std::size_t>(whole);
  if (!warp.empty()) {
    // A slower-than-mean stretch can push the last revolution's end past the block.
    while (revolutions > 0 &&
           !(WarpAt(warp, static_cast<double>(revolutions * m_points - 1) * step) <= last)) {
      --revolutions;
    }
    if (revolutions == 0) {
      return Error{std::string(kStage) + ": the warp leaves no whole revolution of " +
                   std::to_string(shaft_hz) + " Hz in the block"};
    }
  }
  const std::size_t points = revolutions * m_points;
  // The stencils are clamped to the block.
  SetCubicStencilsAt(block_length_, points, plan.grid, [&](std::size_t p) {
    const double at = static_cast<double>(p) * step;
    return warp.empty() ? at : WarpAt(warp, at);
  });
  plan.points_per_revolution = m_points;
  plan.revolutions = revolutions;
  plan.shaft_hz = shaft_hz;
  plan.nyquist_order = 0.5 * samples_per_revolution;
  return Status::Ok();
}

Status SynchronousAverage::Process(std::span<const double> signal, double shaft_hz,
                                   SynchronousAverageRecord& out,
                                   std::span<const double> warp) noexcept {
  if (Status s = dsp_detail::CheckLength(kStage, "signal", signal, block_length_); !s) return s;
  if (Status s = Plan(shaft_hz, plan_, warp); !s) return s;
  return Process(signal, plan_, out);
}

Status SynchronousAverage::CheckPlan(const SynchronousAveragePlan& plan) noexcept {
  if (plan.points_per_revolution == 0) {
    return Error{std::string(kStage) + ": the plan holds no grid (Plan() failed or never ran)"};
  }
  if (plan.revolutions == 0 || plan.points_per_revolution * plan.revolutions > plan.grid.size()) {
    return Error{std::string(kStage) + ": the plan's " + std::to_string(plan.revolutions) +
                 " revolutions of " + std::to_string(plan.points_per_revolution) +
                 " points do not fit its grid"};
  }
  return Status::Ok();
}

Result<CheckedSignal> SynchronousAverage::Check(std::span<const double> signal) const noexcept {
  if (Status s = dsp_detail::CheckLength(kStage, "signal", signal, block_length_); !s) {
    return Error{s.error()};
  }
  if (Status s = dsp_detail::CheckFinite(kStage, "signal", signal); !s) return Error{s.error()};
  return CheckedSignal(signal);
}

Status SynchronousAverage::CheckRecord(const SynchronousAverageRecord& out) const noexcept {
  if (out.tsa_storage.size() < max_points_ || out.order_storage.size() < max_points_ / 2 + 1) {
    return Error{std::string(kStage) +
                 ": output record was not made by this stage's MakeRecord() (storage for " +
                 std::to_string(out.tsa_storage.size()) + " points, need " +
                 std::to_string(max_points_) + ")"};
  }
  return Status::Ok();
}

Status SynchronousAverage::CheckSpreadSpans(const SynchronousAveragePlan& plan,
                                            std::span<const double> locked,
                                            std::span<const double> spread) const noexcept {
  const std::size_t half = plan.points_per_revolution / 2;
  if (locked.size() != spread.size() || locked.size() > half + 1) {
    return Error{std::string(kStage) + ": revolution spread asked for " +
                 std::to_string(locked.size()) + " and " + std::to_string(spread.size()) +
                 " orders, need equal counts of at most " + std::to_string(half + 1) +
                 " for a revolution of " + std::to_string(plan.points_per_revolution) + " points"};
  }
  return Status::Ok();
}

Status SynchronousAverage::Process(std::span<const double> signal,
                                   const SynchronousAveragePlan& plan,
                                   SynchronousAverageRecord& out) noexcept {
  const Result<CheckedSignal> checked = Check(signal);
  if (!checked.ok()) return Error{checked.error()};
  return Process(checked.value(), plan, out);
}

Status SynchronousAverage::Process(const CheckedSignal& checked, const SynchronousAveragePlan& plan,
                                   SynchronousAverageRecord& out) noexcept {
  if (Status s = CheckPlan(plan); !s) return s;
  if (Status s = CheckRecord(out); !s) return s;
  // Angular resampling and averaging, accumulated in the forward plan's input.
  const std::span<const double> signal = checked.values();
  const std::size_t m_points = plan.points_per_revolution;
  std::span<double> average = forward_[PlanIndex(m_points)].real_in();
  std::fill(average.begin(), average.end(), 0.0);
  for (std::size_t r = 0; r < plan.revolutions; ++r) {
    Resample(signal.data(), block_length_, plan, r * m_points, m_points, average.data(), true);
  }
  FinishAverage(plan, out);
  return Status::Ok();
}

void SynchronousAverage::FinishAverage(const SynchronousAveragePlan& plan,
                                       SynchronousAverageRecord& out) noexcept {
  const std::size_t m_points = plan.points_per_revolution;
  const std::size_t half = m_points / 2;
  FftPlan& forward = forward_[PlanIndex(m_points)];
  FftPlan& inverse = inverse_[PlanIndex(m_points)];
  std::span<double> average = forward.real_in();
  const double inv_r = 1.0 / static_cast<double>(plan.revolutions);
  for (double& v : average) v *= inv_r;
  std::copy(average.begin(), average.end(), out.tsa_storage.begin());

  // Order spectrum, amplitude-scaled as in spectrum.h.
  forward.Execute();
  const std::span<const std::complex<double>> bins = forward.complex_out();
  const double interior = 2.0 / static_cast<double>(m_points);
  const double edge = 1.0 / static_cast<double>(m_points);
  std::span<std::complex<double>> orders(out.order_storage.data(), half + 1);
  for (std::size_t k = 0; k <= half; ++k) orders[k] = bins[k] * interior;
  orders[0] = bins[0].real() * edge;
  orders[half] = bins[half].real() * edge;

  // Orders above the Nyquist order hold interpolation images only: zero them, rebuild the TSA.
  const double nyquist_order = plan.nyquist_order;
  if (nyquist_order < static_cast<double>(half)) {
    const auto top = static_cast<std::size_t>(std::floor(nyquist_order));
    for (std::size_t k = top + 1; k <= half; ++k) orders[k] = 0.0;
    std::span<std::complex<double>> in = inverse.complex_in();
    for (std::size_t k = 0; k <= half; ++k) in[k] = 0.5 * orders[k];
    in[0] = orders[0].real();
    in[half] = orders[half].real();
    inverse.Execute();
    const std::span<const double> rebuilt = inverse.real_out();
    std::copy(rebuilt.begin(), rebuilt.end(), out.tsa_storage.begin());
  }

  out.points_per_revolution = m_points;
  out.revolutions = plan.revolutions;
  out.shaft_hz = plan.shaft_hz;
  out.nyquist_order = nyquist_order;
}

Status SynchronousAverage::RevolutionMedian(const CheckedSignal& checked,
                                            const SynchronousAveragePlan& plan,
                                            std::span<double> median) noexcept {
  if (Status s = CheckPlan(plan); !s) return s;
  const std::size_t points = plan.points_per_revolution;
  const std::size_t revolutions = plan.revolutions;
  if (median.size() != points) {
    return Error{std::string(kStage) + ": revolution median asked for " +
                 std::to_string(median.size()) + " points, the plan has " + std::to_string(points) +
                 " per revolution"};
  }
  Resample(checked.values().data(), block_length_, plan, 0, points * revolutions,
           grid_scratch_.data(), false);
  double* rows = grid_scratch_.data();
  SortColumns(rows, revolutions, points);  // the median is then a row
  const std::size_t half = revolutions / 2;
  const double* upper = rows + half * points;
  const double* lower = rows + (half == 0 ? 0 : half - 1) * points;
  for (std::size_t m = 0; m < points; ++m) {
    median[m] = revolutions % 2 == 0 ? 0.5 * (upper[m] + lower[m]) : upper[m];
  }
  return Status::Ok();
}

Status SynchronousAverage::RevolutionSpread(std::span<const double> signal,
                                            const SynchronousAveragePlan& plan,
                                            std::span<double> locked,
                                            std::span<double> spread) noexcept {
  const Result<CheckedSignal> checked = Check(signal);
  if (!checked.ok()) return Error{checked.error()};
  if (Status s = CheckPlan(plan); !s) return s;
  if (Status s = CheckSpreadSpans(plan, locked, spread); !s) return s;
  Spread(signal, plan, locked, spread, nullptr);
  return Status::Ok();
}

Status SynchronousAverage::ProcessWithSpread(std::span<const double> signal,
                                             const SynchronousAveragePlan& plan,
                                             SynchronousAverageRecord& out,
                                             std::span<double> locked,
                                             std::span<double> spread) noexcept {
  const Result<CheckedSignal> checked = Check(signal);
  if (!checked.ok()) return Error{checked.error()};
  return ProcessWithSpread(checked.value(), plan, out, locked, spread);
}

Status SynchronousAverage::ProcessWithSpread(const CheckedSignal& checked,
                                             const SynchronousAveragePlan& plan,
                                             SynchronousAverageRecord& out,
                                             std::span<double> locked,
                                             std::span<double> spread) noexcept {
  if (Status s = CheckPlan(plan); !s) return s;
  if (Status s = CheckRecord(out); !s) return s;
  if (Status s = CheckSpreadSpans(plan, locked, spread); !s) return s;
  std::span<double> average(average_scratch_.data(), plan.points_per_revolution);
  std::fill(average.begin(), average.end(), 0.0);
  Spread(checked.values(), plan, locked, spread, average.data());
  std::span<double> in = forward_[PlanIndex(plan.points_per_revolution)].real_in();
  std::copy(average.begin(), average.end(), in.begin());
  FinishAverage(plan, out);
  return Status::Ok();
}

// RevolutionSpread()'s work; with `average`, each resampled revolution is also added to it
// before its window (the sum Process() accumulates, term for term).
void SynchronousAverage::Spread(std::span<const double> signal, const SynchronousAveragePlan& plan,
                                std::span<double> locked, std::span<double> spread,
                                double* average) noexcept {
  const std::size_t m_points = plan.points_per_revolution;
  const std::size_t half = m_points / 2;
  FftPlan& forward = forward_[PlanIndex(m_points)];
  const std::span<double> revolution = forward.real_in();
  const std::span<const std::complex<double>> bins = forward.complex_out();
  const double* window = hann_.data() + (m_points - kMinPoints);
  // Amplitude scaling of a Hann-windowed line: 2 / (M x the window's mean, 1/2).
  const double interior = 4.0 / static_cast<double>(m_points);
  const double edge = 2.0 / static_cast<double>(m_points);
  const std::size_t orders = locked.size();
  std::span<std::complex<double>> mean(mean_scratch_.data(), orders);
  std::fill(mean.begin(), mean.end(), std::complex<double>{});
  std::fill(spread.begin(), spread.end(), 0.0);
  for (std::size_t r = 0; r < plan.revolutions; ++r) {
    Resample(signal.data(), block_length_, plan, r * m_points, m_points, revolution.data(), false);
    if (average != nullptr) {
      for (std::size_t m = 0; m < m_points; ++m) average[m] += revolution[m];
    }
    for (std::size_t m = 0; m < m_points; ++m) revolution[m] *= window[m];
    forward.Execute();
    // sum of Y and of |Y|^2 for now; DC and order M/2 take the edge scaling.
    AccumulateOrders(reinterpret_cast<const double*>(bins.data()), orders, half, interior, edge,
                     reinterpret_cast<double*>(mean.data()), spread.data());
  }
  const double inv_r = 1.0 / static_cast<double>(plan.revolutions);
  for (std::size_t k = 0; k < orders; ++k) {
    mean[k] *= inv_r;
    locked[k] = std::norm(mean[k]);
    spread[k] = std::max(0.0, spread[k] * inv_r - locked[k]);
  }
}

}  // namespace gearpath
