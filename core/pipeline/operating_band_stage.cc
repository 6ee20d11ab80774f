#include "core/pipeline/operating_band_stage.h"

#include <utility>

#include "core/pipeline/block_workspace.h"
#include "core/pipeline/machine_context.h"
#include "core/pipeline/machine_state.h"

namespace gearpath {
namespace {

bool WithinRange(double value, double lo, double hi, double tolerance) noexcept {
  if (!(hi > 0.0)) return true;
  return value >= lo * (1.0 - tolerance) && value <= hi * (1.0 + tolerance);
}

}  // namespace

bool BandHoldsSpeed(const OperatingBand& band, double speed_hz, double tolerance) noexcept {
  return WithinRange(speed_hz, band.baseline_speed_lo_hz, band.baseline_speed_hi_hz, tolerance);
}

bool BandHoldsLoad(const OperatingBand& band, double load, double tolerance) noexcept {
  if (!(load > 0.0)) return true;  // a block without a load is judged at any load
  return WithinRange(load, band.baseline_load_lo, band.baseline_load_hi, tolerance);
}

Status OperatingBandStage::Configure(const MachineContext&, BlockWorkspace&) {
  return Status::Ok();
}

RejectReason OperatingBandStage::Process(StageContext& ctx) noexcept {
  MachineState& st = ctx.state;
  const AnalysisOptions& o = ctx.machine.setup.options;
  const double speed = ctx.work.speed_hz;
  const double load = ctx.block.load;
  // One band, no speed (nothing is judged), or the machine's first baseline still learning
  // (it learns from every block, as with one band): nothing to choose.
  if (st.parked_bands.empty() || !(speed > 0.0) || !st.any_band_learned()) {
    return RejectReason::kNone;
  }
  const auto holds = [&](const OperatingBand& b) {
    return BandHoldsSpeed(b, speed, o.speed_tolerance) && BandHoldsLoad(b, load, o.load_tolerance);
  };
  const auto make_current = [&st](OperatingBand& b) {
    std::swap(st.band, b);
    st.learning = !st.band.learned();
    st.previous_scored = false;  // the two-block score does not span bands
  };
  // 1. A learned band that holds the block judges it.
  if (st.band.learned() && holds(st.band)) return RejectReason::kNone;
  OperatingBand* learning = st.band.learned() ? nullptr : &st.band;
  for (std::size_t i = 0; i < st.parked_count; ++i) {
    OperatingBand& b = st.parked_bands[i];
    if (!b.learned()) {
      learning = &b;
    } else if (holds(b)) {
      make_current(b);
      return RejectReason::kNone;
    }
  }
  // 2. No learned band holds it. A band learns only while no fault is suspected: the learning
  // band goes on where it holds the block, else it restarts here, else a new band starts.
  const FaultState state = st.alarm->status().state;
  const bool may_learn = state != FaultState::kSuspected && state != FaultState::kAlarm;
  if (may_learn && learning != nullptr) {
    const bool goes_on = holds(*learning);
    if (learning != &st.band) make_current(*learning);
    if (!goes_on) st.band.Reset();
    return RejectReason::kNone;
  }
  if (may_learn && st.parked_count < st.parked_bands.size()) {
    OperatingBand& fresh = st.parked_bands[st.parked_count++];
    fresh.Reset();
    fresh.id = static_cast<int>(st.parked_count);
    make_current(fresh);
    return RejectReason::kNone;
  }
  // 3. Nothing may learn here: a learned band stays in force, which does not hold the block,
  // so it is not judged (and a learning band learns nothing from it).
  if (!st.band.learned()) {
    for (std::size_t i = 0; i < st.parked_count; ++i) {
      if (st.parked_bands[i].learned()) {
        make_current(st.parked_bands[i]);
        break;
      }
    }
  }
  return RejectReason::kNone;
}

}  // namespace gearpath
