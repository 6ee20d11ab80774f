// SpeedStage: the input-shaft speed of the block, and every mesh's lines at that speed.
// Source, in order: the block (acquisition tachometer or other), the configured nominal speed,
// else mesh-frequency tracking on the block's spectra (core/diagnosis/speed_estimate.h).
// Without a speed the rate-based stages have nothing to work on; the verdict says so.
#pragma once

#include <vector>

#include "core/pipeline/pipeline_stage.h"

namespace gearpath {

class SpeedStage final : public PipelineStage {
 public:
  const char* name() const noexcept override { return "speed"; }
  Status Configure(const MachineContext& machine, BlockWorkspace& work) override;
  RejectReason Process(StageContext& ctx) noexcept override;

 private:
  std::vector<double> amplitude_;  // bins: RMS over channels (mesh tracking)
};

}  // namespace gearpath
