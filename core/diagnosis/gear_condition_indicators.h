// GearConditionIndicators: the classical gear condition indicators of one shaft, computed from
// its time-synchronous average (core/dsp/synchronous_average.h) and its order spectrum
// (Lebold et al. 2000, Sect. 4; Samuel & Pines 2005, Sect. 3; Randall 2011, Sect. 5.2 and 7.3).
// Definitions, units and healthy values: docs/condition_indicators.md.
//
// The shaft carries 1..4 gears; a gear of z teeth meshes at order z of its own shaft, so its
// mesh harmonics are the orders h z. The order lines 0..M/2 of the TSA are split, in the order
// domain, into:
//   - regular: the mesh harmonics h z (h = 1..H, every harmonic up to M/2 when H = 0) of every
//     mesh, and the shaft orders 1..L (unbalance, misalignment);
//   - residual: every other line except order 0 (a sensor offset carries no gear information,
//     so the DC line belongs to no signal);
//   - difference: the residual without the first-order sidebands h z +/- 1 of the mesh
//     harmonics.
// The residual and difference signals are rebuilt in time by an inverse r2c transform of their
// lines (plans made once); the regular signal is needed only for its RMS, which its lines give.
//
// Assumes: the TSA and its spectrum come from the same record (not checked: that would cost a
// forward FFT), amplitude-scaled as in spectrum.h; M is a power of two; the order spectrum is
// zero (or noise) above the block's Nyquist order. "Energy" of a set of lines means their
// contribution to the mean square, |S_k|^2 / 2 per interior line (signal units^2).
//
// Compute() is noexcept and allocation-free; one object must not be used by two threads at once.
#pragma once

#include <array>
#include <complex>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "core/common/result.h"
#include "core/dsp/fft_plan.h"

namespace gearpath {

enum class ConditionIndicator : std::uint8_t {
  kFm0,                   // peak-to-peak(TSA) / sum of mesh-harmonic amplitudes
  kFm4,                   // kurtosis of the difference signal
  kNa4,                   // 4th moment of the residual / (reference residual variance)^2
  kM6a,                   // 6th moment of the difference / variance^3
  kM8a,                   // 8th moment of the difference / variance^4
  kEnergyRatio,           // RMS(difference) / RMS(regular)
  kSidebandLevel,         // SLF: first sidebands of the dominant mesh / RMS(TSA)
  kMeshHarmonics,         // sum of mesh-harmonic amplitudes [signal units]
  kResidualRms,           // RMS(residual) / RMS(TSA)
  kResidualLowOrders,     // residual energy below (lowest mesh order) / 2, / TSA energy
  kResidualHighOrders,    // residual energy above the highest mesh order, / TSA energy
  kTsaRms,                // RMS of the TSA (DC removed) [signal units]
  kCrestFactor,           // max |TSA - mean| / RMS(TSA)
  kSynchronousLowOrders,  // low-order residual power locked to the shaft / what its spread
                          // between revolutions leaves in a mean (an F ratio, ~1 when none)
  kCount,
};

inline constexpr std::size_t kConditionIndicatorCount =
    static_cast<std::size_t>(ConditionIndicator::kCount);
inline constexpr std::size_t kMaxMeshesPerShaft = 4;

// snake_case name ("fm4", "energy_ratio", ...); "unknown" out of range.
std::string_view ConditionIndicatorName(ConditionIndicator indicator) noexcept;
// The power of the signal's amplitude an indicator goes with when the whole signal is scaled
// (a load that rises, a sensor's gain): 0 for the ratios and normalised moments, 1 for the
// amplitudes (mesh harmonics, TSA RMS), 4 for NA4 (a fourth moment over a reference variance
// learned once, squared).
int AmplitudePower(ConditionIndicator indicator) noexcept;
// One line: what it measures.
std::string_view ConditionIndicatorDescription(ConditionIndicator indicator) noexcept;
// "1" for dimensionless, "signal" for the signal's own unit (e.g. m/s^2).
std::string_view ConditionIndicatorUnit(ConditionIndicator indicator) noexcept;

struct IndicatorOptions {
  int mesh_harmonics = 0;    // H: mesh harmonics h = 1..H; 0 = every harmonic up to M/2
  int low_shaft_orders = 2;  // L: shaft orders 1..L in the regular signal (>= 0)
  int sideband_orders = 3;   // K: per-mesh sidebands h z +/- k, k = 1..K (>= 1)
};

struct ConditionIndicatorValues {
  std::array<double, kConditionIndicatorCount> value{};
  double& operator[](ConditionIndicator i) noexcept { return value[static_cast<std::size_t>(i)]; }
  double operator[](ConditionIndicator i) const noexcept {
    return value[static_cast<std::size_t>(i)];
  }

