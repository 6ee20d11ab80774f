// Gear verdict: the state of a machine and the gear(s) it points at, as the pipeline publishes
// them (core/pipeline/localisation_stage.h names the gears from physics; core/pipeline/
// alarm_stage.h sets the state through the alarm model, core/diagnosis/alarm_model.h), and the
// machine's topology the localisation needs (which gear sits on which shaft and mesh, which
// meshes each transfer path sees). docs/diagnosis.md explains the reasoning.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "core/diagnosis/fixed_text.h"

namespace gearpath {

enum class FaultState : std::uint8_t {
  kLearning,   // baseline still being learned; indicators published, no verdict yet
  kNoFault,    // every indicator within the machine's healthy baseline
  kSuspected,  // indicators over their limit in some recent blocks, not yet persistent
  kAlarm,      // the exceedance persisted (k of the last n blocks; alarm_model.h)
};
std::string_view ToString(FaultState state) noexcept;

struct GearVerdict {
  FaultState state = FaultState::kLearning;
  int gear = -1;  // gear index of the best candidate; -1 = none
  std::string_view gear_name;
  int shaft = -1;  // shaft whose harmonics stand out; -1 = none
  std::string_view shaft_name;
  double characteristic_hz = 0.0;  // that shaft's rate
  double confidence = 0.0;         // in [0, 1]
  int mesh = -1;                   // mesh index chosen; -1 = none or undecided
  std::vector<int> candidates;     // every gear the evidence cannot exclude (gear indices)
  std::vector<std::string_view> candidate_names;
  MessageText reason;  // why, in one line (names the ambiguity when there is one)
};

// Everything the verdict needs about the machine; built once per setup.
struct VerdictTopology {
  std::vector<std::string> gear_names;
  std::vector<int> gear_shaft;  // shaft index of each gear
  std::vector<int> gear_mesh;   // mesh index of each gear (-1: in no mesh)
  std::vector<std::string> shaft_names;
  std::vector<double> shaft_ratio;            // shaft rate / input-shaft rate
  std::vector<std::string> mesh_names;        // e.g. "G1-G2"
  std::vector<std::vector<int>> path_meshes;  // meshes each path sees (via its gears)
  std::vector<std::string> path_names;        // optional, for the reason text
  double rate_tolerance = 0.02;               // relative: shafts closer than this share a rate

  // Reserves the candidate vectors of `verdict` so DecideGearVerdict never allocates.
  void Reserve(GearVerdict& verdict) const;
};

}  // namespace gearpath
