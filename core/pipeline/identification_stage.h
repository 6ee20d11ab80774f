// IdentificationStage: the bearing forces F(f) per in-range bin, solving x = H_d F with the
// per-bin operator precomputed at Configure (MWI by default, seed Eqs. 40-43; Tikhonov or
// least squares selectable; core/inverse/identification_operator.h), and the figures of the
// inversion (median regularisation parameter and condition number, energy-weighted residual).
// Bins outside the FRF range get zero force and are counted.
#pragma once

#include <Eigen/Dense>
#include <optional>
#include <vector>

#include "core/inverse/identification_operator.h"
#include "core/pipeline/pipeline_stage.h"

namespace gearpath {

class IdentificationStage final : public PipelineStage {
 public:
  const char* name() const noexcept override { return "identification"; }
  Status Configure(const MachineContext& machine, BlockWorkspace& work) override;
  RejectReason Process(StageContext& ctx) noexcept override;

 private:
  std::optional<IdentificationOperator> op_;
  Eigen::VectorXcd x_;               // channels: responses of one bin
  std::vector<double> alpha_;        // in-range bins (median scratch)
  std::vector<double> condition_;
};

}  // namespace gearpath
