#include "core/pipeline/speed_stage.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "core/diagnosis/dominant_path.h"
#include "core/diagnosis/speed_estimate.h"
#include "core/pipeline/block_workspace.h"
#include "core/pipeline/shape_scratch.h"
#include "core/pipeline/machine_context.h"

namespace gearpath {

Status SpeedStage::Configure(const MachineContext&, BlockWorkspace& work) {
  amplitude_.assign(work.bins, 0.0);
  return Status::Ok();
}

RejectReason SpeedStage::Process(StageContext& ctx) noexcept {
  BlockWorkspace& w = ctx.work;
  const AnalysisOptions& o = ctx.machine.setup.options;
  const AccelBlockView& block = ctx.block;
  double speed = 0.0;
  SpeedSource source = SpeedSource::kUnknown;
  if (block.speed_hz > 0.0 && std::isfinite(block.speed_hz)) {
    speed = block.speed_hz;
    source = block.speed_source == SpeedSource::kUnknown ? SpeedSource::kAcquisition
                                                         : block.speed_source;
  } else if (o.nominal_speed_hz > 0.0) {
    speed = o.nominal_speed_hz;
    source = SpeedSource::kConfiguration;
  } else {
    const std::size_t channels = ctx.machine.channels;
    for (std::size_t k = 0; k < w.bins; ++k) {
      double p = 0.0;
      for (std::size_t c = 0; c < channels; ++c) p += std::norm(ctx.scratch.spec[c * w.bins + k]);
      amplitude_[k] = std::sqrt(p);
    }
    SpeedSearch search;
    search.lo_hz = o.speed_search_lo_hz;
    search.hi_hz = o.speed_search_hi_hz;
    const SpeedEstimate est =
        EstimateSpeedFromMeshes(amplitude_, w.bin_hz, ctx.machine.mesh_orders, search);
    if (est.found) {
      speed = est.speed_hz;
      source = SpeedSource::kEstimated;
    }
  }
  w.speed_hz = speed;
  w.speed_source = source;
  ctx.out.speed_hz = speed;
  ctx.out.speed_source = source;
  for (std::size_t m = 0; m < w.meshes.size(); ++m) {
    const MeshLines& unit = ctx.machine.unit_meshes[m];
    w.meshes[m].mesh_hz = unit.mesh_hz * speed;
    w.meshes[m].shaft_hz = {unit.shaft_hz[0] * speed, unit.shaft_hz[1] * speed};
  }
  // The lines of this block's meshes (read from the identification pass on: the dominant-path
  // criterion's sidebands, the mesh tones).
  if (speed > 0.0) {
    BuildSidebandMask(w.bin_hz, w.meshes, o.sideband_orders, ctx.machine.band_lo,
                      ctx.machine.band_hi, 1.0, w.sideband_mask);
    BuildMeshHarmonicMask(w.bin_hz, w.meshes, 1.0, w.mesh_mask);
  } else {
    std::fill(w.sideband_mask.begin(), w.sideband_mask.end(), std::uint8_t{0});
    std::fill(w.mesh_mask.begin(), w.mesh_mask.end(), std::uint8_t{0});
  }
  return RejectReason::kNone;
}

}  // namespace gearpath
