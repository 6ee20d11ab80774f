#include "core/pipeline/envelope_stage.h"

#include <algorithm>
#include <utility>

#include "core/pipeline/block_workspace.h"
#include "core/pipeline/machine_context.h"
#include "core/pipeline/shape_scratch.h"

namespace gearpath {

Status EnvelopeStage::Configure(const MachineContext& machine, BlockWorkspace&) {
  const std::size_t shafts = machine.shaft_ratio.size();
  raw_.assign(shafts, 0.0);
  rec_.assign(shafts, 0.0);
  raw_harmonics_.assign(shafts, {});
  rec_harmonics_.assign(shafts, {});
  return Status::Ok();
}

namespace {

// Time signal of s.one_spec, mesh tones (w.mesh_mask) comb-removed when asked.
void ToTime(const BlockWorkspace& w, ShapeScratch& s, bool remove_mesh_tones,
            std::span<double> dst) noexcept {
  if (remove_mesh_tones) {
    for (std::size_t k = 0; k < w.bins; ++k) {
      if (w.mesh_mask[k]) s.one_spec[k] = {};
    }
  }
  (void)s.inverse->Process(s.one_spec, dst);
}

}  // namespace

RejectReason EnvelopeStage::Process(StageContext& ctx) noexcept {
  BlockWorkspace& w = ctx.work;
  ShapeScratch& sc = ctx.scratch;
  const MachineContext& m = ctx.machine;
  const bool remove = m.setup.options.remove_mesh_tones;
  const std::size_t channel = w.indicator_channel;
  if (remove) {
    std::copy_n(sc.spec.begin() + static_cast<std::ptrdiff_t>(channel * w.bins), w.bins,
                sc.one_spec.begin());
    ToTime(w, sc, remove, sc.raw_signal);
  } else {
    // The measured channel itself (its spectrum's inverse transform, less the rounding).
    std::copy_n(sc.time.begin() + static_cast<std::ptrdiff_t>(channel * w.n), w.n,
                sc.raw_signal.begin());
  }
  if (w.dominant >= 0) {
    w.Contribution(static_cast<std::size_t>(w.dominant), channel, sc.one_spec);
  } else {
    std::fill(sc.one_spec.begin(), sc.one_spec.end(), BlockWorkspace::Cd{});
  }
  ToTime(w, sc, remove, sc.rec_signal);
  sc.envelope->Process(m, sc.raw_signal, w.speed_hz, ctx.out.raw_band, raw_, raw_harmonics_);
  sc.envelope->Process(m, sc.rec_signal, w.speed_hz, ctx.out.reconstructed_band, rec_,
                       rec_harmonics_);
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
