// ToothMesh: one gear stage of the parametric_plate family as a TIME-VARYING mesh: its
// stiffness follows the tooth pairs in contact (parametric excitation), its transmission error
// the tooth profiles, and a tooth fault changes one tooth's pairs only. Independent of
// PlantExcitation (which is an additive / multiplicative TE model of the linear families).
//
// Kinematics. m(t) = z_dr r_dr(t) + m_0 + sum_g runout_g sin(2 pi r_g + psi_g) / p_b is the
// mesh position in mesh cycles (r_g: revolutions of gear g's shaft, m_0 a random mesh phase,
// p_b the base pitch: an eccentric gear advances or delays the contact by its runout along the
// line of action). Tooth pair j engages at m = j and leaves at m = j + eps (eps the contact
// ratio, 1 < eps < 2): at any time one or two pairs are in contact, at path position
// u = m - j in [0, eps). Pair j holds driver tooth (j + o_dr) mod z_dr and driven tooth
// (j + o_dn) mod z_dn (random tooth offsets).
//
// Stiffness. k(t) = sum_{pairs in contact} k_j, with
//   k_j = k_p S(u) W(t) (1 - d_c [pair j holds the cracked tooth]),
//   S(u) = R(u) R(eps - u) (1 - crown (2u / eps - 1)^2),  R(x) = (1 - cos(pi x / r)) / 2 for
//   x < r, else 1: a pair takes its load over a ramp of r mesh periods (tip relief) and is
//   stiffest mid-path; W = 1 + sum_g wobble_g cos(2 pi r_g + chi_g) is the once-per-revolution
//   load-distribution change of each gear's eccentricity / wobble. Single and double contact
//   alternate at the mesh frequency; k_double / k_single ~ 1.6-1.8.
//
// Transmission error (profile deviation, m, positive = material missing: the mesh deflects
// less under the same approach). Stage-wide, healthy: e(t) = sum_h A_h cos(2 pi h m + phi_h)
// (random profile-error harmonics) + sum_g runout_g sin(2 pi r_g + psi_g) (eccentricity).
// Pair-wise: the pair holding a tooth with missing material sees e_j = d_p B(u - u_s; L_p,
// taper) (a tapered box: a spall of L_p mesh periods starting at path position u_s, sharp
// edges); a worn zone gives the pair holding tooth t (k = t - t_worn teeth from the worn one)
// e_j = d_w cos^2(pi k / L_w) sin^2(pi u / eps) for |k| < L_w / 2: the worn tooth's flank
// smoothly over its whole contact, its neighbours less, over L_w = 2..3 mesh periods, no
// edges. (A deviation common to every pair in contact would only be a kinematic TE, which the
// rotors follow at these low frequencies; a pair-wise one shifts the load between the pairs.)
//
// Mesh force (evaluated by the integrator): F = sum_j k_j max(0, delta - e - e_j) + c_c (d delta
// / dt - de/dt), delta the approach of the two gears along the line of action (positive =
// loaded flanks compressed), c_c the mesh damping times the share of the stiffness in contact.
// Contact is unilateral: a pair whose profile deviation exceeds the approach (deep missing
// material, a deep worn dip) unloads; in single contact the gears then separate and re-impact.
//
// Faults (ToothFault, PlantFaultKind names kept): te_pulse = missing material (e_j), mesh_am =
// crack (d_c, the pairs holding the tooth lose that fraction of their stiffness: parametric),
// wear_dip = worn profile (the worn zone's e_j), combined = crack + missing material.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/common/result.h"
#include "core/evaluation/plant_excitation.h"

