#include "core/pipeline/shape_scratch.h"

#include <algorithm>
#include <bit>
#include <utility>

#include "core/pipeline/machine_context.h"

namespace gearpath {

std::size_t SynchronousPointsCap(std::size_t n) noexcept {
  return std::clamp<std::size_t>(std::bit_ceil(n), 4, std::size_t{1} << 16);
}

Result<ShapeScratchKey> ShapeScratchKey::Of(const MachineContext& machine, std::size_t n) {
  const AnalysisOptions& o = machine.setup.options;
  auto envelope = EnvelopeSettings::Of(machine, n);
  if (!envelope) return Error{envelope.error()};
  ShapeScratchKey key;
  key.n = n;
  key.channels = machine.channels;
  key.sample_rate_hz = o.sample_rate_hz;
  key.envelope = envelope.value();
  key.order_tracker = o.order_tracking || o.localisation_tracking;
  key.transient_gate = o.transient_gate;
  return key;
}

Result<std::unique_ptr<ShapeScratch>> ShapeScratch::Create(const ShapeScratchKey& key,
                                                           const MachineContext& machine) {
  const std::size_t n = key.n;
  auto s = std::make_unique<ShapeScratch>();
  s->key = key;
  s->n = n;
  s->bins = n / 2 + 1;
  const double fs = s->key.sample_rate_hz;
  const std::size_t channels = s->key.channels;

  auto spectrum = Spectrum::Create(n, channels, fs);
  if (!spectrum) return Error{"spectra stage: " + spectrum.error()};
  s->spectrum.emplace(std::move(spectrum.value()));
  s->time.assign(channels * n, 0.0);
  s->spec.assign(channels * s->bins, Cd{});

  auto inverse = InverseSpectrum::Create(n, 1);
  if (!inverse) return Error{inverse.error()};
  s->inverse.emplace(std::move(inverse.value()));
  s->one_spec.assign(s->bins, Cd{});
  s->signal.assign(n, 0.0);

  auto envelope = EnvelopeAnalysis::Create(s->key.envelope);
  if (!envelope) return Error{"envelope stage: " + envelope.error()};
  s->envelope.emplace(std::move(envelope.value()));
  s->raw_signal.assign(n, 0.0);
  s->rec_signal.assign(n, 0.0);

  Condition& c = s->condition;
  const std::size_t max_points = SynchronousPointsCap(n);
  auto tsa = SynchronousAverage::Create(n, fs, max_points, SynchronousAverage::OneStepPlan::kNone);
  if (!tsa) return Error{"condition_indicators stage: synchronous average: " + tsa.error()};
  c.tsa.emplace(std::move(tsa.value()));
  auto ind = GearConditionIndicators::Create(max_points);
  if (!ind) return Error{"condition_indicators stage: condition indicators: " + ind.error()};
  c.indicators.emplace(std::move(ind.value()));
  c.record = c.tsa->MakeRecord();
  c.locked_power.assign(max_points / 2 + 1, 0.0);
  c.spread_power.assign(max_points / 2 + 1, 0.0);
  // A block too short for the gate (under 64 samples) is averaged as it is.
  if (key.transient_gate) {
    if (auto gate = TransientGate::Create(n, fs); gate) {
      c.gate.emplace(std::move(gate).value());
      c.residual.assign(n, 0.0);
      c.nominal.assign(n, 0.0);
      c.median_revolution.assign(max_points, 0.0);
      c.wrapped_revolution.assign(max_points + 3, 0.0);
      c.transient.assign(n, 0.0);
      c.cleaned.assign(channels * n, 0.0);
    }
  }
  c.transient_samples.assign(channels, 0);
  if (s->key.order_tracker) {
    // A block too short to track (under 64 samples) is averaged at constant speed.
    if (auto tracker = OrderTracker::Create(n, fs); tracker) {
      c.tracker.emplace(std::move(tracker).value());
      c.warp.assign(n, 0.0);
      c.carrier_warps.assign(kMaxCarrierWarps * n, 0.0);
    }
  }
  s->dominant_time.assign(n, 0.0);
  s->Fit(machine);
  return s;
}

bool ShapeScratch::Serves(const ShapeScratchKey& machine_key,
                          const MachineContext& machine) const noexcept {
  return key == machine_key && condition.plans.size() >= machine.rate_groups.size() &&
         (!condition.gate || condition.periodic_reads.size() >= machine.rate_groups.size());
}

void ShapeScratch::Fit(const MachineContext& machine) {
  while (condition.plans.size() < machine.rate_groups.size()) {
    condition.plans.push_back(condition.tsa->MakePlan());
  }
  while (condition.gate && condition.periodic_reads.size() < machine.rate_groups.size()) {
    condition.periodic_reads.push_back(MakePeriodicReadPlan(n));
  }
}

}  // namespace gearpath
