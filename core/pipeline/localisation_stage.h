// LocalisationStage: which gear the anomaly points at, from physics (DESIGN.md, "Two
// physical facts"; docs/diagnosis.md):
//  1. The SHAFT: the rate group whose synchronous-average indicators score highest (a
//     localized tooth fault engages once per revolution of its own shaft). Shafts at equal
//     rates cannot be told apart by rate, so the group is named, not one shaft.
//  2. The MESH, when the group's gears sit on several meshes: (a) around which mesh's
//     harmonics the sidebands rose (per-mesh sideband energy z on the group's averages), and
//     (b) which END of the train carries the shaft-rate modulation: a mesh force loads the
//     bearings of its own two shafts, so a path whose gears belong to one mesh only (an end
//     bearing) speaks for that mesh; its exclusive residual and residual RMS at the group's
//     rate are its evidence. The mesh with the stronger evidence wins when it leads the next by
//     AnalysisOptions::mesh_separation; otherwise every close mesh stays a candidate.
//  3. The GEARS: the group's gears on the chosen mesh(es). Two gears with the same rate on the
//     same mesh (seed Table 1's G3 and G4) remain joint candidates: nothing separates them.
#pragma once

#include "core/pipeline/pipeline_stage.h"

namespace gearpath {

class LocalisationStage final : public PipelineStage {
 public:
  const char* name() const noexcept override { return "localisation"; }
  Status Configure(const MachineContext& machine, BlockWorkspace& work) override;
  RejectReason Process(StageContext& ctx) noexcept override;
};

}  // namespace gearpath
