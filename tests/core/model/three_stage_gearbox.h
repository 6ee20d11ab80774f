// A three-stage gearbox whose masses, stiffnesses and geometry are all unlike Table 1, for
// tests that must hold beyond the seed's two-stage example (model and decoupling tests).
#pragma once

#include <optional>

#include "core/model/lumped_gearbox_model.h"

namespace gearpath::testing {

inline GearboxParameters ThreeStageParameters() {
  GearboxParameters p = Table1Parameters();
  p.stages = {GearStage{21, 55, std::nullopt}, GearStage{25, 47, 4e8},
              GearStage{30, 61, std::nullopt}};
  p.bearing_stiffness_n_per_m = {2e7, 5e7, 8e7, 3e7};
  p.bearing_damping_ns_per_m = {5e3, 2e3, 1e4, 7e3};
  p.seat_mass_kg = {1.5, 2.5, 0.8, 4.0};
  p.seat_stiffness_n_per_m = {2e8, 6e7, 1.5e8, 9e7};
  p.seat_damping_ns_per_m = {2e3, 1e3, 5e2, 1.5e3};
  p.housing_mass_kg = 41.0;
  p.ground_stiffness_n_per_m = 3e8;
  p.ground_damping_ns_per_m = 4e3;
  p.module_m = 2.5e-3;
  p.face_width_m = 20e-3;
  p.shaft_length_m = 0.2;
  return p;
}

}  // namespace gearpath::testing
