#include "core/pipeline/path_energy_stage.h"

#include <algorithm>
#include <utility>

#include "core/diagnosis/dominant_path.h"
#include "core/pipeline/block_workspace.h"
#include "core/pipeline/machine_context.h"

namespace gearpath {

Status PathEnergyStage::Configure(const MachineContext& m, BlockWorkspace& w) {
  frf_power_ = w.frf_table.get();
  if (frf_power_ == nullptr || frf_power_->paths != m.paths || frf_power_->channels != m.channels ||
      frf_power_->bins != static_cast<std::size_t>(w.map.frf.bins())) {
    return Error{"the FRF power table does not match the machine's FRF shape"};
  }
  return Status::Ok();
}

RejectReason PathEnergyStage::Process(StageContext& ctx) noexcept {
  BlockWorkspace& w = ctx.work;
  const MachineContext& m = ctx.machine;
  const AnalysisOptions& o = m.setup.options;
  for (std::size_t p = 0; p < m.paths; ++p) {
    double band = 0.0;
    double best_e = -1.0;
    int best = 0;
    for (std::size_t c = 0; c < m.channels; ++c) {
      const double channel_energy = w.path_channel_energy[p * m.channels + c];
      band += channel_energy;
      if (channel_energy > best_e) {
        best_e = channel_energy;
        best = static_cast<int>(c);
      }
    }
    w.path_energy[p] = band;
    w.path_criterion[p] = o.criterion == AnalysisOptions::DominantCriterion::kBandEnergy
                              ? band
                              : w.path_sideband_energy[p];
    w.best_channel[p] = o.indicator_channel >= 0 ? o.indicator_channel : best;
  }
  EnergyShares(w.path_energy, w.path_share);
  // Nothing in the analysis band (e.g. a channel pair carrying only DC): no path can be
  // dominant and every later figure would be 0/0. Rejected, so no result names an empty path.
  bool any = false;
  for (std::size_t p = 0; p < m.paths; ++p) any = any || w.path_energy[p] > 0.0;
  if (!any) {
    ctx.message.Format("no transfer path carries energy in the analysis band %g..%g Hz", m.band_lo,
                       m.band_hi);
    return RejectReason::kNoSignalInBand;
  }
  return RejectReason::kNone;
}

}  // namespace gearpath
