#include "core/pipeline/condition_indicator_stage.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <limits>
#include <optional>
#include <utility>

#include "core/diagnosis/mesh_signature.h"
#include "core/pipeline/block_workspace.h"
#include "core/pipeline/machine_context.h"
#include "core/pipeline/machine_state.h"
#include "core/pipeline/shape_scratch.h"

namespace gearpath {
namespace {

// Distance (in orders of `other`) under which a line counts as a harmonic of another rate.
constexpr double kCommonOrderTolerance = 0.1;
// A machine is order-tracked when, on its first block, the tracked average holds this much more
// power on the carrier mesh's first harmonics than the constant-speed one (noise alone moves it
// by well under 1 %).
constexpr double kTrackingGain = 1.02;
constexpr int kCoherenceHarmonics = 4;
// A warp re-phases the revolutions but keeps each one's power, and the power of their mean is at
// most their mean power: tracking can raise the locked power of the mesh harmonics by at most
// the revolutions' spread on them (locked + spread is their mean power). A spread under the
// gain asked for cannot pass the test, so the tracks are skipped and the machine left
// untracked. A quarter of margin, as the spread is read from Hann-windowed revolutions and
// the test from their plain average; the bound is tight: on a plant whose drift was swept,
// the full test starts tracking at a spread of 0.0206 (docs/performance.md).
constexpr double kCoherentEnough = 0.75 * (kTrackingGain - 1.0);
// Mesh harmonics tried as the tracking carrier (each one costs a Track()).
constexpr int kCarrierHarmonics = 3;
// Floor of the locked evidence, which can come out negative when nothing is locked (the
// baseline is judged on a log scale).
constexpr double kLockedEvidenceFloor = 1e-30;
constexpr double kInfinity = std::numeric_limits<double>::infinity();

}  // namespace

Status ConditionIndicatorStage::Configure(const MachineContext& machine, BlockWorkspace& work) {
  // The averager, its grids, the tracker and the buffers are the scratch's (ShapeScratch::
  // condition); the machine keeps its order masks and slot layout.
  const std::size_t max_points = SynchronousPointsCap(work.n);
  const AnalysisOptions& o = machine.setup.options;
  localisation_only_ = o.localisation_tracking && !o.order_tracking;
  plan_ok_.assign(machine.rate_groups.size(), 0);

  const int low_orders = IndicatorOptions{}.low_shaft_orders;  // ShapeScratch's indicators'
  exclusive_.assign(machine.rate_groups.size(), {});
  for (std::size_t g = 0; g < machine.rate_groups.size(); ++g) {
    const RateGroup& rg = machine.rate_groups[g];
    std::vector<std::uint8_t>& mask = exclusive_[g];
    mask.assign(max_points / 2 + 1, 0);
    for (std::size_t k = static_cast<std::size_t>(low_orders) + 1; k < mask.size(); ++k) {
      bool keep = true;
      for (int order : rg.mesh_orders) keep = keep && (k % static_cast<std::size_t>(order)) != 0;
      for (std::size_t h = 0; h < machine.rate_groups.size() && keep; ++h) {
        if (h == g) continue;
        const double x = static_cast<double>(k) * rg.ratio / machine.rate_groups[h].ratio;
        keep = std::abs(x - std::round(x)) > kCommonOrderTolerance;
      }
      mask[k] = keep ? 1 : 0;
    }
  }
  signature_slot_.assign(machine.rate_groups.size() * 2 * kMaxMeshesPerShaft, 0);
  for (std::size_t i = 0; i < machine.signature_slots.size(); ++i) {
    const SignatureSlot& ss = machine.signature_slots[i];
    signature_slot_[(ss.group * 2 + (ss.forces ? 1 : 0)) * kMaxMeshesPerShaft + ss.mesh] = i;
  }
  return Status::Ok();
}

// Copies the lines around each mesh harmonic of the last average (signal `signal` at group
// `group`) into the workspace, for the transfer signature.
void ConditionIndicatorStage::KeepSignatureLines(StageContext& ctx, std::size_t signal,
                                                 std::size_t group) noexcept {
  BlockWorkspace& w = ctx.work;
  const ConditionSignal& cs = ctx.machine.condition_signals[signal];
  if (cs.source == ConditionSource::kContribution) return;
  const ShapeScratch::Condition& cw = ctx.scratch.condition;
  const bool forces = cs.source == ConditionSource::kForce;
  const RateGroup& rg = ctx.machine.rate_groups[group];
  const auto orders = cw.record.orders();
  const auto width = static_cast<std::size_t>(2 * kSignatureSidebands + 1);
  const auto sensor = static_cast<std::size_t>(cs.index);
  for (std::size_t i = 0; i < rg.meshes.size(); ++i) {
    const std::size_t slot =
        signature_slot_[(group * 2 + (forces ? 1 : 0)) * kMaxMeshesPerShaft + i];
    BlockWorkspace::Cd* base = w.signature_lines.data() + slot * w.signature_stride;
    for (int h = 1; h <= kSignatureHarmonics; ++h) {
      BlockWorkspace::Cd* lines =
          base + static_cast<std::size_t>(h - 1) * w.signature_sensors * width + sensor * width;
      for (int k = -kSignatureSidebands; k <= kSignatureSidebands; ++k) {
        const long order = static_cast<long>(h) * rg.mesh_orders[i] + k;
        lines[static_cast<std::size_t>(k + kSignatureSidebands)] =
            order > 0 && static_cast<std::size_t>(order) < orders.size()
                ? orders[static_cast<std::size_t>(order)]
                : BlockWorkspace::Cd{};
      }
    }
  }
}

void ConditionIndicatorStage::Signatures(StageContext& ctx, bool tracked) noexcept {
  BlockWorkspace& w = ctx.work;
  const MachineContext& m = ctx.machine;
  const auto width = static_cast<std::size_t>(2 * kSignatureSidebands + 1);
  for (std::size_t i = 0; i < m.signature_slots.size(); ++i) {
    const SignatureSlot& ss = m.signature_slots[i];
    if (tracked && ss.forces) continue;
    const std::size_t sensors = ss.forces ? m.paths : m.channels;
    MeshSignatureEnergy sum;
    const BlockWorkspace::Cd* base = w.signature_lines.data() + i * w.signature_stride;
    for (int h = 0; h < kSignatureHarmonics; ++h) {
      MeshSignatureEnergy one;
      AccumulateMeshSignature(
          std::span<const BlockWorkspace::Cd>(
              base + static_cast<std::size_t>(h) * w.signature_sensors * width, sensors * width),
          sensors, kSignatureSidebands, one);
      sum.parallel += one.parallel;
      sum.orthogonal += one.orthogonal;
      // The localisation's entries, one pair per harmonic (the tracked pass replaces them).
      if (!ss.forces) {
        const std::size_t at = ss.tracked_offset + 2 * static_cast<std::size_t>(h);
        w.indicators[at] = one.parallel;
        w.indicators[at + 1] = one.orthogonal;
      }
    }
    if (tracked) continue;
    w.indicators[ss.offset] = sum.parallel;
    w.indicators[ss.offset + 1] = sum.orthogonal;
  }
}

bool ConditionIndicatorStage::TrackOrders(StageContext& ctx) noexcept {
  BlockWorkspace& w = ctx.work;
  const ShapeScratch& s = ctx.scratch;
  ShapeScratch::Condition& cw = ctx.scratch.condition;
  int& mode = ctx.state.order_tracking_mode;
  if (!cw.tracker || w.meshes.empty() || mode == 0) return false;
  // The band stays inside +/- 3/4 of the slowest shaft rate, so a fault's shaft-rate sidebands
  // (its modulation) are not tracked as speed.
  double slowest = w.meshes.front().shaft_hz[0];
  for (const MeshLines& ml : w.meshes) {
    slowest = std::min({slowest, ml.shaft_hz[0], ml.shaft_hz[1]});
  }
  const double half_band = 0.75 * slowest;
  const double nyquist = 0.5 * ctx.machine.setup.options.sample_rate_hz;
  // Carriers: each of the first harmonics of every mesh, on the channel where its band is
  // strongest. Each reads the speed through its own stretch of the transfer and beside its
  // own foreign lines (a pump tone, another shaft's harmonic), so each warp errs its own way;
  // the warp kept is their median, sample by sample (docs/diagnosis.md, section 9a). The one
  // with the smallest phase residual also serves the machine's tracking decision below.
  std::array<Carrier, kMaxTrainMeshes * kCarrierHarmonics> carriers;
  std::size_t candidates = 0;
  for (const MeshLines& ml : w.meshes) {
    for (int h = 1; h <= kCarrierHarmonics && candidates < carriers.size(); ++h) {
      const double fc = h * ml.mesh_hz;
      if (!(fc - half_band > 0.0) || !(fc + half_band < nyquist)) continue;
      const auto lo = static_cast<std::size_t>(std::ceil((fc - half_band) / w.bin_hz));
      const auto hi =
          std::min(w.bins - 1, static_cast<std::size_t>(std::floor((fc + half_band) / w.bin_hz)));
      double band_power = 0.0;
      std::size_t band_channel = 0;
      for (std::size_t c = 0; c < ctx.machine.channels; ++c) {
        double power = 0.0;
        for (std::size_t k = lo; k <= hi; ++k) power += std::norm(s.spec[c * w.bins + k]);
        if (power > band_power) {
          band_power = power;
          band_channel = c;
        }
      }
      if (!(band_power > 0.0)) continue;
      carriers[candidates++] = {fc, ml.mesh_hz, ml.shaft_hz[0], band_channel};
    }
  }
  const std::span<const Carrier> tried(carriers.data(), candidates);
  // The decision's shortcut: when every carrier's shaft average already holds its mesh
  // harmonics coherently, no warp can make it gain what the decision asks for.
  if (mode == -1 && LargestIncoherence(ctx, tried) < kCoherentEnough) {
    mode = 0;
    return false;
  }
  std::size_t count = 0;
  double best_residual = 0.0;
  double carrier = 0.0;
  double carrier_shaft = 0.0;
  std::size_t channel = 0;
  for (const Carrier& c : tried) {
    // A train of more than three meshes: the first carriers that track.
    if (count == kMaxCarrierWarps) break;
    const std::optional<OrderTrackResult> track = cw.tracker->TryTrack(
        std::span<const double>(s.time).subspan(c.channel * w.n, w.n), c.hz, half_band,
        std::span<double>(cw.carrier_warps).subspan(count * w.n, w.n));
    if (!track) continue;
    ++count;
    if (count == 1 || track->phase_residual_rad < best_residual) {
      best_residual = track->phase_residual_rad;
      carrier = c.mesh_hz;
      carrier_shaft = c.shaft_hz;
      channel = c.channel;
    }
  }
  const bool tracked = count > 0;
  if (tracked) MedianOfWarps(cw.carrier_warps, count, cw.warp);
  // A block whose tones cannot be tracked (none in range, too weak) is averaged at its mean
  // speed.
  const std::span<const double> reference =
      std::span<const double>(s.time).subspan(channel * w.n, w.n);
  if (mode == -1) {
    // The machine's one decision: track only when it makes the carrier's shaft average more
    // coherent. Another line inside the band (a shaft harmonic, a second mesh) beats with the
    // carrier and would be tracked as a speed change that is not there.
    mode = tracked && MeshCoherence(cw, reference, carrier_shaft, carrier, cw.warp) >
                          kTrackingGain * MeshCoherence(cw, reference, carrier_shaft, carrier, {})
               ? 1
               : 0;
  }
  return mode == 1 && tracked;
}

double ConditionIndicatorStage::LargestIncoherence(StageContext& ctx,
                                                   std::span<const Carrier> carriers) noexcept {
  const BlockWorkspace& w = ctx.work;
  ShapeScratch::Condition& cw = ctx.scratch.condition;
  double largest = 0.0;
  for (std::size_t i = 0; i < carriers.size(); ++i) {
    const Carrier& c = carriers[i];
    // A mesh's harmonics share one shaft and, mostly, one channel: each pair is read once.
    const auto same = [&c](const Carrier& o) {
      return o.mesh_hz == c.mesh_hz && o.shaft_hz == c.shaft_hz && o.channel == c.channel;
    };
    if (std::any_of(carriers.begin(), carriers.begin() + static_cast<std::ptrdiff_t>(i), same)) {
      continue;
    }
    // A mesh's carriers come one after another: their shaft's grid is planned once. One
    // revolution has no spread to read: the tracks decide.
    if (cw.plans.empty()) return kInfinity;
    const SynchronousAveragePlan& plan = cw.plans[0];
    if (plan.shaft_hz != c.shaft_hz || i == 0) {
      if (!cw.tsa->Plan(c.shaft_hz, cw.plans[0], {}).ok()) return kInfinity;
    }
    if (plan.revolutions < 2) return kInfinity;
    const std::size_t orders = plan.points_per_revolution / 2 + 1;
    const std::span<double> locked(cw.locked_power.data(), orders);
    const std::span<double> spread(cw.spread_power.data(), orders);
    const std::span<const double> signal =
        std::span<const double>(ctx.scratch.time).subspan(c.channel * w.n, w.n);
    if (!cw.tsa->RevolutionSpread(signal, plan, locked, spread).ok()) return kInfinity;
    const double teeth = std::round(c.mesh_hz / c.shaft_hz);
    double locked_sum = 0.0;
    double spread_sum = 0.0;
    for (int h = 1; h <= kCoherenceHarmonics; ++h) {
      const double k = h * teeth;
      if (!(k < static_cast<double>(orders))) break;
      locked_sum += locked[static_cast<std::size_t>(k)];
      spread_sum += spread[static_cast<std::size_t>(k)];
    }
    if (!(locked_sum > 0.0)) return kInfinity;
    largest = std::max(largest, spread_sum / locked_sum);
  }
  return largest;
}

double ConditionIndicatorStage::MeshCoherence(ShapeScratch::Condition& cw,
                                              std::span<const double> signal, double shaft_hz,
                                              double mesh_hz,
                                              std::span<const double> warp) noexcept {
  // cw.plans[0] as scratch: TrackOrders() runs before Process() plans the block's groups.
  if (cw.plans.empty() || !cw.tsa->Plan(shaft_hz, cw.plans[0], warp).ok() ||
      !cw.tsa->Process(signal, cw.plans[0], cw.record).ok()) {
    return 0.0;
  }
  const auto orders = cw.record.orders();
  const double teeth = std::round(mesh_hz / shaft_hz);
  double power = 0.0;
  for (int h = 1; h <= kCoherenceHarmonics; ++h) {
    const double k = h * teeth;
    if (k < static_cast<double>(orders.size()))
      power += std::norm(orders[static_cast<std::size_t>(k)]);
  }
  return power;
}

double ConditionIndicatorStage::ExclusiveEnergy(const SynchronousAverageRecord& record,
                                                std::size_t g) const noexcept {
  // Units^2: comparable between rate groups of one signal.
  const auto orders = record.orders();
  const std::vector<std::uint8_t>& mask = exclusive_[g];
  double exclusive = 0.0;
  for (std::size_t k = 1; k < orders.size() && k < mask.size(); ++k) {
    if (mask[k]) exclusive += 0.5 * std::norm(orders[k]);
  }
  return exclusive;
}

double ConditionIndicatorStage::LockedExclusiveEnergy(
    std::size_t g, const RevolutionSpreadView& spread) const noexcept {
  // Units^2 like ExclusiveEnergy. Per order: the power locked to the shaft less what the
  // unlocked content of R revolutions leaves in their mean on average (spread / (R - 1)). The
  // revolutions are Hann-windowed, which spreads every line over k +/- 1: an order next to one
  // that is not exclusive (a mesh harmonic, another shaft's line) is left out.
  const std::vector<std::uint8_t>& mask = exclusive_[g];
  const double in_mean = 1.0 / (static_cast<double>(spread.revolutions) - 1.0);
  double locked = 0.0;
  for (std::size_t k = 2; k + 1 < spread.locked.size() && k + 1 < mask.size(); ++k) {
    if (!(mask[k] && mask[k - 1] && mask[k + 1])) continue;
    locked += 0.5 * (spread.locked[k] - spread.spread[k] * in_mean);
  }
  return std::max(locked, kLockedEvidenceFloor);
}

void ConditionIndicatorStage::TrackedLocalisation(StageContext& ctx) noexcept {
  BlockWorkspace& w = ctx.work;
  ShapeScratch::Condition& cw = ctx.scratch.condition;
  const MachineContext& m = ctx.machine;
  const std::size_t groups = m.rate_groups.size();
  for (std::size_t g = 0; g < groups; ++g) {
    // The constant-speed grids of cw.plans are used up by now: the tracked ones replace them
    // (Process() plans every group again next block).
    if (!cw.tsa->Plan(m.rate_groups[g].ratio * w.speed_hz, cw.plans[g], cw.warp).ok()) continue;
    for (std::size_t c = 0; c < m.channels; ++c) {
      const std::size_t slot = c * groups + g;  // measured signals come first
      if (!w.slot_valid[slot]) continue;
      // The measured channel as the scored averages saw it (its transients taken out).
      if (!cw.tsa->Process(SignalOf(ctx, c), cw.plans[g], cw.record).ok()) continue;
      w.indicators[m.tracked_offset + slot] = ExclusiveEnergy(cw.record, g);
      KeepSignatureLines(ctx, c, g);  // overwrites the measured lines (already used)
    }
  }
  Signatures(ctx, /*tracked=*/true);
}

void ConditionIndicatorStage::RemoveTransients(StageContext& ctx,
                                               std::span<const double> warp) noexcept {
  const BlockWorkspace& w = ctx.work;
  const ShapeScratch& s = ctx.scratch;
  ShapeScratch::Condition& cw = ctx.scratch.condition;
  const MachineContext& m = ctx.machine;
  std::fill(cw.transient_samples.begin(), cw.transient_samples.end(), 0);
  if (!cw.gate) return;  // off (the scratch's key holds the option) or a block too short
  if (!warp.empty()) InvertWarp(warp, cw.nominal);
  const std::span<const double> nominal =
      warp.empty() ? std::span<const double>() : std::span<const double>(cw.nominal);
  const double fs = m.setup.options.sample_rate_hz;
  for (std::size_t g = 0; g < m.rate_groups.size(); ++g) {
    // Where each sample reads each shaft's revolution: once for every channel.
    PeriodicReadPlan& read = cw.periodic_reads[g];
    read.points = 0;
    if (plan_ok_[g]) {
      const SynchronousAveragePlan& plan = cw.plans[g];
      (void)PlanPeriodicRead(plan.points_per_revolution, plan.shaft_hz / fs, nominal, read);
    }
  }
  for (std::size_t c = 0; c < m.channels; ++c) {
    const std::span<const double> x = std::span<const double>(s.time).subspan(c * w.n, w.n);
    std::copy(x.begin(), x.end(), cw.residual.begin());
    // Each shaft's periodic part is taken from what the shafts before it left, so a line that
    // two shafts share (a mesh harmonic) is taken once.
    bool any_shaft = false;
    for (std::size_t g = 0; g < m.rate_groups.size(); ++g) {
      const PeriodicReadPlan& read = cw.periodic_reads[g];
      if (read.points == 0) continue;
      const SynchronousAveragePlan& plan = cw.plans[g];
      const std::span<double> median(cw.median_revolution.data(), plan.points_per_revolution);
      const Result<CheckedSignal> residual = cw.tsa->Check(cw.residual);
      if (!residual.ok() || !cw.tsa->RevolutionMedian(residual.value(), plan, median).ok()) {
        continue;
      }
      SubtractPeriodicPart(cw.residual, median, read, cw.wrapped_revolution);
      any_shaft = true;
    }
    if (!any_shaft) continue;
    cw.transient_samples[c] = cw.gate->Estimate(cw.residual, cw.transient);
    if (cw.transient_samples[c] == 0) continue;
    double* cleaned = cw.cleaned.data() + c * w.n;
    for (std::size_t i = 0; i < w.n; ++i) cleaned[i] = x[i] - cw.transient[i];
  }
}

// The time signal of condition signal `signal` (a view of the block or of s.signal).
std::span<const double> ConditionIndicatorStage::SignalOf(const StageContext& ctx,
                                                          std::size_t signal) noexcept {
  BlockWorkspace& w = ctx.work;
  ShapeScratch& s = ctx.scratch;
  const ConditionSignal& cs = ctx.machine.condition_signals[signal];
  const auto index = static_cast<std::size_t>(cs.index);
  switch (cs.source) {
    case ConditionSource::kMeasured:
      if (s.condition.transient_samples[index] > 0) {
        return std::span<const double>(s.condition.cleaned).subspan(index * w.n, w.n);
      }
      return std::span<const double>(s.time).subspan(index * w.n, w.n);
    case ConditionSource::kContribution:
      w.Contribution(index, static_cast<std::size_t>(w.best_channel[index]), s.one_spec);
      break;
    case ConditionSource::kForce:
      std::fill(s.one_spec.begin(), s.one_spec.end(), BlockWorkspace::Cd{});
      for (Eigen::Index i = 0; i < w.map.frf.bins(); ++i) {
        s.one_spec[w.map.first_bin + static_cast<std::size_t>(i)] =
            w.forces(static_cast<Eigen::Index>(index), i);
      }
      break;
  }
  (void)s.inverse->Process(s.one_spec, s.signal);
  return s.signal;
}

RejectReason ConditionIndicatorStage::Process(StageContext& ctx) noexcept {
  BlockWorkspace& w = ctx.work;
  ShapeScratch::Condition& cw = ctx.scratch.condition;
  const MachineContext& m = ctx.machine;
  const MachineState& st = ctx.state;
  std::fill(w.indicators.begin(), w.indicators.end(), 0.0);
  std::fill(w.slot_valid.begin(), w.slot_valid.end(), std::uint8_t{0});
  std::fill(w.slot_revolutions.begin(), w.slot_revolutions.end(), 0);
  std::fill(w.slot_transient_samples.begin(), w.slot_transient_samples.end(), 0);
  std::fill(w.signature_lines.begin(), w.signature_lines.end(), BlockWorkspace::Cd{});
  if (!(w.speed_hz > 0.0)) return RejectReason::kNone;
  const std::size_t groups = m.rate_groups.size();
  const bool tracked = TrackOrders(ctx);
  const std::span<const double> warp = tracked && m.setup.options.order_tracking
                                           ? std::span<const double>(cw.warp)
                                           : std::span<const double>();
  for (std::size_t g = 0; g < groups; ++g) {
    plan_ok_[g] = cw.tsa->Plan(m.rate_groups[g].ratio * w.speed_hz, cw.plans[g], warp).ok() ? 1 : 0;
  }
  RemoveTransients(ctx, warp);
  for (std::size_t sig = 0; sig < m.condition_signals.size(); ++sig) {
    // Checked once for all its rate groups; a signal that fails leaves its slots invalid.
    const Result<CheckedSignal> signal = cw.tsa->Check(SignalOf(ctx, sig));
    for (std::size_t g = 0; g < groups; ++g) {
      const std::size_t slot = sig * groups + g;
      const ConditionSlot& cs = m.condition_slots[slot];
      const RateGroup& rg = m.rate_groups[g];
      const double shaft_hz = rg.ratio * w.speed_hz;
      w.slot_shaft_hz[slot] = shaft_hz;
      if (!plan_ok_[g] || !signal.ok()) continue;
      // The revolutions' spread (for the synchronous ratios) costs R more FFTs: measured
      // channels only (the contributions are built from them; the forces are not scored).
      RevolutionSpreadView spread;
      if (cs.signal < m.channels) {
        const std::size_t orders = cw.plans[g].points_per_revolution / 2 + 1;
        const std::span<double> locked(cw.locked_power.data(), orders);
        const std::span<double> between(cw.spread_power.data(), orders);
        if (!cw.tsa->ProcessWithSpread(signal.value(), cw.plans[g], cw.record, locked, between)
                 .ok()) {
          continue;
        }
        spread = {locked, between, cw.record.revolutions, cw.record.nyquist_order};
      } else if (!cw.tsa->Process(signal.value(), cw.plans[g], cw.record).ok()) {
        continue;
      }
      const HealthyMean& na4 = st.band.residual_variance_healthy;
      const double na4_reference = na4.blocks > 0 ? na4.mean[slot] : 0.0;
      if (!cw.indicators
               ->Compute(cw.record.tsa(), cw.record.orders(), rg.mesh_orders, na4_reference,
                         cw.values, spread)
               .ok()) {
        continue;
      }
      double* out = w.indicators.data() + cs.offset;
      std::copy(cw.values.value.begin(), cw.values.value.end(), out);
      std::size_t e = kConditionIndicatorCount;
      for (std::size_t i = 0; i < rg.meshes.size(); ++i) out[e++] = cw.values.sideband_energy[i];
      out[e] = ExclusiveEnergy(cw.record, g);
      // The localisation's entry: this value unless TrackedLocalisation() replaces it.
      // From the revolutions' spread when there is one: an average of R revolutions still
      // passes up to 1/R of another shaft's line, which at 2-3 revolutions named the wrong shaft
      // in most low-speed tuning scenarios (docs/diagnosis.md section 11).
      if (cs.signal < m.channels) {
        w.indicators[m.tracked_offset + slot] =
            spread.revolutions >= 2 ? LockedExclusiveEnergy(g, spread) : out[e];
      }
      w.slot_valid[slot] = 1;
      w.slot_revolutions[slot] = static_cast<int>(cw.record.revolutions);
      if (m.condition_signals[sig].source == ConditionSource::kMeasured) {
        w.slot_transient_samples[slot] = static_cast<int>(
            cw.transient_samples[static_cast<std::size_t>(m.condition_signals[sig].index)]);
      }
      w.slot_residual_variance[slot] = cw.values.residual_variance;
      KeepSignatureLines(ctx, sig, g);
    }
  }
  Signatures(ctx, /*tracked=*/false);
  if (tracked && localisation_only_) TrackedLocalisation(ctx);
  return RejectReason::kNone;
}

}  // namespace gearpath