  // Variance of the residual signal (mean removed) [signal units^2]; the mean of this over
  // healthy records is NA4's reference variance.
  double residual_variance = 0.0;

  // Per mesh, in the order of `mesh_orders` (entries past mesh_count are zero):
  std::size_t mesh_count = 0;
  // Energy of the lines h z +/- k (k = 1..K, h = 1..H), mesh harmonics and shaft orders 1..L
  // excluded; a line within K of harmonics of two different meshes is ambiguous and counted
  // for neither [signal units^2].
  std::array<double, kMaxMeshesPerShaft> sideband_energy{};
  // sideband_energy / energy of that mesh's harmonics (0 when the harmonics are all zero).
  std::array<double, kMaxMeshesPerShaft> sideband_ratio{};
  // Energy of that mesh's harmonics h z [signal units^2].
  std::array<double, kMaxMeshesPerShaft> mesh_energy{};
};

// Per order k, the power locked to the shaft and the spread between revolutions
// (SynchronousAverage::RevolutionSpread, orders 0..M/2), over R revolutions; orders above
// nyquist_order hold interpolation images only.
struct RevolutionSpreadView {
  std::span<const double> locked;
  std::span<const double> spread;
  std::size_t revolutions = 0;
  double nyquist_order = 0.0;
};

class GearConditionIndicators {
 public:
  // For TSAs of up to `max_points_per_revolution` points (a power of two, 8..2^20); validates
  // the options (names the field). Plans one c2r FFT per power of two from 8 to the cap.
  static Result<GearConditionIndicators> Create(std::size_t max_points_per_revolution,
                                                const IndicatorOptions& options = {});

  const IndicatorOptions& options() const noexcept { return options_; }

  // tsa: M points (a power of two, 8..cap); orders: M/2 + 1 lines; mesh_orders: 1..4 tooth
  // counts of the gears on this shaft, each in 2..M/2 - 1; na4_reference_variance: the healthy
  // mean residual variance, <= 0 to use this record's own (NA4 is then the residual kurtosis).
  // Rejects wrong sizes, non-finite values and bad mesh orders (the message names the
  // argument); `out` is then untouched. noexcept, no allocation on success.
  //
  //
  // spread: SynchronousAverage::RevolutionSpread() of the same signal and plan; without it
  // (default, or fewer than 2 revolutions) kSynchronousLowOrders is 0.
  Status Compute(std::span<const double> tsa, std::span<const std::complex<double>> orders,
                 std::span<const int> mesh_orders, double na4_reference_variance,
                 ConditionIndicatorValues& out, const RevolutionSpreadView& spread = {}) noexcept;

 private:
  GearConditionIndicators() = default;

  IndicatorOptions options_;
  std::size_t max_points_ = 0;
  std::vector<FftPlan> inverse_;           // inverse_[i]: c2r plan of 8 << i points
  std::vector<std::uint8_t> line_role_;    // per order line: role bits (see the .cc)
  std::vector<std::uint8_t> sideband_of_;  // per order line: bit j set = near mesh j's harmonics
};

}  // namespace gearpath
