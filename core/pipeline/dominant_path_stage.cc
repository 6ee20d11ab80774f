#include "core/pipeline/dominant_path_stage.h"

#include <algorithm>
#include <utility>

#include "core/diagnosis/dominant_path.h"
#include "core/pipeline/block_workspace.h"
#include "core/pipeline/machine_context.h"
#include "core/pipeline/machine_state.h"
#include "core/pipeline/shape_scratch.h"

namespace gearpath {

Status DominantPathStage::Configure(const MachineContext& machine, BlockWorkspace&) {
  indicator_criterion_ =
      machine.setup.options.criterion == AnalysisOptions::DominantCriterion::kIndicator;
  if (indicator_criterion_) {
    indicator_.assign(machine.shaft_ratio.size(), 0.0);
    harmonics_.assign(machine.shaft_ratio.size(), {});
  }
  return Status::Ok();
}

// Each path's own fault indicator (max over shafts) at its best channel.
void DominantPathStage::IndicatorCriterion(StageContext& ctx) noexcept {
  BlockWorkspace& w = ctx.work;
  ShapeScratch& s = ctx.scratch;
  BlockEnvelopeBand band;
  for (std::size_t p = 0; p < ctx.machine.paths; ++p) {
    w.Contribution(p, static_cast<std::size_t>(w.best_channel[p]), s.one_spec);
    (void)s.inverse->Process(s.one_spec, s.signal);
    s.envelope->Process(ctx.machine, s.signal, w.speed_hz, band, indicator_, harmonics_);
    w.path_criterion[p] = *std::max_element(indicator_.begin(), indicator_.end());
  }
}

RejectReason DominantPathStage::Process(StageContext& ctx) noexcept {
  BlockWorkspace& w = ctx.work;
  MachineState& st = ctx.state;
  const MachineContext& m = ctx.machine;
  const AnalysisOptions& o = m.setup.options;
  const bool have_speed = w.speed_hz > 0.0;
  if (indicator_criterion_ && have_speed) IndicatorCriterion(ctx);

  // Excess over the healthy level (see AnalysisOptions::criterion_over_baseline).
  if (o.criterion_over_baseline && st.learning && have_speed) {
    st.band.criterion_healthy.Add(w.path_criterion);
  } else if (o.criterion_over_baseline && st.band.criterion_healthy.blocks > 0) {
    bool any = false;
    for (std::size_t p = 0; p < m.paths; ++p) {
      any = any || w.path_criterion[p] > st.band.criterion_healthy.mean[p];
    }
    if (any) {
      for (std::size_t p = 0; p < m.paths; ++p) {
        w.path_criterion[p] =
            std::max(0.0, w.path_criterion[p] - st.band.criterion_healthy.mean[p]);
      }
    }
  }
  int dominant = SelectDominantPath(w.path_criterion);
  BlockResult& out = ctx.out;
  if (dominant < 0) {
    // The criterion is zero on every path (sideband energy without a known speed): fall back
    // to band energy, and say so in the result, rather than publish a dominant path with no
    // name. The path-energy stage has rejected blocks with no energy in the band at all.
    std::copy(w.path_energy.begin(), w.path_energy.end(), w.path_criterion.begin());
    dominant = SelectDominantPath(w.path_criterion);
    out.criterion = AnalysisOptions::DominantCriterion::kBandEnergy;
  }
  w.dominant = dominant;
  out.dominant_path = dominant;
  out.dominant_path_name =
      dominant >= 0 ? std::string_view(m.setup.frf_set.paths[static_cast<std::size_t>(dominant)].name)
                    : std::string_view{};
  for (std::size_t p = 0; p < m.paths; ++p) {
    out.paths[p].name = m.setup.frf_set.paths[p].name;
    out.paths[p].bearing = m.setup.frf_set.paths[p].bearing;
    out.paths[p].energy = w.path_energy[p];
    out.paths[p].share = w.path_share[p];
    out.paths[p].criterion = w.path_criterion[p];
  }

  // Its contribution in time at a channel is made only if asked for (DominantTime()).
  w.dominant_time_row = BlockWorkspace::kNoRow;
  w.indicator_channel =
      dominant >= 0
          ? static_cast<std::size_t>(w.best_channel[static_cast<std::size_t>(dominant)])
          : (o.indicator_channel >= 0 ? static_cast<std::size_t>(o.indicator_channel) : 0);
  out.indicator_channel = static_cast<int>(w.indicator_channel);
  return RejectReason::kNone;
}

}  // namespace gearpath
