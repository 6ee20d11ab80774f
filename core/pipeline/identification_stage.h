// IdentificationStage: the bearing forces F(f) per in-range bin, solving x = H_d F with the
// per-bin operator precomputed at Configure (MWI by default, seed Eqs. 40-43; Tikhonov or
// least squares selectable; core/inverse/identification_operator.h), and the figures of the
// inversion (median regularisation parameter and condition number, energy-weighted residual).
// Bins outside the FRF range get zero force and are counted.
//
// One pass over the bins (issue 9), IdentificationOperator::kChunkBins at a time: the chunk's
// responses are split into real and imaginary planes, its forces come from the contiguous
// precomputed operators (a vectorised kernel), and in the same pass, while they are in cache,
// the residual ||x - H F||^2 of the analysis-band bins. Then each path's contribution energy
// per FRF row, |H_cj|^2 |F_j|^2 over the analysis band and over the mesh sideband lines, as one
// streaming dot product per (path, row) over the |H|^2 table (frf_power_table.h; the
// path-energy stage turns them into shares and the criterion). With a parameter chosen per
// block (kGcv, kDiscrepancy) the chunk's bins go through Identify() one by one instead. With a
// precomputed operator the parameter and condition figures do not depend on the block: their
// medians are taken once, at Configure.
#pragma once

#include <memory>
#include <optional>
#include <vector>

#include "core/inverse/identification_operator.h"
#include "core/pipeline/frf_power_table.h"
#include "core/pipeline/pipeline_stage.h"

namespace gearpath {

class IdentificationStage final : public PipelineStage {
 public:
  const char* name() const noexcept override { return "identification"; }
  Status Configure(const MachineContext& machine, BlockWorkspace& work) override;
  RejectReason Process(StageContext& ctx) noexcept override;

 private:
  static constexpr std::size_t kChunk = IdentificationOperator::kChunkBins;
  // Forces of one chunk from the split responses, bin by bin through Identify() (parameter
  // chosen per block); accumulates the residual and the figures' scratch.
  void IdentifyChunkPerBin(BlockWorkspace& w, std::size_t chunk, std::size_t count) noexcept;

  std::optional<IdentificationOperator> op_;
  const FrfPowerTable* table_ = nullptr;  // the workspace's (BlockWorkspace::frf_table)
  // One chunk, split planes (identification_operator.h): responses channels x kChunk, forces
  // paths x kChunk.
  std::vector<double> x_re_, x_im_, f_re_, f_im_;
  // One path's |F|^2 per in-range bin on the analysis band, and on its sideband lines (0 off).
  std::vector<double> f2_band_, f2_side_;
  Eigen::VectorXcd x_;       // channels: responses of one bin (per-bin path)
  Eigen::VectorXcd forces_;  // paths: forces of one bin (per-bin path)
  // Block figures: fixed at Configure for a precomputed operator; else per block.
  std::vector<double> alpha_;  // in-range bins (median scratch)
  std::vector<double> condition_;
  std::size_t used_ = 0;
  double cond_max_ = 0.0;
  double static_alpha_median_ = 0.0;
  double static_condition_median_ = 0.0;
  double static_condition_max_ = 0.0;
  double residual_ = 0.0;  // sum of ||x - H F||^2 over the band bins, this block
};

}  // namespace gearpath
