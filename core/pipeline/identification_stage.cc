#include "core/pipeline/identification_stage.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "core/pipeline/block_workspace.h"
#include "core/pipeline/machine_context.h"
#include "core/pipeline/shared_frf_operators.h"

namespace gearpath {
namespace {

// Median of the first n values of `v` (reorders them). 0 for n == 0.
double MedianInPlace(std::vector<double>& v, std::size_t n) noexcept {
  if (n == 0) return 0.0;
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(n / 2);
  std::nth_element(v.begin(), mid, v.begin() + static_cast<std::ptrdiff_t>(n));
  return *mid;
}

}  // namespace

Status IdentificationStage::Configure(const MachineContext& machine, BlockWorkspace& work) {
  const IdentificationOptions& options = machine.setup.options.identification;
  // Machines on one shared FRF set share the per-bin operators; each keeps its own workspace.
  auto op = machine.setup.shared_frf
                ? machine.setup.shared_frf->Operator(work.n, work.map.sample_rate_hz, options)
                : IdentificationOperator::Create(*work.map.in_range, options);
  if (!op) return Error{"identification operator: " + op.error()};
  op_.emplace(std::move(op.value()));
  const auto in_range = static_cast<std::size_t>(work.map.frf.bins());
  x_ = Eigen::VectorXcd::Zero(static_cast<Eigen::Index>(machine.channels));
  alpha_.assign(in_range, 0.0);
  condition_.assign(in_range, 0.0);
  return Status::Ok();
}

RejectReason IdentificationStage::Process(StageContext& ctx) noexcept {
  BlockWorkspace& w = ctx.work;
  const std::size_t channels = ctx.machine.channels;
  const Eigen::Index in_range = w.map.frf.bins();
  double res_num = 0.0;
  double res_den = 0.0;
  std::size_t used = 0;
  double cond_max = 0.0;
  for (Eigen::Index i = 0; i < in_range; ++i) {
    const std::size_t k = w.map.first_bin + static_cast<std::size_t>(i);
    double x2 = 0.0;
    for (std::size_t c = 0; c < channels; ++c) {
      x_[static_cast<Eigen::Index>(c)] = w.spec[c * w.bins + k];
      x2 += std::norm(w.spec[c * w.bins + k]);
    }
    BinFigures fig;  // read in this bin only: Identify() sets every field
    if (op_->Identify(i, x_, w.forces.col(i), &fig) != IdentifyStatus::kOk) {
      w.forces.col(i).setZero();
      continue;
    }
    if (w.band_mask[k]) {
      res_num += fig.relative_residual * fig.relative_residual * x2;
      res_den += x2;
    }
    if (std::isfinite(fig.parameter) && std::isfinite(fig.condition_weighted)) {
      alpha_[used] = fig.parameter;
      condition_[used] = fig.condition_weighted;
      cond_max = std::max(cond_max, fig.condition_weighted);
      ++used;
    }
  }
  BlockRegularisation& reg = ctx.out.regularisation;
  reg.alpha_median = MedianInPlace(alpha_, used);
  reg.condition_median = MedianInPlace(condition_, used);
  reg.condition_max = cond_max;
  reg.relative_residual = res_den > 0.0 ? std::sqrt(res_num / res_den) : 0.0;
  reg.bins_used = static_cast<std::uint32_t>(in_range);
  reg.bins_outside_frf = static_cast<std::uint32_t>(w.map.bins_outside);
  return RejectReason::kNone;
}

}  // namespace gearpath
