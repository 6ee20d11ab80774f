#include "core/diagnosis/gear_condition_indicators.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <string>
#include <utility>

#include "core/common/simd_clones.h"

namespace gearpath {
namespace {

constexpr const char* kStage = "gear condition indicators";
constexpr std::size_t kMinPoints = 8;
constexpr std::size_t kMaxPoints = std::size_t{1} << 20;

// Role bits of an order line.
constexpr std::uint8_t kMeshLine = 1;       // a mesh harmonic h z
constexpr std::uint8_t kShaftLine = 2;      // a low shaft order 1..L
constexpr std::uint8_t kFirstSideband = 4;  // h z +/- 1

// A signal whose variance is below this fraction of the TSA's is numerically zero (rounding
// left over from removing lines): its normalised moments are reported as 0, not as the
// kurtosis of rounding noise.
constexpr double kZeroVarianceFraction = 1e-24;

std::size_t PlanIndex(std::size_t points) noexcept {
  return static_cast<std::size_t>(std::countr_zero(points) - std::countr_zero(kMinPoints));
}

// a / b, or 0 when b is not positive (documented: undefined ratios read 0, never inf/NaN).
double Ratio(double a, double b) noexcept { return b > 0.0 ? a / b : 0.0; }

struct Moments {
  double mean = 0.0;
  double m2 = 0.0;  // central moments, 1/N normalised
  double m4 = 0.0;
  double m6 = 0.0;
  double m8 = 0.0;
};

// Partial sums in eight lanes in a fixed order, added up at the end: element-wise over the lanes,
// so the compiler vectorises the sums and every clone rounds alike (simd_clones.h).
constexpr std::size_t kLanes = 8;

// The sum, least and largest value of x (n >= 1, finite).
struct SumRange {
  double sum = 0.0;
  double lo = 0.0;
  double hi = 0.0;
};

GEARPATH_SIMD_CLONES
SumRange SumAndRange(const double* __restrict x, std::size_t n) noexcept {
  double sum[kLanes] = {};
  double lo[kLanes], hi[kLanes];
  for (std::size_t k = 0; k < kLanes; ++k) lo[k] = hi[k] = x[0];
  std::size_t i = 0;
  for (; i + kLanes <= n; i += kLanes) {
    for (std::size_t k = 0; k < kLanes; ++k) {
      sum[k] += x[i + k];
      lo[k] = x[i + k] < lo[k] ? x[i + k] : lo[k];
      hi[k] = x[i + k] > hi[k] ? x[i + k] : hi[k];
    }
  }
  for (std::size_t k = 0; i < n; ++i, ++k) {
    sum[k] += x[i];
    lo[k] = x[i] < lo[k] ? x[i] : lo[k];
    hi[k] = x[i] > hi[k] ? x[i] : hi[k];
  }
  SumRange r{0.0, lo[0], hi[0]};
  for (std::size_t k = 0; k < kLanes; ++k) {
    r.sum += sum[k];
    r.lo = std::min(r.lo, lo[k]);
    r.hi = std::max(r.hi, hi[k]);
  }
  return r;
}

// The central moments 2, 4, 6, 8 about `mean` (1/N normalised), or only the second without
// `higher`.
GEARPATH_SIMD_CLONES
void CentralSums(const double* __restrict x, std::size_t n, double mean, bool higher,
                 Moments& m) noexcept {
  double s2[kLanes] = {}, s4[kLanes] = {}, s6[kLanes] = {}, s8[kLanes] = {};
  std::size_t i = 0;
  if (higher) {
    for (; i + kLanes <= n; i += kLanes) {
      for (std::size_t k = 0; k < kLanes; ++k) {
        const double d2 = (x[i + k] - mean) * (x[i + k] - mean);
        const double d4 = d2 * d2;
        s2[k] += d2;
        s4[k] += d4;
        s6[k] += d4 * d2;
        s8[k] += d4 * d4;
      }
    }
  } else {
    for (; i + kLanes <= n; i += kLanes) {
      for (std::size_t k = 0; k < kLanes; ++k) s2[k] += (x[i + k] - mean) * (x[i + k] - mean);
    }
  }
  for (std::size_t k = 0; i < n; ++i, ++k) {
    const double d2 = (x[i] - mean) * (x[i] - mean);
    const double d4 = d2 * d2;
    s2[k] += d2;
    s4[k] += d4;
    s6[k] += d4 * d2;
    s8[k] += d4 * d4;
  }
  m.m2 = m.m4 = m.m6 = m.m8 = 0.0;
  for (std::size_t k = 0; k < kLanes; ++k) {
    m.m2 += s2[k];
    m.m4 += s4[k];
    m.m6 += s6[k];
    m.m8 += s8[k];
  }
  const double inv_n = 1.0 / static_cast<double>(n);
  m.m2 *= inv_n;
  if (higher) {
    m.m4 *= inv_n;
    m.m6 *= inv_n;
    m.m8 *= inv_n;
  } else {
    m.m4 = m.m6 = m.m8 = 0.0;
  }
}

// Mean and central moments of x.
Moments CentralMoments(std::span<const double> x) noexcept {
  Moments m;
  m.mean = SumAndRange(x.data(), x.size()).sum / static_cast<double>(x.size());
  CentralSums(x.data(), x.size(), m.mean, /*higher=*/true, m);
  return m;
}

Status Reject(const std::string& message) { return Error{std::string(kStage) + ": " + message}; }

}  // namespace

int AmplitudePower(ConditionIndicator indicator) noexcept {
  switch (indicator) {
    case ConditionIndicator::kNa4:
      return 4;
    case ConditionIndicator::kMeshHarmonics:
    case ConditionIndicator::kTsaRms:
      return 1;
    default:
      return 0;
  }
}

std::string_view ConditionIndicatorName(ConditionIndicator indicator) noexcept {
  switch (indicator) {
    case ConditionIndicator::kFm0:
      return "fm0";
    case ConditionIndicator::kFm4:
      return "fm4";
    case ConditionIndicator::kNa4:
      return "na4";
    case ConditionIndicator::kM6a:
      return "m6a";
    case ConditionIndicator::kM8a:
      return "m8a";
    case ConditionIndicator::kEnergyRatio:
      return "energy_ratio";
    case ConditionIndicator::kSidebandLevel:
      return "sideband_level_factor";
    case ConditionIndicator::kMeshHarmonics:
      return "mesh_harmonics";
    case ConditionIndicator::kResidualRms:
      return "residual_rms";
    case ConditionIndicator::kResidualLowOrders:
      return "residual_low_orders";
    case ConditionIndicator::kResidualHighOrders:
      return "residual_high_orders";
    case ConditionIndicator::kTsaRms:
      return "tsa_rms";
    case ConditionIndicator::kCrestFactor:
      return "crest_factor";
    case ConditionIndicator::kSynchronousLowOrders:
      return "synchronous_low_orders";
    case ConditionIndicator::kCount:
      break;
  }
  return "unknown";
}

std::string_view ConditionIndicatorDescription(ConditionIndicator indicator) noexcept {
  switch (indicator) {
    case ConditionIndicator::kFm0:
      return "peak-to-peak of the TSA over the sum of the mesh-harmonic amplitudes (gross damage)";
    case ConditionIndicator::kFm4:
      return "kurtosis of the difference signal (3 when healthy; one or two damaged teeth)";
    case ConditionIndicator::kNa4:
      return "fourth moment of the residual over the squared healthy residual variance "
             "(damage that spreads)";
    case ConditionIndicator::kM6a:
      return "sixth moment of the difference signal over its variance cubed (15 when healthy)";
    case ConditionIndicator::kM8a:
      return "eighth moment of the difference signal over its variance to the fourth (105 when "
             "healthy)";
    case ConditionIndicator::kEnergyRatio:
      return "RMS of the difference signal over RMS of the regular signal (distributed wear)";
    case ConditionIndicator::kSidebandLevel:
      return "first sidebands of the dominant mesh over the RMS of the TSA (eccentricity, "
             "localized faults)";
    case ConditionIndicator::kMeshHarmonics:
      return "sum of the amplitudes of the mesh harmonics";
    case ConditionIndicator::kResidualRms:
      return "RMS of the residual signal over the RMS of the TSA";
    case ConditionIndicator::kResidualLowOrders:
      return "residual energy below half the lowest mesh order over the TSA energy (wide, "
             "smooth defects such as wear)";
    case ConditionIndicator::kResidualHighOrders:
      return "residual energy above the highest mesh order over the TSA energy (sharp "
             "defects)";
    case ConditionIndicator::kTsaRms:
      return "RMS of the TSA, mean removed";
    case ConditionIndicator::kCrestFactor:
      return "largest deviation of the TSA from its mean over its RMS";
    case ConditionIndicator::kSynchronousLowOrders:
      return "residual power below half the lowest mesh order that is locked to the shaft, over "
             "what its spread between revolutions leaves in a mean (~1 when healthy; wide, "
             "smooth defects such as wear; unmoved by bursts and noise)";
    case ConditionIndicator::kCount:
      break;
  }
  return "unknown";
}

std::string_view ConditionIndicatorUnit(ConditionIndicator indicator) noexcept {
  switch (indicator) {
    case ConditionIndicator::kMeshHarmonics:
    case ConditionIndicator::kTsaRms:
      return "signal";
    default:
      return "1";
  }
}

Result<GearConditionIndicators> GearConditionIndicators::Create(
    std::size_t max_points_per_revolution, const IndicatorOptions& options) {
  const std::string what = std::string(kStage) + ": ";
  if (max_points_per_revolution < kMinPoints || max_points_per_revolution > kMaxPoints ||
      !std::has_single_bit(max_points_per_revolution)) {
    return Error{what + "max points per revolution " + std::to_string(max_points_per_revolution) +
                 " must be a power of two between " + std::to_string(kMinPoints) + " and " +
                 std::to_string(kMaxPoints)};
  }
  if (options.mesh_harmonics < 0) {
    return Error{what + "mesh_harmonics " + std::to_string(options.mesh_harmonics) +
                 " must be >= 0 (0 = every harmonic)"};
  }
  if (options.low_shaft_orders < 0) {
    return Error{what + "low_shaft_orders " + std::to_string(options.low_shaft_orders) +
                 " must be >= 0"};
  }
  if (options.sideband_orders < 1) {
    return Error{what + "sideband_orders " + std::to_string(options.sideband_orders) +
                 " must be >= 1"};
  }
  GearConditionIndicators stage;
  stage.options_ = options;
  stage.max_points_ = max_points_per_revolution;
  for (std::size_t m = kMinPoints; m <= max_points_per_revolution; m *= 2) {
    Result<FftPlan> plan = FftPlan::Create(FftKind::kComplexToReal, m);
    if (!plan) return Error{what + plan.error()};
    stage.inverse_.push_back(std::move(plan).value());
  }
  stage.line_role_.assign(max_points_per_revolution / 2 + 1, 0);
  stage.sideband_of_.assign(max_points_per_revolution / 2 + 1, 0);
  return stage;
}

Status GearConditionIndicators::Compute(std::span<const double> tsa,
                                        std::span<const std::complex<double>> orders,
                                        std::span<const int> mesh_orders,
                                        double na4_reference_variance,
                                        ConditionIndicatorValues& out,
                                        const RevolutionSpreadView& spread) noexcept {
  // ---- Validation (nothing written before it passes).
  const std::size_t m_points = tsa.size();
  if (m_points < kMinPoints || m_points > max_points_ || !std::has_single_bit(m_points)) {
    return Reject("tsa has " + std::to_string(m_points) + " points, need a power of two between " +
                  std::to_string(kMinPoints) + " and " + std::to_string(max_points_));
  }
  const std::size_t half = m_points / 2;
  if (orders.size() != half + 1) {
    return Reject("orders has " + std::to_string(orders.size()) +
                  " lines, need M/2 + 1 = " + std::to_string(half + 1) + " for a tsa of " +
                  std::to_string(m_points) + " points");
  }
  if (mesh_orders.empty() || mesh_orders.size() > kMaxMeshesPerShaft) {
    return Reject("mesh_orders has " + std::to_string(mesh_orders.size()) + " entries, need 1 to " +
                  std::to_string(kMaxMeshesPerShaft));
  }
  for (std::size_t j = 0; j < mesh_orders.size(); ++j) {
    const int z = mesh_orders[j];
    if (z < 2 || static_cast<std::size_t>(z) + 1 > half) {
      return Reject("mesh_orders[" + std::to_string(j) + "] = " + std::to_string(z) +
                    " must be between 2 and M/2 - 1 = " + std::to_string(half - 1));
    }
  }
  for (std::size_t i = 0; i < m_points; ++i) {
    if (!std::isfinite(tsa[i])) {
      return Reject("tsa has a non-finite value at index " + std::to_string(i));
    }
  }
  for (std::size_t k = 0; k <= half; ++k) {
    if (!std::isfinite(orders[k].real()) || !std::isfinite(orders[k].imag())) {
      return Reject("orders has a non-finite value at order " + std::to_string(k));
    }
  }
  if (std::isnan(na4_reference_variance) || std::isinf(na4_reference_variance)) {
    return Reject("na4_reference_variance must be finite (<= 0 to use the record's own)");
  }
  const bool with_spread = spread.revolutions >= 2;
  if (with_spread && (spread.locked.size() != half + 1 || spread.spread.size() != half + 1)) {
    return Reject("the revolution spread has " + std::to_string(spread.locked.size()) + " and " +
                  std::to_string(spread.spread.size()) +
                  " orders, need M/2 + 1 = " + std::to_string(half + 1) + " each");
  }
  for (std::size_t k = 0; with_spread && k <= half; ++k) {
    if (!(spread.locked[k] >= 0.0 && spread.spread[k] >= 0.0) || std::isinf(spread.locked[k]) ||
        std::isinf(spread.spread[k])) {
      return Reject("the revolution spread has a negative or non-finite power at order " +
                    std::to_string(k));
    }
  }

  // ---- Line roles.
  std::span<std::uint8_t> role(line_role_.data(), half + 1);
  std::span<std::uint8_t> near(sideband_of_.data(), half + 1);
  std::fill(role.begin(), role.end(), std::uint8_t{0});
  std::fill(near.begin(), near.end(), std::uint8_t{0});
  const auto harmonics_of = [&](std::size_t z) {
    const std::size_t all = half / z;
    return options_.mesh_harmonics > 0
               ? std::min(all, static_cast<std::size_t>(options_.mesh_harmonics))
               : all;
  };
  const auto sidebands = static_cast<std::size_t>(options_.sideband_orders);
  std::size_t z_min = half;
  std::size_t z_max = 0;
  for (std::size_t j = 0; j < mesh_orders.size(); ++j) {
    const auto z = static_cast<std::size_t>(mesh_orders[j]);
    z_min = std::min(z_min, z);
    z_max = std::max(z_max, z);
    for (std::size_t h = 1; h <= harmonics_of(z); ++h) {
      const std::size_t line = h * z;
      role[line] |= kMeshLine;
      if (line + 1 <= half) role[line + 1] |= kFirstSideband;
      role[line - 1] |= kFirstSideband;  // line >= 2
      for (std::size_t s = 1; s <= sidebands; ++s) {
        if (line > s) near[line - s] |= static_cast<std::uint8_t>(1u << j);
        if (line + s <= half) near[line + s] |= static_cast<std::uint8_t>(1u << j);
      }
    }
  }
  const std::size_t low_orders =
      std::min(half, static_cast<std::size_t>(options_.low_shaft_orders));
  for (std::size_t k = 1; k <= low_orders; ++k) role[k] |= kShaftLine;
  const auto is_regular = [&](std::size_t k) { return (role[k] & (kMeshLine | kShaftLine)) != 0; };
  // Contribution of line k to the mean square (DC and order M/2 appear once, real).
  const auto energy = [&](std::size_t k) __attribute__((always_inline)) {
    return k == half ? orders[k].real() * orders[k].real() : 0.5 * std::norm(orders[k]);
  };

  // ---- The TSA itself.
  // Its variance, range and mean; no higher moment.
  const SumRange range = SumAndRange(tsa.data(), m_points);
  Moments whole;
  whole.mean = range.sum / static_cast<double>(m_points);
  CentralSums(tsa.data(), m_points, whole.mean, /*higher=*/false, whole);
  const double tsa_rms = std::sqrt(whole.m2);
  const double peak_to_peak = range.hi - range.lo;
  const double crest = Ratio(std::max(range.hi - whole.mean, whole.mean - range.lo), tsa_rms);
  const double zero_variance = kZeroVarianceFraction * whole.m2;

  // ---- Line sums.
  double mesh_amplitude_sum = 0.0;
  double regular_energy = 0.0;  // the regular signal's variance, by Parseval (no DC line)
  double low_energy = 0.0;
  double high_energy = 0.0;
  for (std::size_t k = 1; k <= half; ++k) {
    if ((role[k] & kMeshLine) != 0) mesh_amplitude_sum += std::abs(orders[k]);
    const double e = energy(k);
    if (is_regular(k)) {
      regular_energy += e;
    } else if (2 * k < z_min) {
      low_energy += e;
    } else if (k > z_max) {
      high_energy += e;
    }
  }
  // F ratio of the low band: the power locked to the shaft against what the unlocked content of
  // R revolutions leaves in their mean (spread / (R - 1) per order). Noise, or a burst in some
  // revolutions, raises both alike; a defect that returns every revolution raises only the
  // locked part. Orders above the Nyquist order hold interpolation images only.
  double low_locked = 0.0;
  double low_spread = 0.0;
  if (with_spread) {
    const std::size_t top =
        std::min(half, static_cast<std::size_t>(std::max(0.0, std::floor(spread.nyquist_order))));
    for (std::size_t k = 1; k <= top && 2 * k < z_min; ++k) {
      if (is_regular(k)) continue;
      low_locked += spread.locked[k];
      low_spread += spread.spread[k];
    }
  }
  std::array<double, kMaxMeshesPerShaft> sideband_energy{};
  std::array<double, kMaxMeshesPerShaft> mesh_energy{};
  std::size_t dominant = 0;
  for (std::size_t j = 0; j < mesh_orders.size(); ++j) {
    const auto z = static_cast<std::size_t>(mesh_orders[j]);
    for (std::size_t h = 1; h <= harmonics_of(z); ++h) mesh_energy[j] += energy(h * z);
    if (std::abs(orders[z]) > std::abs(orders[static_cast<std::size_t>(mesh_orders[dominant])])) {
      dominant = j;
    }
  }
  for (std::size_t k = 1; k <= half; ++k) {
    if (is_regular(k) || near[k] == 0 || !std::has_single_bit(near[k])) continue;
    sideband_energy[static_cast<std::size_t>(std::countr_zero(near[k]))] += energy(k);
  }
  const auto z_dominant = static_cast<std::size_t>(mesh_orders[dominant]);
  const double slf =
      Ratio(std::abs(orders[z_dominant - 1]) + std::abs(orders[z_dominant + 1]), tsa_rms);

  // ---- Residual and difference signals, rebuilt in time from their lines.
  FftPlan& plan = inverse_[PlanIndex(m_points)];
  const auto rebuild = [&](auto keep) -> std::span<const double> {
    std::span<std::complex<double>> in = plan.complex_in();
    in[0] = 0.0;
    for (std::size_t k = 1; k < half; ++k) in[k] = keep(k) ? 0.5 * orders[k] : 0.0;
    in[half] = keep(half) ? orders[half].real() : 0.0;
    plan.Execute();
    return plan.real_out();
  };
  // The regular signal's RMS needs no time signal (Parseval); the residual's and the
  // difference's higher moments do.
  const double regular_rms = std::sqrt(regular_energy);
  const Moments residual = CentralMoments(rebuild([&](std::size_t k) { return !is_regular(k); }));
  const Moments difference = CentralMoments(
      rebuild([&](std::size_t k) { return !is_regular(k) && (role[k] & kFirstSideband) == 0; }));

  // ---- Indicators.
  ConditionIndicatorValues v;
  using CI = ConditionIndicator;
  v[CI::kFm0] = Ratio(peak_to_peak, mesh_amplitude_sum);
  const bool difference_zero = difference.m2 <= zero_variance;
  if (!difference_zero) {
    v[CI::kFm4] = difference.m4 / (difference.m2 * difference.m2);
    v[CI::kM6a] = difference.m6 / (difference.m2 * difference.m2 * difference.m2);
    v[CI::kM8a] = difference.m8 / std::pow(difference.m2, 4);
  }
  const double na4_reference = na4_reference_variance > 0.0 ? na4_reference_variance : residual.m2;
  if (residual.m2 > zero_variance) {
    v[CI::kNa4] = Ratio(residual.m4, na4_reference * na4_reference);
  }
  v[CI::kEnergyRatio] = difference_zero ? 0.0 : Ratio(std::sqrt(difference.m2), regular_rms);
  v[CI::kSidebandLevel] = slf;
  v[CI::kMeshHarmonics] = mesh_amplitude_sum;
  v[CI::kResidualRms] = Ratio(std::sqrt(residual.m2), tsa_rms);
  v[CI::kResidualLowOrders] = Ratio(low_energy, whole.m2);
  v[CI::kResidualHighOrders] = Ratio(high_energy, whole.m2);
  v[CI::kTsaRms] = tsa_rms;
  v[CI::kCrestFactor] = crest;
  v[CI::kSynchronousLowOrders] =
      with_spread ? Ratio(low_locked, low_spread / (static_cast<double>(spread.revolutions) - 1.0))
                  : 0.0;
  v.residual_variance = residual.m2;
  v.mesh_count = mesh_orders.size();
  v.sideband_energy = sideband_energy;
  v.mesh_energy = mesh_energy;
  for (std::size_t j = 0; j < mesh_orders.size(); ++j) {
    v.sideband_ratio[j] = Ratio(sideband_energy[j], mesh_energy[j]);
  }
  out = v;
  return Status::Ok();
}

}  // namespace gearpath
