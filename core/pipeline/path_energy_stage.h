// PathEnergyStage: what each transfer path carries in this block (seed Eq. 45,
// C_cj = H_d,cj F_j): its contribution energy over the analysis band (summed over channels)
// and its share, its energy on the mesh sideband lines h f_m +/- k f_s (the default
// dominant-path criterion, docs/diagnosis.md), and the FRF row where its contribution is
// largest (its indicator channel).
//
// Since |H F|^2 = |H|^2 |F|^2, the FRF's power |H_cj|^2 is laid out once per block shape
// (frf_power_table.h; one table for every machine on a shared FRF set), and each block costs
// two dot products per (path, channel) instead of a walk over the per-bin FRF matrices.
#pragma once

#include <memory>
#include <vector>

#include "core/pipeline/frf_power_table.h"
#include "core/pipeline/pipeline_stage.h"

namespace gearpath {

class PathEnergyStage final : public PipelineStage {
 public:
  const char* name() const noexcept override { return "path_energy"; }
  Status Configure(const MachineContext& machine, BlockWorkspace& work) override;
  RejectReason Process(StageContext& ctx) noexcept override;

  // The |H|^2 table in use (tests: machines on one shared FRF set hold the same one).
  const FrfPowerTable* frf_power() const noexcept { return frf_power_.get(); }

 private:
  std::shared_ptr<const FrfPowerTable> frf_power_;  // read-only, maybe shared
  std::vector<double> band_force_;      // in-range bins: |F_j|^2 inside the analysis band
  std::vector<double> sideband_force_;  // in-range bins: |F_j|^2 on the sideband lines
};

}  // namespace gearpath
