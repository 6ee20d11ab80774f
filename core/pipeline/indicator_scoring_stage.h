// IndicatorScoringStage: every condition indicator judged against the machine's own healthy
// baseline (DESIGN.md: never against zero). The first baseline_blocks accepted blocks with a
// known speed are the healthy baseline: per indicator a robust location and scale (median,
// Qn or MAD with a relative floor, on a log scale: every indicator is a positive ratio, energy or
// moment; core/diagnosis/robust_baseline.h). Afterwards each indicator gets a robust z-score,
// and the block's score is the largest DIRECTIONAL z (a rise for indicators that damage
// raises; either way for the mesh-harmonic amplitude and the TSA level, which a broken tooth
// can lower) over the measured channels and the measured transfer signatures (the identified
// forces', the path contributions' and the envelope indicators get a z and are published, but
// do not raise an alarm: too noisy, or, for the envelope, measured in a band that moves from
// block to block), taken over the last two scored blocks (the sum of their z over sqrt 2, the
// previous one clipped) and divided by the limit that keeps a healthy block's chance of any
// exceedance at AnalysisOptions::false_alarm_rate. Scores are kept per slot and per rate group
// for the localisation stage. The envelope indicators (seed) also keep their published mean +
// k sigma thresholds (core/diagnosis/healthy_baseline.h). A block whose speed lies outside the
// speeds the baseline learned at (widened by AnalysisOptions::speed_tolerance) is not judged.
#pragma once

#include <vector>

#include "core/pipeline/pipeline_stage.h"

namespace gearpath {

class IndicatorScoringStage final : public PipelineStage {
 public:
  const char* name() const noexcept override { return "indicator_scoring"; }
  Status Configure(const MachineContext& machine, BlockWorkspace& work) override;
  RejectReason Process(StageContext& ctx) noexcept override;

 private:
  void Learn(StageContext& ctx) noexcept;
  void Score(StageContext& ctx) noexcept;
  void Publish(StageContext& ctx) noexcept;

  std::vector<std::uint8_t> two_sided_;  // per indicator entry
  std::vector<double> envelope_;         // raw (shafts) then reconstructed (shafts)
};

}  // namespace gearpath
