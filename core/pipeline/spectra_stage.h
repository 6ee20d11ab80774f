// SpectraStage: the block's samples, reordered to FRF rows and converted to double, and their
// one-sided amplitude spectra (one real FFT per channel, no window: core/dsp/spectrum.h).
// First arrow of the data flow; everything downstream reads ShapeScratch::time and ::spec (the
// FFT plan is the scratch's too: the stage keeps nothing per machine).
#pragma once

#include "core/pipeline/pipeline_stage.h"

namespace gearpath {

class SpectraStage final : public PipelineStage {
 public:
  const char* name() const noexcept override { return "spectra"; }
  Status Configure(const MachineContext& machine, BlockWorkspace& work) override;
  RejectReason Process(StageContext& ctx) noexcept override;
};

}  // namespace gearpath
