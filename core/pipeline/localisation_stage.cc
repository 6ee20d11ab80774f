#include "core/pipeline/localisation_stage.h"

#include <algorithm>
#include <array>
#include <vector>

#include "core/diagnosis/gear_condition_indicators.h"
#include "core/pipeline/block_workspace.h"
#include "core/pipeline/machine_context.h"
#include "core/pipeline/machine_state.h"

namespace gearpath {

Status LocalisationStage::Configure(const MachineContext& machine, BlockWorkspace&) {
  if (machine.topology.gear_names.size() > 31) {
    return Error{"localisation: more than 31 gears in the train"};
  }
  group_excess_.assign(machine.rate_groups.size(), 0.0);
  group_clear_.assign(machine.rate_groups.size(), 0);
  return Status::Ok();
}

namespace {

// Transfer-signature evidence for each mesh of rate group g, from the measured channels
// (fractions summing to 1; zeros when nothing rose). A tooth fault on mesh m adds sideband
// energy that travels like m's own tone (through m's transfer): near the OTHER meshes'
// harmonics that energy does not point along their tones, so it rises in their orthogonal part.
// Evidence for m = the other meshes' orthogonal rise. Near m's own harmonics the fault's lines are
// parallel to m's tone, but so are m's healthy eccentricity sidebands, whose block-to-block
// variation buries the fault's parallel rise: the parallel rise decides only when nothing rose
// orthogonally anywhere. Each rise is its robust z (clamped at 0), in units of that
// neighbourhood's own healthy spread, and each mesh harmonic's neighbourhood is one such rise
// (summed over the harmonics): in energy units the neighbourhood the housing transmits most
// loudly outvoted the others, first between the meshes, then between one mesh's harmonics
// (docs/diagnosis.md section 13, sixteenth session). The identified forces' signatures are
// published but not used: on the evaluation families they named the mesh less often than the
// measured channels alone (docs/diagnosis.md section 11).
std::array<double, kMaxMeshesPerShaft> MeshEvidence(const MachineContext& m,
                                                    const BlockWorkspace& w,
                                                    std::size_t g) noexcept {
  const std::size_t meshes = m.rate_groups[g].meshes.size();
  std::array<double, kMaxMeshesPerShaft> evidence{};
  if (meshes < 2) return evidence;
  std::array<double, kMaxMeshesPerShaft> par{}, orth{};
  double orth_total = 0.0;
  for (const SignatureSlot& ss : m.signature_slots) {
    if (ss.group != g || ss.forces) continue;
    for (std::size_t h = 0; h < static_cast<std::size_t>(kSignatureHarmonics); ++h) {
      par[ss.mesh] += std::max(0.0, w.z[ss.tracked_offset + 2 * h]);
      orth[ss.mesh] += std::max(0.0, w.z[ss.tracked_offset + 2 * h + 1]);
    }
    orth_total += orth[ss.mesh];
  }
  double total = 0.0;
  for (std::size_t i = 0; i < meshes; ++i) {
    if (orth_total > 0.0) {
      for (std::size_t j = 0; j < meshes; ++j) {
        if (j != i) evidence[i] += orth[j] / static_cast<double>(meshes - 1);
      }
    } else {
      evidence[i] = par[i];
    }
    total += evidence[i];
  }
  if (!(total > 0.0)) return {};
  for (std::size_t i = 0; i < meshes; ++i) evidence[i] /= total;
  return evidence;
}

// Evidence accumulated over a fault's blocks: added on a block at or above the clear level,
// halved on a quiet one, so one block's noisy evidence cannot decide alone.
void Accumulate(double& sum, double block_evidence, bool counts) noexcept {
  sum = counts ? sum + block_evidence : 0.5 * sum;
}

int GearMesh(const MachineContext& m, int gear) noexcept {
  return m.topology.gear_mesh[static_cast<std::size_t>(gear)];
}

}  // namespace

RejectReason LocalisationStage::Process(StageContext& ctx) noexcept {
  BlockWorkspace& w = ctx.work;
  const MachineContext& m = ctx.machine;
  MachineState& st = ctx.state;
  BlockWorkspace::Localisation& loc = w.localisation;
  loc = {};
  BlockLocalisation& record = ctx.out.localisation;
  record = {};
  // Not judged (learning, no speed, a speed the baseline did not learn at): evidence held.
  if (!ctx.out.score.judged) return RejectReason::kNone;
  const std::size_t groups = m.rate_groups.size();

  // This block's shaft evidence: per group the EXCLUSIVE residual energy's rise over healthy,
  // summed over the measured channels (the same unit for every group; a fault's comb is whole
  // only at its own shaft's rate). A group's rise counts only when one of its channels rose
  // clearly (z >= kShaftEvidenceZ): half of all healthy blocks sit above the median, so an
  // ungated sum let noise name the shaft whenever the fault's comb did not reach the exclusive
  // orders, and the block's score never decided (docs/diagnosis.md section 11).
  std::fill(group_excess_.begin(), group_excess_.end(), 0.0);
  std::fill(group_clear_.begin(), group_clear_.end(), 0);
  for (std::size_t s = 0; s < m.condition_slots.size(); ++s) {
    const ConditionSlot& cs = m.condition_slots[s];
    if (!w.slot_valid[s] || m.condition_signals[cs.signal].source != ConditionSource::kMeasured) {
      continue;
    }
    group_excess_[cs.group] += w.excess[m.tracked_offset + s];  // exclusive residual (tracked)
    if (w.z[m.tracked_offset + s] >= kShaftEvidenceZ) group_clear_[cs.group] = 1;
  }
  for (std::size_t g = 0; g < groups; ++g) {
    if (!group_clear_[g]) group_excess_[g] = 0.0;
  }
  // The shaft evidence accumulates over the blocks at or above the clear level (a fault's
  // blocks) and decays by half on each quiet block, so one block's noisy evidence cannot name
  // the shaft.
  const bool counts = ctx.out.score.score >= m.setup.options.clear_level;
  double total_excess = 0.0;
  for (std::size_t g = 0; g < groups; ++g) {
    double& sum = st.group_excess_sum[g];
    Accumulate(sum, group_excess_[g], counts);
    total_excess += sum;
  }

  // 1. The rate group: the largest accumulated clear exclusive-residual rise; by the groups'
  // scores when none rose clearly.
  std::size_t g = 0;
  for (std::size_t i = 1; i < groups; ++i) {
    if (st.group_excess_sum[i] > st.group_excess_sum[g]) g = i;
  }
  if (!(total_excess > 0.0)) {
    g = static_cast<std::size_t>(std::max_element(w.group_score.begin(), w.group_score.end()) -
                                 w.group_score.begin());
  }
  const RateGroup& rg = m.rate_groups[g];
  loc.group = static_cast<int>(g);
  loc.mesh_count = static_cast<int>(rg.meshes.size());
  record.group = loc.group;
  record.group_count = static_cast<int>(groups);
  for (std::size_t i = 0; i < groups && i < BlockLocalisation::kMaxGroups; ++i) {
    record.shaft_evidence[i] = group_excess_[i];
    record.shaft_evidence_accumulated[i] = st.group_excess_sum[i];
  }
  for (const SignatureSlot& ss : m.signature_slots) {
    if (ss.group >= BlockLocalisation::kMaxGroups || ss.mesh >= BlockLocalisation::kMaxMeshes) {
      continue;
    }
    auto& e = record.signature_excess[ss.group][ss.mesh];
    if (ss.forces) {
      e[2] = w.excess[ss.offset];
      e[3] = w.excess[ss.offset + 1];
      continue;
    }
    e[0] = e[1] = 0.0;
    for (std::size_t h = 0; h < static_cast<std::size_t>(kSignatureHarmonics); ++h) {
      e[0] += w.excess[ss.tracked_offset + 2 * h];
      e[1] += w.excess[ss.tracked_offset + 2 * h + 1];
    }
  }

  // 2. The mesh, when the group's gears sit on several: the transfer-signature evidence
  // accumulated like the shaft's (every group's, so that a later block naming another group
  // finds its sums), as fractions of their total.
  for (std::size_t i = 0; i < groups; ++i) {
    if (m.rate_groups[i].meshes.size() < 2) continue;
    // A quiet block only halves the sums: its evidence is not needed.
    const std::array<double, kMaxMeshesPerShaft> block =
        counts ? MeshEvidence(m, w, i) : std::array<double, kMaxMeshesPerShaft>{};
    double* sum = st.mesh_evidence_sum.data() + i * kMaxMeshesPerShaft;
    for (std::size_t k = 0; k < kMaxMeshesPerShaft; ++k) Accumulate(sum[k], block[k], counts);
  }
  std::array<double, kMaxMeshesPerShaft> evidence{};
  {
    const double* sum = st.mesh_evidence_sum.data() + g * kMaxMeshesPerShaft;
    double total = 0.0;
    for (std::size_t k = 0; k < rg.meshes.size(); ++k) total += sum[k];
    if (total > 0.0) {
      for (std::size_t k = 0; k < rg.meshes.size(); ++k) evidence[k] = sum[k] / total;
    }
  }
  record.mesh_count = static_cast<int>(rg.meshes.size());
  for (std::size_t i = 0; i < rg.meshes.size() && i < BlockLocalisation::kMaxMeshes; ++i) {
    record.mesh_evidence[i] = evidence[i];
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

  // 3. The gears of the group on the chosen mesh(es); the most likely one sits on the mesh
  // with the strongest evidence.
  std::size_t top = 0;
  for (std::size_t i = 1; i < rg.meshes.size(); ++i) {
    if (evidence[i] > evidence[top]) top = i;
  }
  const int best_mesh = rg.meshes.empty() ? -1 : rg.meshes[top];
  for (std::size_t i = 0; i < rg.gears.size(); ++i) {
    bool on_chosen = rg.meshes.empty() || rg.gear_meshes[i] < 0;
    for (std::size_t j = 0; j < rg.meshes.size(); ++j) {
      on_chosen = on_chosen || ((chosen >> j & 1u) && rg.gear_meshes[i] == rg.meshes[j]);
    }
    if (!on_chosen) continue;
    loc.gear_mask |= 1u << rg.gears[i];
    if (loc.best_gear < 0 ||
        (rg.gear_meshes[i] == best_mesh && GearMesh(m, loc.best_gear) != best_mesh)) {
      loc.best_gear = rg.gears[i];
    }
  }
  return RejectReason::kNone;
}

}  // namespace gearpath
