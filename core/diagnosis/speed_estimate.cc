#include "core/diagnosis/speed_estimate.h"

#include <algorithm>
#include <cmath>

namespace gearpath {
namespace {

double Interpolate(std::span<const double> a, double bin) noexcept {
  if (bin < 0.0) return 0.0;
  const auto k = static_cast<std::size_t>(bin);
  if (k + 1 >= a.size()) return k < a.size() ? a[k] : 0.0;
  const double t = bin - static_cast<double>(k);
  return (1.0 - t) * a[k] + t * a[k + 1];
}

double Score(std::span<const double> a, double bin_hz, std::span<const double> orders,
             int harmonics, double f) noexcept {
  double s = 0.0;
  for (double o : orders) {
    for (int h = 1; h <= harmonics; ++h) s += Interpolate(a, h * o * f / bin_hz);
  }
  return s;
}

}  // namespace

SpeedEstimate EstimateSpeedFromMeshes(std::span<const double> amplitude, double bin_hz,
                                      std::span<const double> mesh_orders,
                                      const SpeedSearch& search) noexcept {
  SpeedEstimate out;
  if (amplitude.size() < 2 || !(bin_hz > 0.0) || mesh_orders.empty() || search.harmonics < 1 ||
      !(search.lo_hz > 0.0) || !(search.hi_hz > search.lo_hz)) {
    return out;
  }
  double max_order = 0.0;
  for (double o : mesh_orders) {
    if (!(o > 0.0) || !std::isfinite(o)) return out;
    max_order = std::max(max_order, o);
  }
  const double step = 0.25 * bin_hz / (max_order * search.harmonics);
  const auto steps = static_cast<long>(std::ceil((search.hi_hz - search.lo_hz) / step));
  if (steps < 2 || steps > 10'000'000) return out;
  double best = -1.0;
  long best_i = 0;
  double sum = 0.0;
  double prev = 0.0, before = 0.0, after = 0.0;
  for (long i = 0; i <= steps; ++i) {
    const double f = search.lo_hz + static_cast<double>(i) * step;
    const double s = Score(amplitude, bin_hz, mesh_orders, search.harmonics, f);
    sum += s;
    if (s > best) {
      best = s;
      best_i = i;
      before = prev;
    }
    prev = s;
  }
  const double f_best = search.lo_hz + static_cast<double>(best_i) * step;
  after = Score(amplitude, bin_hz, mesh_orders, search.harmonics, f_best + step);
  const double mean = sum / static_cast<double>(steps + 1);
  double f = f_best;
  if (best_i > 0 && best_i < steps) {
    const double denom = before - 2.0 * best + after;
    if (denom < 0.0) f += 0.5 * step * (before - after) / denom;
  }
  out.speed_hz = f;
  out.prominence = mean > 0.0 ? best / mean : 0.0;
  out.found = out.prominence >= search.min_prominence;
  return out;
}

}  // namespace gearpath
