#include "core/pipeline/identification_stage.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "core/common/simd_clones.h"
#include "core/pipeline/block_workspace.h"
#include "core/pipeline/shape_scratch.h"
#include "core/pipeline/machine_context.h"
#include "core/pipeline/shared_frf_operators.h"

namespace gearpath {
namespace {

constexpr std::size_t kChunk = IdentificationOperator::kChunkBins;

// Median of the first n values of `v` (reorders them). 0 for n == 0.
double MedianInPlace(std::vector<double>& v, std::size_t n) noexcept {
  if (n == 0) return 0.0;
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(n / 2);
  std::nth_element(v.begin(), mid, v.begin() + static_cast<std::ptrdiff_t>(n));
  return *mid;
}

// One (path, FRF row)'s band and sideband energies: sum over the bins of |H_cp|^2 times the
// path's band and sideband weighted |F_p|^2. Eight partial sums per figure in a fixed order
// (element-wise over the lanes, so the compiler vectorises it and every clone rounds alike),
// added up at the end.
GEARPATH_SIMD_CLONES
void DotEnergies(const float* __restrict power, const double* __restrict f2_band,
                 const double* __restrict f2_side, std::size_t bins, double& band,
                 double& side) noexcept {
  constexpr std::size_t kLanes = 8;
  double b[kLanes] = {};
  double s[kLanes] = {};
  std::size_t j = 0;
  for (; j + kLanes <= bins; j += kLanes) {
    for (std::size_t k = 0; k < kLanes; ++k) {
      const double h2 = static_cast<double>(power[j + k]);
      b[k] += h2 * f2_band[j + k];
      s[k] += h2 * f2_side[j + k];
    }
  }
  for (std::size_t k = 0; j < bins; ++j, ++k) {
    const double h2 = static_cast<double>(power[j]);
    b[k] += h2 * f2_band[j];
    s[k] += h2 * f2_side[j];
  }
  band = 0.0;
  side = 0.0;
  for (std::size_t k = 0; k < kLanes; ++k) {
    band += b[k];
    side += s[k];
  }
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
  table_ = work.frf_table.get();
  const auto in_range = static_cast<std::size_t>(work.map.frf.bins());
  if (static_cast<std::size_t>(op_->bins()) != in_range || table_ == nullptr ||
      table_->bins != in_range) {
    return Error{"identification operator: does not match the block's in-range bins"};
  }
  x_re_.assign(machine.channels * kChunk, 0.0);
  x_im_.assign(machine.channels * kChunk, 0.0);
  f_re_.assign(machine.paths * kChunk, 0.0);
  f_im_.assign(machine.paths * kChunk, 0.0);
  f2_band_.assign(in_range, 0.0);
  f2_side_.assign(in_range, 0.0);
  x_ = Eigen::VectorXcd::Zero(static_cast<Eigen::Index>(machine.channels));
  forces_ = Eigen::VectorXcd::Zero(static_cast<Eigen::Index>(machine.paths));
  alpha_.assign(in_range, 0.0);
  condition_.assign(in_range, 0.0);
  if (op_->precomputed()) {
    // The figures do not depend on the block (every bin of a validated, finite block is
    // identified): their medians once, here.
    std::size_t used = 0;
    double cond_max = 0.0;
    for (std::size_t i = 0; i < in_range; ++i) {
      const BinFigures fig = op_->StaticFigures(static_cast<Eigen::Index>(i));
      if (std::isfinite(fig.parameter) && std::isfinite(fig.condition_weighted)) {
        alpha_[used] = fig.parameter;
        condition_[used] = fig.condition_weighted;
        cond_max = std::max(cond_max, fig.condition_weighted);
        ++used;
      }
    }
    static_alpha_median_ = MedianInPlace(alpha_, used);
    static_condition_median_ = MedianInPlace(condition_, used);
    static_condition_max_ = cond_max;
  }
  return Status::Ok();
}

void IdentificationStage::IdentifyChunkPerBin(BlockWorkspace& w, std::size_t chunk,
                                              std::size_t count) noexcept {
  const auto channels = static_cast<std::size_t>(x_.size());
  const auto paths = static_cast<std::size_t>(forces_.size());
  for (std::size_t j = 0; j < count; ++j) {
    const auto i = static_cast<Eigen::Index>(chunk * kChunk + j);
    double x2 = 0.0;
    for (std::size_t c = 0; c < channels; ++c) {
      const BlockWorkspace::Cd v(x_re_[c * kChunk + j], x_im_[c * kChunk + j]);
      x_[static_cast<Eigen::Index>(c)] = v;
      x2 += std::norm(v);
    }
    BinFigures fig;  // read in this bin only: Identify() sets every field
    if (op_->Identify(i, x_, forces_, &fig) != IdentifyStatus::kOk) {
      forces_.setZero();
    } else {
      if (w.band_mask[w.map.first_bin + static_cast<std::size_t>(i)]) {
        residual_ += fig.relative_residual * fig.relative_residual * x2;
      }
      if (std::isfinite(fig.parameter) && std::isfinite(fig.condition_weighted)) {
        alpha_[used_] = fig.parameter;
        condition_[used_] = fig.condition_weighted;
        cond_max_ = std::max(cond_max_, fig.condition_weighted);
        ++used_;
      }
    }
    for (std::size_t p = 0; p < paths; ++p) {
      f_re_[p * kChunk + j] = forces_[static_cast<Eigen::Index>(p)].real();
      f_im_[p * kChunk + j] = forces_[static_cast<Eigen::Index>(p)].imag();
    }
  }
}

RejectReason IdentificationStage::Process(StageContext& ctx) noexcept {
  BlockWorkspace& w = ctx.work;
  const std::size_t channels = ctx.machine.channels;
  const std::size_t paths = ctx.machine.paths;
  const auto in_range = static_cast<std::size_t>(w.map.frf.bins());
  const std::size_t first = w.map.first_bin;
  const bool batched = op_->precomputed();
  residual_ = 0.0;
  used_ = 0;
  cond_max_ = 0.0;
  double response = 0.0;  // sum of ||x||^2 over the band bins
  for (std::size_t chunk = 0; chunk < op_->chunks(); ++chunk) {
    const std::size_t b0 = chunk * kChunk;
    const std::size_t count = std::min(kChunk, in_range - b0);
    // Responses, split; the last chunk's missing bins read zero.
    for (std::size_t c = 0; c < channels; ++c) {
      const BlockWorkspace::Cd* s = ctx.scratch.spec.data() + c * w.bins + first + b0;
      double* re = x_re_.data() + c * kChunk;
      double* im = x_im_.data() + c * kChunk;
      for (std::size_t j = 0; j < count; ++j) {
        re[j] = s[j].real();
        im[j] = s[j].imag();
      }
      std::fill(re + count, re + kChunk, 0.0);
      std::fill(im + count, im + kChunk, 0.0);
    }
    if (batched) {
      op_->ForcesOfChunk(chunk, x_re_.data(), x_im_.data(), f_re_.data(), f_im_.data());
      for (std::size_t j = 0; j < count; ++j) {
        if (w.band_mask[first + b0 + j] != 0) {
          residual_ += op_->Residual2(static_cast<Eigen::Index>(b0 + j), x_re_.data() + j,
                                      x_im_.data() + j, kChunk);
        }
      }
    } else {
      IdentifyChunkPerBin(w, chunk, count);
    }
    for (std::size_t j = 0; j < count; ++j) {
      if (w.band_mask[first + b0 + j] == 0) continue;
      double x2 = 0.0;
      for (std::size_t c = 0; c < channels; ++c) {
        const double re = x_re_[c * kChunk + j];
        const double im = x_im_[c * kChunk + j];
        x2 += re * re + im * im;
      }
      response += x2;
    }
    for (std::size_t p = 0; p < paths; ++p) {
      BlockWorkspace::Cd* dst = w.forces.data() + p * in_range + b0;
      for (std::size_t j = 0; j < count; ++j) {
        dst[j] = {f_re_[p * kChunk + j], f_im_[p * kChunk + j]};
      }
    }
  }
  // Each (path, FRF row)'s energies, |H_cp|^2 |F_p|^2 over the analysis band and over its
  // sideband lines: one streaming pass per path over its |H|^2 rows, after the forces.
  for (std::size_t p = 0; p < paths; ++p) {
    const BlockWorkspace::Cd* f = w.forces.data() + p * in_range;
    for (std::size_t i = 0; i < in_range; ++i) {
      const bool in_band = w.band_mask[first + i] != 0;
      f2_band_[i] = in_band ? std::norm(f[i]) : 0.0;
      f2_side_[i] = in_band && w.sideband_mask[first + i] != 0 ? f2_band_[i] : 0.0;
    }
    double side = 0.0;
    for (std::size_t c = 0; c < channels; ++c) {
      double band = 0.0;
      double side_c = 0.0;
      DotEnergies(table_->Row(p, c), f2_band_.data(), f2_side_.data(), in_range, band, side_c);
      w.path_channel_energy[p * channels + c] = band;
      side += side_c;
    }
    w.path_sideband_energy[p] = side;
  }
  BlockRegularisation& reg = ctx.out.regularisation;
  if (batched) {
    reg.alpha_median = static_alpha_median_;
    reg.condition_median = static_condition_median_;
    reg.condition_max = static_condition_max_;
  } else {
    reg.alpha_median = MedianInPlace(alpha_, used_);
    reg.condition_median = MedianInPlace(condition_, used_);
    reg.condition_max = cond_max_;
  }
  reg.relative_residual = response > 0.0 ? std::sqrt(residual_ / response) : 0.0;
  reg.bins_used = static_cast<std::uint32_t>(in_range);
  reg.bins_outside_frf = static_cast<std::uint32_t>(w.map.bins_outside);
  return RejectReason::kNone;
}

}  // namespace gearpath
