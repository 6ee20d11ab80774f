// DominantPathStage: which transfer path carries the fault (seed Sect. 4.2), judged by the
// configured criterion (sideband energy by default, band energy, or each path's own envelope
// indicator), as its EXCESS over the path's healthy level when a baseline is learned
// (AnalysisOptions::criterion_over_baseline); the indicator channel; and the
// dominant path's contribution back in time at every channel (Algorithm 2's first step).
#pragma once

#include <array>
#include <optional>
#include <vector>

#include "core/pipeline/envelope_analysis.h"
#include "core/pipeline/pipeline_stage.h"

namespace gearpath {

class DominantPathStage final : public PipelineStage {
 public:
  const char* name() const noexcept override { return "dominant_path"; }
  Status Configure(const MachineContext& machine, BlockWorkspace& work) override;
  RejectReason Process(StageContext& ctx) noexcept override;

 private:
  void IndicatorCriterion(StageContext& ctx) noexcept;

  // The `indicator` criterion (its analysis and signal are the scratch's): per shaft.
  bool indicator_criterion_ = false;
  std::vector<double> indicator_;
  std::vector<std::array<double, kIndicatorHarmonics>> harmonics_;
};

}  // namespace gearpath
