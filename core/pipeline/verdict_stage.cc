#include "core/pipeline/verdict_stage.h"

#include <span>

#include "core/pipeline/block_workspace.h"
#include "core/pipeline/machine_context.h"
#include "core/pipeline/machine_state.h"

namespace gearpath {

Status VerdictStage::Configure(const MachineContext& machine, BlockWorkspace&) {
  const std::size_t shafts = machine.shaft_ratio.size();
  indicators_.assign(2 * shafts, 0.0);
  raw_thr_.assign(shafts, 0.0);
  rec_thr_.assign(shafts, 0.0);
  return Status::Ok();
}

RejectReason VerdictStage::Process(StageContext& ctx) noexcept {
  BlockWorkspace& w = ctx.work;
  const MachineContext& m = ctx.machine;
  MachineState& st = ctx.state;
  BlockResult& out = ctx.out;
  const std::size_t shafts = raw_thr_.size();
  const double speed = w.speed_hz;
  for (std::size_t s = 0; s < shafts; ++s) {
    indicators_[s] = out.shafts[s].raw;
    indicators_[shafts + s] = out.shafts[s].reconstructed;
  }
  HealthyBaseline& baseline = *st.envelope_baseline;
  const bool learning = !baseline.learned();
  if (learning && speed > 0.0) baseline.Add(indicators_);
  for (std::size_t s = 0; s < shafts; ++s) {
    raw_thr_[s] = learning ? 0.0 : baseline.thresholds()[s];
    rec_thr_[s] = learning ? 0.0 : baseline.thresholds()[shafts + s];
    out.shafts[s].raw_threshold = raw_thr_[s];
    out.shafts[s].reconstructed_threshold = rec_thr_[s];
  }
  VerdictInputs vin;
  vin.input_speed_hz = speed;
  vin.raw = std::span<const double>(indicators_.data(), shafts);
  vin.reconstructed = std::span<const double>(indicators_.data() + shafts, shafts);
  vin.raw_threshold = raw_thr_;
  vin.reconstructed_threshold = rec_thr_;
  vin.path_criterion = w.path_criterion;
  if (speed > 0.0) vin.mesh_evidence = w.mesh_evidence;
  vin.dominant_path = w.dominant;
  vin.alarm_factor = m.setup.options.alarm_factor;
  vin.learning = learning;
  DecideGearVerdict(m.topology, vin, out.verdict);
  if (!(speed > 0.0)) {
    out.verdict.state = learning ? FaultState::kLearning : FaultState::kNoFault;
    out.verdict.confidence = 0.0;
    out.verdict.reason.Assign(
        "input speed unknown (not in the block, not configured, no mesh lines to track): "
        "indicators not computed");
  }
  st.learning = !baseline.learned();
  return RejectReason::kNone;
}

}  // namespace gearpath
