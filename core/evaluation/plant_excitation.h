// PlantExcitation: the mesh transmission error (TE) of every stage of an evaluation plant, as
// a function of the input-shaft ANGLE, healthy or with one of several fault models of
// different physics. It is deliberately independent of core/simulation/fault_excitation.h
// (the daemon's own simulator, an additive pulse model): the evaluation must not share the
// simulator's assumptions.
//
// Angle, not time: everything here is a function of theta, the input shaft's angle in
// revolutions since t = 0, so the plant simulator can drive it with a varying speed (drift).
// Shaft i turns r_i theta revolutions (r_i = shaft rate / input rate from the tooth counts);
// stage s goes through z_dr r_dr theta mesh cycles.
//
// Healthy TE of stage s (all amplitudes and phases drawn from the seed, per stage / gear):
//   e_s = [1 + sum_{g in {driver, driven}} mu_g cos(2 pi r_g theta + psi_g)]
//         * sum_{h=1..H} A_{s,h} cos(2 pi h m_s(theta) + phi_{s,h}),   m_s = mesh cycles,
//   A_{s,1} = mesh_fundamental_m x U(0.7, 1.3), A_{s,h} = A_{s,1} rho_s^(h-1), rho_s in
//   U(0.25, 0.45); mu_g (eccentricity / runout, once per revolution) in U(0.5, 1.5) x
//   eccentricity_depth.
//
// Fault on gear g (teeth z_g, stage s_g, shaft rate ratio r_f): the damaged tooth (a random
// tooth, from the seed) is in mesh once per revolution of g's shaft. With u = fractional part
// of (r_f theta - onset) in revolutions of that shaft, x = u z_g is the time since the damaged
// tooth engaged, in tooth-mesh periods. Fault models (PlantFaultKind):
//   te_pulse : e_s += d_p B(x; L_p, taper_p)          additive TE pulse, ~1 mesh period, sharp
//                                                    edges (B: tapered box, cosine ramps)
//   mesh_am  : e_s *= 1 - d_a B(x; L_a, taper_a)       the stage's mesh content loses a fraction
//                                                    d_a while the tooth meshes (multiplicative)
//   wear_dip : e_s += d_w hann(x / L_w), L_w in U(2, 3) mesh periods: smooth, wide, no edges
//   combined : te_pulse and mesh_am together
// Only the faulty gear's own stage is changed. Severities (PlantFaultSeverity) are chosen so
// the raw housing signal's RMS changes by a few percent at most (tests/core/evaluation).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/common/result.h"
#include "core/model/gear_train.h"

namespace gearpath {

enum class PlantFaultKind : std::uint8_t { kNone, kTePulse, kMeshAm, kWearDip, kCombined };

// "none", "te_pulse", "mesh_am", "wear_dip", "combined".
std::string_view PlantFaultKindName(PlantFaultKind kind) noexcept;
std::optional<PlantFaultKind> ParsePlantFaultKind(std::string_view name) noexcept;
inline constexpr PlantFaultKind kAllPlantFaultKinds[] = {
    PlantFaultKind::kNone, PlantFaultKind::kTePulse, PlantFaultKind::kMeshAm,
    PlantFaultKind::kWearDip, PlantFaultKind::kCombined};

struct PlantFaultSeverity {
  double pulse_depth_m = 0.6e-6;      // d_p
  double pulse_length_periods = 1.0;  // L_p, tooth-mesh periods
  double pulse_taper = 0.08;          // fraction of L_p in each ramp (sharp edges)
  double am_depth = 0.35;             // d_a, fraction of the mesh content lost
  double am_length_periods = 1.0;     // L_a
  double am_taper = 0.2;
  double dip_depth_m = 1.0e-6;  // d_w
  double dip_length_lo = 2.0;   // L_w drawn in [lo, hi] mesh periods
  double dip_length_hi = 3.0;
  // Physical caps ScaleSeverity never exceeds (a missing tooth cannot deflect the mesh by more
  // than a few times its loaded deflection; the mesh cannot lose more than most of its load).
  double max_pulse_depth_m = 3.0e-6;
  double max_dip_depth_m = 5.0e-6;
  double max_am_depth = 0.6;
};

struct PlantExcitationConfig {
  PlantFaultKind fault = PlantFaultKind::kNone;
  std::string faulty_gear;  // gear name in the train; ignored for kNone
  std::uint64_t seed = 1;   // phases, amplitudes, damaged tooth
  double mesh_fundamental_m = 1.0e-6;
  int mesh_harmonics = 4;  // H, >= 1
  double eccentricity_depth = 0.04;
  PlantFaultSeverity severity;
};

class PlantExcitation {
 public:
  // Fails (naming the argument) on an invalid train, an unknown faulty gear, or parameters out
  // of range (negative depths, am_depth outside [0, 1], window longer than a revolution).
  static Result<PlantExcitation> Create(const GearTrain& train,
                                        const PlantExcitationConfig& config);

