// PathEnergyStage: what each transfer path carries in this block (seed Eq. 45,
// C_cj = H_d,cj F_j): its contribution energy over the analysis band (summed over channels)
// and its share, its energy on the mesh sideband lines h f_m +/- k f_s (the default
// dominant-path criterion, docs/diagnosis.md), and the FRF row where its contribution is
// largest (its indicator channel).
//
// Since |H F|^2 = |H|^2 |F|^2, the energies are sums of |H_cj|^2 (frf_power_table.h, laid out
// once per block shape and shared by every machine on a shared FRF set) times |F_j|^2; the
// identification stage accumulates them in its pass over the bins, while the forces are in
// cache (BlockWorkspace::path_channel_energy, path_sideband_energy). This stage turns them into
// the published energies, shares, criterion and indicator channels.
#pragma once

#include "core/pipeline/frf_power_table.h"
#include "core/pipeline/pipeline_stage.h"

namespace gearpath {

class PathEnergyStage final : public PipelineStage {
 public:
  const char* name() const noexcept override { return "path_energy"; }
  Status Configure(const MachineContext& machine, BlockWorkspace& work) override;
  RejectReason Process(StageContext& ctx) noexcept override;

  // The |H|^2 table in use (tests: machines on one shared FRF set hold the same one).
  const FrfPowerTable* frf_power() const noexcept { return frf_power_; }

 private:
  const FrfPowerTable* frf_power_ = nullptr;  // the workspace's (BlockWorkspace::frf_table)
};

}  // namespace gearpath
