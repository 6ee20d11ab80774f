#include "core/pipeline/spectra_stage.h"

#include <utility>

#include "core/pipeline/block_workspace.h"
#include "core/pipeline/machine_context.h"

namespace gearpath {

Status SpectraStage::Configure(const MachineContext& machine, BlockWorkspace& work) {
  auto spectrum = Spectrum::Create(work.n, machine.channels, machine.setup.options.sample_rate_hz);
  if (!spectrum) return Error{spectrum.error()};
  spectrum_.emplace(std::move(spectrum.value()));
  return Status::Ok();
}

RejectReason SpectraStage::Process(StageContext& ctx) noexcept {
  BlockWorkspace& w = ctx.work;
  for (std::size_t c = 0; c < ctx.machine.channels; ++c) {
    const auto src = ctx.block.channel(c);
    double* dst = w.time.data() + static_cast<std::size_t>(ctx.machine.block_to_row[c]) * w.n;
    for (std::size_t i = 0; i < w.n; ++i) dst[i] = static_cast<double>(src[i]);
  }
  if (!spectrum_->Process(w.time, w.spec).ok()) {
    ctx.message.Assign("spectrum rejected the block");
    return RejectReason::kNonFinite;
  }
  return RejectReason::kNone;
}

}  // namespace gearpath
