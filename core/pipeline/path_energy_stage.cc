#include "core/pipeline/path_energy_stage.h"

#include <algorithm>
#include <complex>
#include <memory>
#include <utility>

#include "core/diagnosis/dominant_path.h"
#include "core/pipeline/block_workspace.h"
#include "core/pipeline/machine_context.h"
#include "core/pipeline/shared_frf_operators.h"

namespace gearpath {

Status PathEnergyStage::Configure(const MachineContext& m, BlockWorkspace& w) {
  const auto bins = static_cast<std::size_t>(w.map.frf.bins());
  if (m.setup.shared_frf) {
    auto power = m.setup.shared_frf->Power(w.n, m.setup.options.sample_rate_hz);
    if (!power) return Error{power.error()};
    frf_power_ = std::move(power.value());
  } else {
    frf_power_ = std::make_shared<const FrfPowerTable>(FrfPowerTable::Build(w.map));
  }
  if (frf_power_->paths != m.paths || frf_power_->channels != m.channels ||
      frf_power_->bins != bins) {
    return Error{"the FRF power table does not match the machine's FRF shape"};
  }
  band_force_.assign(bins, 0.0);
  sideband_force_.assign(bins, 0.0);
  return Status::Ok();
}

RejectReason PathEnergyStage::Process(StageContext& ctx) noexcept {
  BlockWorkspace& w = ctx.work;
  const MachineContext& m = ctx.machine;
  const AnalysisOptions& o = m.setup.options;
  if (w.speed_hz > 0.0) {
    BuildSidebandMask(w.bin_hz, w.meshes, o.sideband_orders, m.band_lo, m.band_hi, 1.0,
                      w.sideband_mask);
    BuildMeshHarmonicMask(w.bin_hz, w.meshes, 1.0, w.mesh_mask);
  } else {
    std::fill(w.sideband_mask.begin(), w.sideband_mask.end(), std::uint8_t{0});
    std::fill(w.mesh_mask.begin(), w.mesh_mask.end(), std::uint8_t{0});
  }
  const auto bins = static_cast<std::size_t>(w.map.frf.bins());
  for (std::size_t p = 0; p < m.paths; ++p) {
    const auto pi = static_cast<Eigen::Index>(p);
    for (std::size_t i = 0; i < bins; ++i) {
      const std::size_t k = w.map.first_bin + i;
      const double f2 = w.band_mask[k] ? std::norm(w.forces(pi, static_cast<Eigen::Index>(i))) : 0.0;
      band_force_[i] = f2;
      sideband_force_[i] = w.sideband_mask[k] ? f2 : 0.0;
    }
    double band = 0.0;
    double side = 0.0;
    double best_e = -1.0;
    int best = 0;
    for (std::size_t c = 0; c < m.channels; ++c) {
      const float* power = frf_power_->Row(p, c);
      double channel_energy = 0.0;
      double channel_side = 0.0;
      for (std::size_t i = 0; i < bins; ++i) {
        channel_energy += static_cast<double>(power[i]) * band_force_[i];
        channel_side += static_cast<double>(power[i]) * sideband_force_[i];
      }
      side += channel_side;
      band += channel_energy;
      if (channel_energy > best_e) {
        best_e = channel_energy;
        best = static_cast<int>(c);
      }
    }
    w.path_energy[p] = band;
    w.path_criterion[p] =
        o.criterion == AnalysisOptions::DominantCriterion::kBandEnergy ? band : side;
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
