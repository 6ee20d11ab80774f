// AlarmStage: the verdict. The block's score (IndicatorScoringStage) and its localisation
// (LocalisationStage) go through the machine's alarm model (core/diagnosis/alarm_model.h:
// k-of-n persistence, hysteresis, clear delay), so the published state is stable block to
// block and a single noisy block raises nothing; the gear named is the one the recent
// exceeding blocks voted for most (latched), not this block's alone. `learning` until the
// healthy baseline is complete; without a speed no indicator is computed and the state holds.
#pragma once

#include "core/pipeline/pipeline_stage.h"

namespace gearpath {

class AlarmStage final : public PipelineStage {
 public:
  const char* name() const noexcept override { return "alarm"; }
  Status Configure(const MachineContext& machine, BlockWorkspace& work) override;
  RejectReason Process(StageContext& ctx) noexcept override;
};

}  // namespace gearpath
