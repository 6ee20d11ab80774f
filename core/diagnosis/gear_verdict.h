// Gear verdict: which gear most likely carries the fault, from the envelope indicators and
// the dominant transfer path (step 9 of the per-block flow; docs/diagnosis.md).
//
// Physics it rests on (DESIGN.md, last bullets):
//  - A localized tooth fault engages once per revolution of its gear, so it modulates the mesh
//    at the rate of the gear's shaft (seed Table 6). The shaft whose harmonics stand out in the
//    squared envelope spectrum names the SHAFT (or the group of shafts turning at that rate:
//    the envelope cannot tell equal rates apart).
//  - A mesh force pushes on both shafts of its pair, so both shafts' bearings carry it: the
//    dominant path alone does not name the gear. Which end of the train carries the fault
//    (the bearing paths of one mesh and not of the other) names the MESH.
//  - Shaft group x mesh names the gear. Where even that leaves several gears (seed Table 1:
//    gears 3 and 4 have equal tooth counts, share mesh 2 and both turn at 7 Hz) they are all
//    reported as candidates and the reason says why.
//
// Indicators are judged against thresholds (configured, or learned from the machine's own
// healthy blocks: a healthy gearbox already shows envelope lines at shaft harmonics from mesh
// beating), never against zero. Exceedance of shaft s: e_s = max(raw_s / raw_thr_s,
// rec_s / rec_thr_s). No shaft with e_s >= 1 -> kNoFault.
//
// Mesh evidence: the dominant path restricts the meshes to those it "sees" (the meshes of the
// gears nearest its bearing). Among those the mesh score decides: each path adds its weight
// / n to each of the n meshes it sees (a path seeing one mesh is clean evidence for it; a
// path on a shaft shared by two meshes splits its weight). The weight is the caller's
// per-mesh evidence when given (VerdictInputs::mesh_evidence), else the path criterion.
//
// Confidence in [0, 1] = strength x shaft separation x mesh separation:
//   strength   = 1 - 1/e_max (0 at the threshold, -> 1 far above it),
//   shaft sep. = 1 - e_other / e_max (e_other: best exceedance at a DIFFERENT shaft rate),
//   mesh sep.  = 1 - S_2 / S_1 of the mesh scores among the candidate meshes (1 if only one).
// It is the confidence that the fault is among the reported candidates. For kNoFault it is
// 1 - e_max (how far under the thresholds the block stayed).
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
  kNoFault,    // every shaft's indicator under its threshold
  kSuspected,  // a shaft's indicator over its threshold
  kAlarm,      // over alarm_factor x threshold
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

struct VerdictInputs {
  double input_speed_hz = 0.0;
  std::span<const double> raw;                      // per shaft
  std::span<const double> reconstructed;            // per shaft
  std::span<const double> raw_threshold;            // per shaft (> 0)
  std::span<const double> reconstructed_threshold;  // per shaft (> 0)
  std::span<const double> path_criterion;           // per path (>= 0), the dominant-path criterion
  // Optional, per mesh (>= 0): evidence that this mesh is the faulty one, computed by the
  // caller; when given and not all zero it replaces the path-criterion weights as the mesh
  // score (the pipeline passes the bearing FORCES' sideband excess, split over the meshes
  // each path sees). Empty = path-criterion weights.
  std::span<const double> mesh_evidence;
  int dominant_path = -1;
  double alarm_factor = 2.0;
  bool learning = false;  // thresholds not yet known
};

// Fills `out` (noexcept; allocation-free once `topology.Reserve(out)` was called). Sizes of
// the spans must match the topology (else kNoFault with a reason naming the mismatch).
void DecideGearVerdict(const VerdictTopology& topology, const VerdictInputs& in,
                       GearVerdict& out) noexcept;

}  // namespace gearpath
