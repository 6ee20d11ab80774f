// FaultExcitation: static transmission error (TE) of every mesh stage of a gearbox running at
// constant speed, healthy or with one localized gear fault, as a function of time.
//
// This is the excitation of the lumped model (core/model/lumped_gearbox_model.h: the mesh
// force of stage s is (k_s + j w c_s) e_s), i.e. the source the seed's experiment creates by
// swapping in a damaged gear (seed Sec. 4, Fig. 11: chipped tooth, localized wear, tooth
// fracture). The seed gives the damage geometry, not the TE, so the model below is ours.
//
// Healthy part, per stage s with mesh frequency f_m and shaft rates f_dr (driver), f_dn:
//   e_h(t) = [1 + mu cos(2 pi f_dr t + psi_dr) + mu cos(2 pi f_dn t + psi_dn)]
//            * sum_h A_h cos(2 pi h f_m t + phi_h)
// Mesh harmonics A = {1.0, 0.3, 0.1} um by default: the loaded TE of accurate (ISO 6-7) spur
// gears is of the order of 1 um peak. mu = 0.05 is a small once-per-revolution amplitude
// modulation (eccentricity, runout) of each gear, which gives the sidebands every real mesh
// spectrum has. Phases phi, psi are drawn from the seed.
//
// Fault part: a localized fault on gear g (on stage s, on shaft S) changes the TE only while
// the damaged tooth is in mesh, once per revolution of S: a pulse p(t) starting at the damaged
// tooth's engagement t_on + n / f_S (n integer), on stage s only. Positive TE = material
// missing on the flank, which reduces the mesh force. The pulse is a tapered box (cosine ramps)
//   depth  = depth_factor * deflection_scale * severity,
//   length = length_factor * eps * T_m   (eps: contact ratio, T_m = 1 / f_m: a tooth is in
//            mesh for eps mesh periods),
//   ramps  = taper * length at each end (taper 0.5 = Hann, smooth; small taper = abrupt).
// The deviation cannot exceed what the remaining tooth pairs deflect under load: when a tooth
// is missing the neighbouring pairs take its load, so the TE grows by about the loaded mesh
// deflection, not by the (much larger) depth of the missing material. deflection_scale = 5 um
// is the deflection of the Table 1 mesh (k ~ 3.4e8 N/m, ISO 6336 estimate) under ~1.7 kN of
// tooth load (~65 N m on G1). Per fault type (depth_factor, length_factor, taper):
//   tooth fracture (whole tooth height removed): (1.0, 1.0, 0.2) - the whole engagement loses
//     its load, abruptly (load transfer within ~0.2 of the engagement, ~1.2 ms at 600 r/min);
//   chipped tooth (70 % of the tooth edge removed): (0.5, 0.5, 0.35) - the chipped tip region
//     carries ~30 % of its face width during about half of the engagement;
//   localized wear (0.3 mm deep): (0.25, 1.0, 0.5) - a shallow, smooth deviation over the
//     whole engagement (the worn profile blends into the intact one, so no sharp edges).
// At equal severity the pulse energy is therefore ordered fracture > chipped > wear, and the
// mesh harmonics stay the largest lines of the raw spectrum. The ramp time decides how hard
// the pulse rings the housing modes (1.0-1.7 kHz for Table 1): with the values above the raw
// seat signal of Table 1 at 600 r/min, fault on G1, has kurtosis ~6.6 (fracture), ~2.7
// (chipped), ~2.4 (wear; healthy 2.4) and RMS +19 %, +5 %, +0 %: the fault is there but not
// dominant, as in the seed, where it needs the path-contribution enhancement to stand out.
// Shorter ramps (taper 0.1) make kurtosis > 50 at p1; ExcitationParameters::shape overrides
// the table. No random jitter: every revolution is identical, which keeps the TE exactly
// periodic (see gearbox_simulator.h).
//
// Everything is periodic with the least common period of all shafts (GearTrain::
// InputRevolutionsPerCommonPeriod / input speed); evaluation is exact at any time.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "core/common/result.h"
#include "core/model/gear_train.h"

