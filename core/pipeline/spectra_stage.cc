#include "core/pipeline/spectra_stage.h"

#include "core/pipeline/block_workspace.h"
#include "core/pipeline/machine_context.h"
#include "core/pipeline/shape_scratch.h"

namespace gearpath {

Status SpectraStage::Configure(const MachineContext&, BlockWorkspace&) { return Status::Ok(); }

RejectReason SpectraStage::Process(StageContext& ctx) noexcept {
  ShapeScratch& s = ctx.scratch;
  for (std::size_t c = 0; c < ctx.machine.channels; ++c) {
    const auto src = ctx.block.channel(c);
    double* dst = s.time.data() + static_cast<std::size_t>(ctx.machine.block_to_row[c]) * s.n;
    for (std::size_t i = 0; i < s.n; ++i) dst[i] = static_cast<double>(src[i]);
  }
  if (!s.spectrum->Process(s.time, s.spec).ok()) {
    ctx.message.Assign("spectrum rejected the block");
    return RejectReason::kNonFinite;
  }
  return RejectReason::kNone;
}

}  // namespace gearpath
