// PathEnergyStage: what each transfer path carries in this block (seed Eq. 45,
// C_cj = H_d,cj F_j): its contribution energy over the analysis band (summed over channels)
// and its share, its energy on the mesh sideband lines h f_m +/- k f_s (the default
// dominant-path criterion, docs/diagnosis.md), and the FRF row where its contribution is
// largest (its indicator channel).
//
// Since |H F|^2 = |H|^2 |F|^2, the FRF's power |H_cj|^2 is laid out once per block shape,
// contiguous per (path, channel) over the in-range bins (float: energies need no more than 7
// digits), and each block costs two dot products per (path, channel) instead of a walk over
// the per-bin FRF matrices.
#pragma once

#include <vector>

#include "core/pipeline/pipeline_stage.h"

namespace gearpath {

class PathEnergyStage final : public PipelineStage {
 public:
  const char* name() const noexcept override { return "path_energy"; }
  Status Configure(const MachineContext& machine, BlockWorkspace& work) override;
  RejectReason Process(StageContext& ctx) noexcept override;

 private:
  std::vector<float> frf_power_;  // (path * channels + channel) * bins + bin: |H|^2
  std::vector<double> band_force_;      // in-range bins: |F_j|^2 inside the analysis band
  std::vector<double> sideband_force_;  // in-range bins: |F_j|^2 on the sideband lines
};

}  // namespace gearpath
