// ShapeScratch: what one Process() call of one block shape works in and carries nothing of into
// the next block: the block's time signals and spectra, one-signal scratch spectra and signals,
// the FFT plans, the envelope analysis, and the condition-indicator stage's averager, grids,
// order tracker and buffers (~13 MB for the reference workload: 12 channels x 16 000 samples).
//
// Why apart from the machine: every buffer here is written before it is read within one call,
// so a worker thread can lend one to whichever machine it runs (BlockScratch, block_scratch.h)
// instead of every machine holding its own (issue 9's memory bar). What a block leaves for the
// next one or for the caller (the identified forces, the learned state, the result) stays in
// the machine's BlockWorkspace / MachineState.
//
// An area is made for a ShapeScratchKey (everything its plans and sizes depend on) and serves
// every machine with that key; the grids per rate group grow to the most any of them needs.
#pragma once

#include <complex>
#include <cstddef>
#include <memory>
#include <optional>
#include <vector>

#include "core/common/result.h"
#include "core/diagnosis/gear_condition_indicators.h"
#include "core/dsp/order_tracker.h"
#include "core/dsp/spectrum.h"
#include "core/dsp/synchronous_average.h"
#include "core/dsp/transient_gate.h"
#include "core/pipeline/envelope_analysis.h"

namespace gearpath {

// Most carriers whose warps the condition stage keeps for their median (three harmonics of three
// meshes; a larger train's first three meshes).
inline constexpr std::size_t kMaxCarrierWarps = 9;
static_assert(kMaxCarrierWarps <= kMaxMedianWarps);

struct MachineContext;

// The cap on the points per revolution of a block of n samples: a whole revolution must fit in
// the block, so M (>= fs / f) never needs to exceed it.
std::size_t SynchronousPointsCap(std::size_t n) noexcept;

struct ShapeScratchKey {
  std::size_t n = 0;         // samples per channel
  std::size_t channels = 0;  // FRF rows
  double sample_rate_hz = 0.0;
  EnvelopeSettings envelope;
  bool order_tracker = false;  // order or localisation tracking: the condition stage tracks
  bool transient_gate = false;  // AnalysisOptions::transient_gate: the condition stage gates
  bool operator==(const ShapeScratchKey&) const = default;

  // Errors name the option (EnvelopeSettings::Of).
  static Result<ShapeScratchKey> Of(const MachineContext& machine, std::size_t n);
};

struct ShapeScratch {
  using Cd = std::complex<double>;

  ShapeScratchKey key;
  std::size_t n = 0;
  std::size_t bins = 0;  // n/2 + 1

  // Spectra stage: the measured samples in FRF row order (channels x n, row-major) and their
  // amplitude spectra (channels x bins); read by every later stage of the same call.
  std::optional<Spectrum> spectrum;
  std::vector<double> time;
  std::vector<Cd> spec;

  // One signal at a time, any stage: a spectrum (bins), its inverse transform, and a time
  // signal (n; condition signals, the dominant-path stage's indicator criterion).
  std::optional<InverseSpectrum> inverse;
  std::vector<Cd> one_spec;
  std::vector<double> signal;

  // Envelope stage (and the indicator criterion): the raw and reconstructed signals (n).
  std::optional<EnvelopeAnalysis> envelope;
  std::vector<double> raw_signal;
  std::vector<double> rec_signal;

  // Condition-indicator stage.
  struct Condition {
    std::optional<SynchronousAverage> tsa;  // no grid of its own: every average runs on plans
    std::optional<GearConditionIndicators> indicators;
    SynchronousAverageRecord record;
    // Per rate group: its shaft's angular grid in this block, shared by every signal (grow-only:
    // the most groups of any machine served). The mesh coherence test borrows plans[0] before
    // the block's groups are planned, the tracked localisation reuses them after.
    std::vector<SynchronousAveragePlan> plans;
    std::optional<OrderTracker> tracker;  // key.order_tracker and a block long enough to track
    std::vector<double> warp;             // n: uniform angle -> sample position
    // Up to kMaxCarrierWarps carriers' warps (n each): the block's warp is their median.
    std::vector<double> carrier_warps;
    // Measured channels: each order's locked power and spread between revolutions, 0..M/2.
    std::vector<double> locked_power;
    std::vector<double> spread_power;
    ConditionIndicatorValues values;
    // The transient gate (core/dsp/transient_gate.h): a measured channel less its shafts'
    // periodic parts (n), each sample's uniform-angle position on a tracked block (n), one
    // shaft's revolution median (max M), the transients' estimate (n), and the measured channels
    // with their transients taken out (channels x n; valid where transient_samples > 0).
    std::optional<TransientGate> gate;  // key.transient_gate and a block long enough
    std::vector<double> residual;
    std::vector<double> nominal;
    std::vector<double> median_revolution;
    std::vector<double> wrapped_revolution;  // max M + 3: SubtractPeriodicPart's scratch
    // Per rate group: where each sample reads that shaft's revolution in this block (grow-only,
    // like `plans`).
    std::vector<PeriodicReadPlan> periodic_reads;
    std::vector<double> transient;
    std::vector<double> cleaned;
    std::vector<std::size_t> transient_samples;  // per measured channel: samples marked
  } condition;

  // BlockProcessor::DominantPathSignal()'s signal (n): only the processor's own scratch is
  // ever asked for it; it lives until the next block.
  std::vector<double> dominant_time;

  // Plans and sizes everything for `machine`'s blocks of key.n samples (`key` is
  // ShapeScratchKey::Of(machine, n)). Allocates (FFTW's planner runs under FftPlan's lock).
  static Result<std::unique_ptr<ShapeScratch>> Create(const ShapeScratchKey& key,
                                                      const MachineContext& machine);

  // True when this area serves `machine` (whose key is `key`) without allocating.
  bool Serves(const ShapeScratchKey& machine_key, const MachineContext& machine) const noexcept;
  // Grows what depends on the machine beyond the key (the grids per rate group). Allocates.
  void Fit(const MachineContext& machine);
};

}  // namespace gearpath
