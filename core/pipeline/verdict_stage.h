// VerdictStage: the envelope indicators judged against the machine's healthy baseline
// (learned from its first accepted blocks, or configured), and the suspected gear
// (core/diagnosis/gear_verdict.h). While the baseline is incomplete the verdict is `learning`.
#pragma once

#include <vector>

#include "core/pipeline/pipeline_stage.h"

namespace gearpath {

class VerdictStage final : public PipelineStage {
 public:
  const char* name() const noexcept override { return "verdict"; }
  Status Configure(const MachineContext& machine, BlockWorkspace& work) override;
  RejectReason Process(StageContext& ctx) noexcept override;

 private:
  std::vector<double> indicators_;  // raw (shafts) then reconstructed (shafts)
  std::vector<double> raw_thr_;
  std::vector<double> rec_thr_;
};

}  // namespace gearpath
