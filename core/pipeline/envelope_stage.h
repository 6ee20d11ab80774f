// EnvelopeStage: the seed's envelope fault indicators (Algorithm 2, Table 5) of the measured
// signal and of the dominant path's reconstructed contribution at the indicator channel, per
// shaft, with the enhancement (reconstructed vs raw). Mesh tones are comb-removed from both
// alike first when AnalysisOptions::remove_mesh_tones is set.
#pragma once

#include <array>
#include <vector>

#include "core/pipeline/envelope_analysis.h"
#include "core/pipeline/pipeline_stage.h"

namespace gearpath {

class EnvelopeStage final : public PipelineStage {
 public:
  const char* name() const noexcept override { return "envelope"; }
  Status Configure(const MachineContext& machine, BlockWorkspace& work) override;
  RejectReason Process(StageContext& ctx) noexcept override;

 private:
  // The analysis, its plans and the signals are the scratch's (ShapeScratch::envelope, ...).
  std::vector<double> raw_;  // per shaft
  std::vector<double> rec_;
  std::vector<std::array<double, kIndicatorHarmonics>> raw_harmonics_;
  std::vector<std::array<double, kIndicatorHarmonics>> rec_harmonics_;
};

}  // namespace gearpath