namespace gearpath {

// One shaft's angle: revolutions since t = 0, rate, and cos / sin of 2 pi revs.
struct ShaftPhase {
  double revs = 0.0;
  double rate_hz = 0.0;
  double cos = 1.0;
  double sin = 0.0;
};
ShaftPhase MakeShaftPhase(double revs, double rate_hz) noexcept;

struct GearEccentricity {
  double runout_m = 0.0;  // eccentric displacement along the line of action (amplitude)
  double runout_phase = 0.0;
  double wobble = 0.0;  // once-per-revolution stiffness modulation depth
  double wobble_phase = 0.0;
};

struct ToothMeshParameters {
  int z_driver = 0;
  int z_driven = 0;
  double contact_ratio = 1.6;           // eps, in (1, 2)
  double pair_stiffness_n_per_m = 2e8;  // k_p
  double ramp_periods = 0.1;            // r, in (0, eps / 2)
  double crown = 0.2;                   // in [0, 1)
  double base_pitch_m = 8.86e-3;        // p_b
  double mesh_phase = 0.0;              // m_0, mesh cycles
  int driver_tooth_offset = 0;          // o_dr
  int driven_tooth_offset = 0;          // o_dn
  std::vector<double> profile_amplitude_m;  // A_h, h = 1..
  std::vector<double> profile_phase;        // phi_h
  GearEccentricity driver, driven;
};

struct ToothFault {
  PlantFaultKind kind = PlantFaultKind::kNone;
  int stage = -1;            // the faulty gear's stage (its mesh)
  bool on_driver = true;     // the faulty gear is the stage's driver (else its driven gear)
  int tooth = 0;             // the damaged tooth, 0..z-1
  double spall_start = 0.0;  // u_s, mesh periods along the pair's path
  double wear_length = 2.5;  // L_w, mesh periods (teeth) of the worn zone
  // pulse_depth_m = d_p (missing material), pulse_length_periods = L_p, pulse_taper;
  // am_depth = d_c (crack: fraction of the pair stiffness lost); dip_depth_m = d_w (wear).
  PlantFaultSeverity severity;
};

// The mesh at one instant: the (one or two) tooth pairs on the contact path. Pair j carries
// k_j (delta - gap_j) while delta > gap_j and nothing otherwise (contact loss), gap_j = e +
// e_j its profile deviation; the mesh damping c (d delta/dt - de/dt) acts in proportion to the
// share of the stiffness in contact.
struct MeshSample {
  int pairs = 0;
  double stiffness[2] = {0.0, 0.0};  // k_j, N/m
  double gap[2] = {0.0, 0.0};        // e + e_j, m
  double error_rate = 0.0;           // de/dt of the stage-wide error, m/s
  bool bilateral = false;            // the linear limit: every pair carries load, tension too

  double TotalStiffness() const noexcept { return stiffness[0] + stiffness[1]; }
  // sum_j k_j gap_j, N (the mesh force at delta = 0 with every pair in contact, negated).
  double ErrorForce() const noexcept { return stiffness[0] * gap[0] + stiffness[1] * gap[1]; }
};

class ToothMesh {
 public:
  ToothMesh() = default;
  // Fails (naming the field) on tooth counts < 2, a contact ratio outside (1, 2), a ramp
  // outside (0, eps / 2), a crown outside [0, 1), non-positive stiffness or base pitch,
  // profile amplitude / phase lists of different lengths.
  static Result<ToothMesh> Create(const ToothMeshParameters& parameters);
  // Checks a fault against this mesh (tooth in range, spall inside the contact path, depths
  // >= 0, crack depth < 1, wear length shorter than a revolution).
  Status CheckFault(const ToothFault& fault) const;

  const ToothMeshParameters& parameters() const noexcept { return p_; }
  // Pair stiffness shape S(u) (k_j / k_p before wobble and crack), 0 outside [0, eps).
  double PairShape(double u) const noexcept;
  // Mean and largest healthy mesh stiffness over a mesh period (no wobble), N/m.
  double mean_stiffness() const noexcept { return mean_stiffness_; }
  double max_stiffness() const noexcept { return max_stiffness_; }

  // Mesh cycles m(t) (see the file comment).
  double MeshCycles(const ShaftPhase& driver, const ShaftPhase& driven) const noexcept;
  // The mesh at the shafts' angles; fault == nullptr: healthy. constant_stiffness: one
  // bilateral "pair" of mean_stiffness() with gap e (tests: the linear time-invariant limit).
  void Evaluate(const ShaftPhase& driver, const ShaftPhase& driven, const ToothFault* fault,
                bool constant_stiffness, MeshSample& out) const noexcept;

 private:
  ToothMeshParameters p_;
  std::vector<double> cos_phase_, sin_phase_;
  // cos / sin of the runout and wobble phases: driver runout, driven runout, driver wobble,
  // driven wobble.
  std::array<double, 8> trig_{};
  double mean_stiffness_ = 0.0;
  double max_stiffness_ = 0.0;
};

}  // namespace gearpath
