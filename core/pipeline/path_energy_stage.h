// PathEnergyStage: what each transfer path carries in this block (seed Eq. 45,
// C_cj = H_d,cj F_j): its contribution energy over the analysis band (summed over channels)
// and its share, its energy on the mesh sideband lines h f_m +/- k f_s (the default
// dominant-path criterion, docs/diagnosis.md), and the FRF row where its contribution is
// largest (its indicator channel).
#pragma once

#include "core/pipeline/pipeline_stage.h"

namespace gearpath {

class PathEnergyStage final : public PipelineStage {
 public:
  const char* name() const noexcept override { return "path_energy"; }
  Status Configure(const MachineContext& machine, BlockWorkspace& work) override;
  RejectReason Process(StageContext& ctx) noexcept override;
};

}  // namespace gearpath
