// The parametric_plate family's random plant (its truth, a ParametricGearbox), the model the
// daemon's FRF set is made from, and the family's tooth fault draw. Every value below is drawn
// from the plant seed (stream 303) unless said otherwise; U(lo, hi) uniform.
//
// Train (gears of module 3 mm, face width 16 mm, 20 deg, steel discs of pitch radius m z / 2,
// as Table 1): per shaft a shaft mass U(1.5, 3.0) kg (shaft, bearing inner rings, hubs; radius
// 24 mm) added to its gears' mass and inertia; bearings k_b log-U(1e8, 4e8) N/m, c_b U(500,
// 2000) N s/m. Motor coupling k_m log-U(1e4, 4e4) N m/rad, c_m U(0.5, 2) N m s/rad; load torque
// T_L U(40, 90) N m plus viscous c_L U(0.05, 0.25) N m s/rad on the output shaft.
// Meshes: contact ratio eps = the standard involute value x U(0.92, 1.02), clamped to
// [1.4, 1.8]; load ramp U(0.06, 0.12) mesh periods; crown U(0.15, 0.3); mean stiffness = ISO
// 6336-1 c' (0.75 eps + 0.25) b x U(0.85, 1.15) (c' = 14 N/(mm um)); mesh damping ratio
// U(0.03, 0.08) on the equivalent mass; profile errors: 4 harmonics, 0.5 um x U(0.6, 1.4) with
// a decay U(0.3, 0.5) per harmonic, random phases; per gear a runout U(2, 8) um and a wobble
// U(0.01, 0.03), random phases; random mesh phase and tooth offsets.
// Plate: steel (E 210 GPa, nu 0.3, 7850 kg/m^3), a = U(0.5, 0.7) m, b = a U(0.6, 0.85),
// h = U(12, 20) mm, modes up to 5 kHz, damping U(0.01, 0.03) each. Bearing seat i at
// x = a (0.2 + 0.6 i / (S - 1) + U(-0.05, 0.05)), y = b U(0.35, 0.65); m1 at x = a U(0.15,
// 0.85), y = b U(0.1, 0.2) or b U(0.8, 0.9) (always drawn, so both channel sets share a plate).
// Model (what the daemon's FRF set is computed from, never the truth): the same plate with its
// thickness x U(0.97, 1.03) and Young's modulus x U(0.95, 1.05), the modes above a cutoff
// U(2.2, 2.8) kHz missing, each damping ratio x U(0.7, 1.3).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/common/accel_block.h"
#include "core/common/result.h"
#include "core/evaluation/parametric_gearbox.h"
#include "core/frf/frf_set.h"
#include "core/model/gear_train.h"

namespace gearpath {

struct ParametricPlatePlant {
  std::shared_ptr<const ParametricGearbox> truth;
  PlateHousing model_plate;         // same points as the truth's plate
  double model_cutoff_hz = 0.0;
  std::vector<int> channel_points;  // plate point of each block channel
  std::vector<int> shaft_of_rotor;  // train shaft index of each rotor (rotor i = bearing i)
};

// The plant of `seed`; include_m1 adds the m1 channel (4 channels instead of 3).
Result<ParametricPlatePlant> DrawParametricPlatePlant(const GearTrain& train, bool include_m1,
                                                      std::uint64_t seed);

// The daemon's FRF set: the model plate's accelerance from the bearing seats (paths B1x..) to
// the channels (p1.., m1), on EvaluationFrfGrid(). For a housing measured through the
// rotors and virtually decoupled, Eq. 22 / Eq. 24 give exactly this housing-alone FRF on an
// exact model; the error here is the model's.
FrfSet ParametricPlateFrfSet(const ParametricPlatePlant& plant, const GearTrain& train,
                             const std::vector<ChannelInfo>& channels,
                             const Eigen::VectorXd& grid_hz);

// The family's tooth fault on `gear` (stream 304 of `seed`): a random damaged tooth, a spall of
// U(0.4, 0.8) mesh periods at a random place on that tooth's contact path (8 % cosine edges), a
// wear length U(2, 3) mesh periods; default depths pulse (missing material) 1 um, crack 0.15,
// wear 1 um; caps 10 um (deeper than any static approach of the family: the spalled zone then
// carries no load, and a deeper spall changes nothing), 0.6 and 5 um. kNone gives an empty
// fault.
Result<ToothFault> DrawToothFault(const ParametricPlatePlant& plant, const GearTrain& train,
                                  PlantFaultKind kind, const std::string& gear,
                                  std::uint64_t seed);

}  // namespace gearpath