namespace gearpath {

enum class FaultType { kNone, kChippedTooth, kLocalizedWear, kToothFracture };

// "none", "chipped", "wear", "fracture" (the names the tools and configuration use).
const char* FaultTypeName(FaultType type) noexcept;
std::optional<FaultType> ParseFaultType(std::string_view name) noexcept;

struct GearFault {
  FaultType type = FaultType::kNone;
  std::string gear;       // gear name in the GearTrain (e.g. "G2"); ignored for kNone
  double severity = 1.0;  // scales the fault depth; 1 = the seed's damage, >= 0
};

// Pulse parameters of one fault type (see the file comment for the reasoning).
struct FaultShape {
  double depth_factor = 0.0;   // x deflection_scale
  double length_factor = 0.0;  // x contact ratio x mesh period
  double taper = 0.5;          // fraction of the length in each cosine ramp, (0, 0.5]
};
FaultShape FaultShapeOf(FaultType type) noexcept;

struct ExcitationParameters {
  std::vector<double> mesh_harmonic_amplitude_m = {1.0e-6, 0.3e-6, 0.1e-6};  // A_1, A_2, ...
  double shaft_modulation_depth = 0.05;                                      // mu, [0, 0.5)
  double deflection_scale_m = 5.0e-6;  // loaded mesh deflection, > 0
  std::uint64_t seed = 1;              // phases and the angular position of the damaged tooth
  std::optional<FaultShape> shape;     // overrides FaultShapeOf(fault type) when set
};

class FaultExcitation {
 public:
  // Fails (message names the argument) on an invalid train, input speed <= 0, unknown fault
  // gear, negative severity, or invalid parameters.
  static Result<FaultExcitation> Create(const GearTrain& train, double input_hz,
                                        const GearFault& fault,
                                        const ExcitationParameters& parameters = {});

  const TrainKinematics& kinematics() const noexcept { return kinematics_; }
  const GearFault& fault() const noexcept { return fault_; }
  int stage_count() const noexcept { return static_cast<int>(stages_.size()); }

  // TE of stage `stage` (0-based) at time t_s (s), in m; out-of-range stage gives 0.
  double Healthy(int stage, double t_s) const noexcept;
  double Fault(int stage, double t_s) const noexcept;
  double Total(int stage, double t_s) const noexcept {
    return Healthy(stage, t_s) + Fault(stage, t_s);
  }
  // out[n] = Total(stage, t0_s + n / sample_rate_hz).
  void Sample(int stage, double t0_s, double sample_rate_hz, std::span<double> out) const noexcept;

  // Fault timing (all 0 / -1 when healthy or severity 0): the stage the fault acts on, its
  // repetition period (1 / faulty gear's shaft rate), the start of the first damaged-tooth
  // engagement within [0, period), the pulse length and its depth.
  int fault_stage() const noexcept { return fault_stage_; }
  double fault_period_s() const noexcept { return fault_period_s_; }
  double fault_onset_s() const noexcept { return fault_onset_s_; }
  double fault_length_s() const noexcept { return fault_length_s_; }
  double fault_depth_m() const noexcept { return fault_depth_m_; }
  // Every stage's TE repeats after this (least common period of all shafts), s.
  double common_period_s() const noexcept { return common_period_s_; }

 private:
  struct Stage {
    double mesh_hz = 0.0;
    double driver_shaft_hz = 0.0;
    double driven_shaft_hz = 0.0;
    std::vector<double> harmonic_phase;  // phi_h
    double driver_phase = 0.0;           // psi_dr
    double driven_phase = 0.0;           // psi_dn
  };

  FaultExcitation() = default;

  TrainKinematics kinematics_;
  GearFault fault_;
  ExcitationParameters parameters_;
  std::vector<Stage> stages_;
  int fault_stage_ = -1;
  double fault_period_s_ = 0.0;
  double fault_onset_s_ = 0.0;
  double fault_length_s_ = 0.0;
  double fault_depth_m_ = 0.0;
  double fault_taper_ = 0.5;
  double common_period_s_ = 0.0;
};

}  // namespace gearpath