  const PlantExcitationConfig& config() const noexcept { return config_; }
  int stage_count() const noexcept { return static_cast<int>(stages_.size()); }
  // TE of `stage` at input-shaft angle `input_revs` (revolutions), m; fault applied when
  // fault_on is true (and the config has a fault). Out-of-range stage gives 0.
  double Te(int stage, double input_revs, bool fault_on) const noexcept;
  // Te(fault on) - Te(fault off), cheap outside the fault window (returns 0 there without
  // evaluating the mesh content).
  double FaultDeviation(int stage, double input_revs) const noexcept;
  // Highest frequency of the healthy TE per unit input speed (H x mesh order + the shaft
  // orders of the eccentricity sidebands): the healthy TE is band-limited to it.
  double HealthyBandwidthOrder() const noexcept;

  // Multiplies every fault depth (pulse, dip, AM) by factor >= 0, each clamped to its cap;
  // the runner uses it to bring a fault to a target raw RMS change (evaluation_runner.h).
  void ScaleSeverity(double factor) noexcept;
  const PlantFaultSeverity& severity() const noexcept { return config_.severity; }

  // Kinematics per input revolution: mesh cycles of each stage, revolutions of each shaft.
  double mesh_order(int stage) const noexcept { return stages_[stage].mesh_order; }
  const std::vector<double>& shaft_orders() const noexcept { return shaft_orders_; }
  // Fault description (-1 / 0 when healthy).
  int fault_stage() const noexcept { return fault_stage_; }
  int fault_gear() const noexcept { return fault_gear_; }
  double fault_shaft_order() const noexcept { return fault_shaft_order_; }
  int fault_teeth() const noexcept { return fault_teeth_; }
  double fault_onset_revs() const noexcept { return fault_onset_revs_; }  // of the faulty shaft
  double dip_length_periods() const noexcept { return dip_length_; }

 private:
  struct Stage {
    double mesh_order = 0.0;  // mesh cycles per input revolution
    std::vector<double> amplitude;
    std::vector<double> phase;
    double order_driver = 0.0, order_driven = 0.0;  // shaft revolutions per input revolution
    double mu_driver = 0.0, mu_driven = 0.0;
    double psi_driver = 0.0, psi_driven = 0.0;
  };
  PlantExcitation() = default;
  double MeshContent(const Stage& st, double input_revs) const noexcept;
  // Gain and additive pulse of the fault at x mesh periods after the damaged tooth engaged.
  void FaultAt(double x, double& gain, double& pulse) const noexcept;
  double FaultX(double input_revs) const noexcept;

  PlantExcitationConfig config_;
  std::vector<Stage> stages_;
  std::vector<double> shaft_orders_;
  int fault_stage_ = -1;
  int fault_gear_ = -1;
  int fault_teeth_ = 0;
  double fault_shaft_order_ = 0.0;
  double fault_onset_revs_ = 0.0;
  double dip_length_ = 0.0;
  double window_periods_ = 0.0;  // longest fault window, mesh periods
};

// Tapered box on [0, length): cosine ramps of taper x length at each end, 1 in between.
double TaperedWindow(double x, double length, double taper) noexcept;

}  // namespace gearpath
