#include "core/pipeline/localisation_stage.h"

#include <algorithm>
#include <array>

#include "core/diagnosis/gear_condition_indicators.h"
#include "core/pipeline/block_workspace.h"
#include "core/pipeline/machine_context.h"
#include "core/pipeline/machine_state.h"

namespace gearpath {

Status LocalisationStage::Configure(const MachineContext& machine, BlockWorkspace&) {
  if (machine.topology.gear_names.size() > 31) {
    return Error{"localisation: more than 31 gears in the train"};
  }
  return Status::Ok();
}

RejectReason LocalisationStage::Process(StageContext& ctx) noexcept {
  BlockWorkspace& w = ctx.work;
  const MachineContext& m = ctx.machine;
  BlockWorkspace::Localisation& loc = w.localisation;
  loc = {};
  if (ctx.out.score.limit_z <= 0.0) return RejectReason::kNone;  // not scored (learning)
  const double limit = ctx.out.score.limit_z;

  // 1. The rate group.
  const auto best = std::max_element(w.group_score.begin(), w.group_score.end());
  if (best == w.group_score.end()) return RejectReason::kNone;
  const auto g = static_cast<std::size_t>(best - w.group_score.begin());
  const RateGroup& rg = m.rate_groups[g];
  loc.group = static_cast<int>(g);
  loc.mesh_count = static_cast<int>(rg.meshes.size());

  // 2. Evidence per mesh of the group.
  std::array<double, kMaxMeshesPerShaft> evidence{};
  const std::size_t exclusive = rg.indicator_names.size() - 1;
  const auto residual_rms = static_cast<std::size_t>(ConditionIndicator::kResidualRms);
  for (std::size_t s = 0; s < m.condition_slots.size(); ++s) {
    const ConditionSlot& cs = m.condition_slots[s];
    if (cs.group != g || !w.slot_valid[s]) continue;
    const double* z = w.z.data() + cs.offset;
    for (std::size_t i = 0; i < rg.meshes.size(); ++i) {
      evidence[i] = std::max(evidence[i], z[kConditionIndicatorCount + i] / limit);
    }
    const ConditionSignal& sig = m.condition_signals[cs.signal];
    if (sig.source == ConditionSource::kMeasured) continue;
    const auto& seen = m.topology.path_meshes[static_cast<std::size_t>(sig.index)];
    if (seen.size() != 1) continue;  // a bearing between two meshes speaks for neither
    const double end = std::max(z[exclusive], z[residual_rms]) / limit;
    for (std::size_t i = 0; i < rg.meshes.size(); ++i) {
      if (rg.meshes[i] == seen.front()) evidence[i] = std::max(evidence[i], end);
    }
  }
  std::uint32_t chosen = 0;  // bit i = rg.meshes[i]
  if (rg.meshes.size() == 1) {
    chosen = 1u;
    loc.mesh = rg.meshes.front();
  } else if (rg.meshes.size() > 1) {
    std::size_t first = 0;
    for (std::size_t i = 1; i < rg.meshes.size(); ++i) {
      if (evidence[i] > evidence[first]) first = i;
    }
    double second = 0.0;
    for (std::size_t i = 0; i < rg.meshes.size(); ++i) {
      if (i != first) second = std::max(second, evidence[i]);
    }
    loc.mesh_evidence = evidence[first];
    loc.other_evidence = second;
    const double separation = m.setup.options.mesh_separation;
    if (evidence[first] > 0.0 && evidence[first] >= separation * second) {
      chosen = 1u << first;
      loc.mesh = rg.meshes[first];
    } else {
      for (std::size_t i = 0; i < rg.meshes.size(); ++i) {
        if (evidence[i] * separation >= evidence[first]) chosen |= 1u << i;
      }
    }
  }

  // 3. The gears of the group on the chosen mesh(es).
  for (std::size_t i = 0; i < rg.gears.size(); ++i) {
    bool on_chosen = rg.meshes.empty() || rg.gear_meshes[i] < 0;
    for (std::size_t j = 0; j < rg.meshes.size(); ++j) {
      on_chosen = on_chosen || ((chosen >> j & 1u) && rg.gear_meshes[i] == rg.meshes[j]);
    }
    if (on_chosen) loc.gear_mask |= 1u << rg.gears[i];
  }
  return RejectReason::kNone;
}

}  // namespace gearpath
