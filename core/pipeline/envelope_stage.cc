#include "core/pipeline/envelope_stage.h"

#include <algorithm>
#include <utility>

#include "core/pipeline/block_workspace.h"
#include "core/pipeline/machine_context.h"

namespace gearpath {

Status EnvelopeStage::Configure(const MachineContext& machine, BlockWorkspace& work) {
  auto e = EnvelopeAnalysis::Create(machine, work.n);
  if (!e) return Error{e.error()};
  envelope_.emplace(std::move(e.value()));
  const std::size_t shafts = machine.shaft_ratio.size();
  raw_.assign(shafts, 0.0);
  rec_.assign(shafts, 0.0);
  raw_harmonics_.assign(shafts, {});
  rec_harmonics_.assign(shafts, {});
  return Status::Ok();
}

// Time signal of w.one_spec, mesh tones comb-removed when asked.
void EnvelopeStage::ToTime(BlockWorkspace& w, bool remove_mesh_tones,
                           std::span<double> dst) noexcept {
  if (remove_mesh_tones) {
    for (std::size_t k = 0; k < w.bins; ++k) {
      if (w.mesh_mask[k]) w.one_spec[k] = {};
    }
  }
  (void)w.inverse->Process(w.one_spec, dst);
}

RejectReason EnvelopeStage::Process(StageContext& ctx) noexcept {
  BlockWorkspace& w = ctx.work;
  const MachineContext& m = ctx.machine;
  const bool remove = m.setup.options.remove_mesh_tones;
  const std::size_t channel = w.indicator_channel;
  if (remove) {
    std::copy_n(w.spec.begin() + static_cast<std::ptrdiff_t>(channel * w.bins), w.bins,
                w.one_spec.begin());
    ToTime(w, remove, w.raw_signal);
  } else {
    // The measured channel itself (its spectrum's inverse transform, less the rounding).
    std::copy_n(w.time.begin() + static_cast<std::ptrdiff_t>(channel * w.n), w.n,
                w.raw_signal.begin());
  }
  if (w.dominant >= 0) {
    w.Contribution(static_cast<std::size_t>(w.dominant), channel, w.one_spec);
  } else {
    std::fill(w.one_spec.begin(), w.one_spec.end(), BlockWorkspace::Cd{});
  }
  ToTime(w, remove, w.rec_signal);
  envelope_->Process(w.raw_signal, w.speed_hz, ctx.out.raw_band, raw_, raw_harmonics_);
  envelope_->Process(w.rec_signal, w.speed_hz, ctx.out.reconstructed_band, rec_, rec_harmonics_);
  for (std::size_t s = 0; s < raw_.size(); ++s) {
    BlockShaftIndicator& si = ctx.out.shafts[s];
    si.shaft = m.topology.shaft_names[s];
    si.characteristic_hz = m.shaft_ratio[s] * w.speed_hz;
    si.raw = raw_[s];
    si.reconstructed = rec_[s];
    si.raw_harmonics = raw_harmonics_[s];
    si.reconstructed_harmonics = rec_harmonics_[s];
    const auto e = EnhancementPercent(si.reconstructed, si.raw);
    si.enhancement_percent = e.ok() ? e.value() : 0.0;
  }
  return RejectReason::kNone;
}

}  // namespace gearpath
