// LocalisationStage: which gear the anomaly points at, from physics (DESIGN.md, "Two
// physical facts"; docs/diagnosis.md):
//  1. The SHAFT: the rate group whose EXCLUSIVE residual energy (orders of its rate that are
//     no harmonic of another rate) rose most over healthy, summed over the measured channels
//     (one unit for every group; a fault's comb is whole only at its own shaft's rate),
//     counting a group only when one of its channels rose clearly (z >= 3); by the groups'
//     scores when none did. Shafts at equal rates cannot be told apart by rate, so the
//     group is named, not one shaft.
//  2. The MESH, when the group's gears sit on several meshes: by transfer signature
//     (core/diagnosis/mesh_signature.h). A tooth fault on mesh m adds sideband energy that
//     travels like m's own tone (parallel to it across the sensors) near m's harmonics and,
//     when broadband, energy that does not travel like the other meshes' tones near theirs.
//     Evidence for m = the other meshes' orthogonal rise on the measured channels, in robust z
//     over its own healthy spread, harmonic by harmonic, summed over the harmonics (m's
//     parallel rise when nothing rose orthogonally), as a fraction of the total, accumulated
//     over the fault's blocks like the shaft evidence.
//     The mesh wins when it leads the next by AnalysisOptions::mesh_separation; otherwise
//     every close mesh stays a candidate. (Tried first: each mesh's sideband energy, and the
//     end bearings' force excess - a mesh force loads its own two shafts' bearings. On the
//     evaluation families both were right about half the time: the lumped model couples the
//     meshes through the shared shaft's rotation, and an additive pulse's comb spreads over
//     every mesh's neighbourhood.)
//  Both read the measured channels' entries from order-tracked averages when the machine is
//  tracked for localisation (AnalysisOptions::localisation_tracking; MachineContext::
//  tracked_offset): speed drift within a block smears constant-speed averages across groups.
//  The shaft and mesh evidence accumulate over the blocks at or above the clear level (the
//  fault's blocks) and decay by half on each quiet block: one block's noisy evidence does not
//  name the shaft or the mesh (MachineState keeps the sums).
//  3. The GEARS: the group's gears on the chosen mesh(es). Two gears with the same rate on the
//     same mesh (seed Table 1's G3 and G4) remain joint candidates: nothing separates them.
#pragma once

#include <cstdint>
#include <vector>

#include "core/pipeline/pipeline_stage.h"

namespace gearpath {

class LocalisationStage final : public PipelineStage {
 public:
  const char* name() const noexcept override { return "localisation"; }
  Status Configure(const MachineContext& machine, BlockWorkspace& work) override;
  RejectReason Process(StageContext& ctx) noexcept override;

 private:
  // A group's exclusive-residual rise is shaft evidence only when one of its measured channels'
  // robust z reaches this (the tail guard's level: clearly outside the healthy spread).
  static constexpr double kShaftEvidenceZ = 3.0;
  std::vector<double> group_excess_;        // per rate group, this block
  std::vector<std::uint8_t> group_clear_;   // per rate group: a channel rose clearly
};

}  // namespace gearpath
