// ConditionIndicatorStage: time-synchronous averages and the classical gear condition
// indicators (core/dsp/synchronous_average.h, core/diagnosis/gear_condition_indicators.h) of
// every condition signal at every shaft rate: each measured channel, each path's contribution
// at its indicator channel and each identified bearing force (DESIGN.md: a fault must be seen
// whether it is impulsive or not, and on whichever signal carries it best).
//
// Besides the standard indicators, per rate group: the sideband energy around each of its
// meshes (which mesh a fault modulates) and the EXCLUSIVE residual: the residual energy (in
// signal units^2) on the orders of this rate that are not harmonics of any other shaft rate. Equal
// tooth ratios make some orders common to two rates (Table 1: 10 Hz and 7 Hz share every 70 Hz
// line); leaving them out keeps one shaft's fault from scoring on another.
//
// Before its averages, each measured channel loses the short transients that none of the
// block's shafts explains (the transient gate, core/dsp/transient_gate.h; an option).
#pragma once

#include <vector>

#include "core/diagnosis/gear_condition_indicators.h"
#include "core/dsp/synchronous_average.h"
#include "core/pipeline/pipeline_stage.h"
#include "core/pipeline/shape_scratch.h"

namespace gearpath {

class ConditionIndicatorStage final : public PipelineStage {
 public:
  const char* name() const noexcept override { return "condition_indicators"; }
  Status Configure(const MachineContext& machine, BlockWorkspace& work) override;
  RejectReason Process(StageContext& ctx) noexcept override;

 private:
  std::span<const double> SignalOf(const StageContext& ctx, std::size_t signal) noexcept;
  void KeepSignatureLines(StageContext& ctx, std::size_t signal, std::size_t group) noexcept;
  // Parallel and orthogonal energies of every signature slot from the kept lines; with
  // `tracked`, only the measured slots', into their tracked entries.
  void Signatures(StageContext& ctx, bool tracked) noexcept;
  // Tracks this block's speed variation into the scratch's warp: the per-sample median of the
  // warps of the first mesh harmonics that track;
  // false (and constant speed) when tracking is off, the block too short or the tone too weak.
  // The machine's first block with a speed decides, once, whether it is tracked at all
  // (MachineState::order_tracking_mode): a baseline must be averaged like the blocks it judges.
  bool TrackOrders(StageContext& ctx) noexcept;
  // A mesh harmonic tried as the tracking carrier: its frequency, its mesh's and shaft's, and
  // the channel where its band is strongest.
  struct Carrier {
    double hz = 0.0;
    double mesh_hz = 0.0;
    double shaft_hz = 0.0;
    std::size_t channel = 0;
  };
  // Over `carriers`: the largest ratio of the revolutions' spread to their locked power on the
  // first mesh harmonics of the carrier's shaft average at constant speed (infinity when one
  // cannot be taken).
  double LargestIncoherence(StageContext& ctx, std::span<const Carrier> carriers) noexcept;
  // Power of the first mesh harmonics in `signal`'s average at `shaft_hz` (averaged into
  // cw.record on cw.plans[0]).
  double MeshCoherence(ShapeScratch::Condition& cw, std::span<const double> signal,
                       double shaft_hz, double mesh_hz, std::span<const double> warp) noexcept;
  // Exclusive residual energy of an average (`record`) at rate group g.
  double ExclusiveEnergy(const SynchronousAverageRecord& record, std::size_t g) const noexcept;
  // The same from the revolutions' spread: only the part locked to the shaft (the shaft
  // evidence at constant speed).
  double LockedExclusiveEnergy(std::size_t g, const RevolutionSpreadView& spread) const noexcept;
  // AnalysisOptions::localisation_tracking: the measured slots' exclusive residuals and
  // transfer signatures again, from averages at the tracked angle (the warp), into the indicator
  // vector's tracked entries (MachineContext::tracked_offset).
  void TrackedLocalisation(StageContext& ctx) noexcept;
  // AnalysisOptions::transient_gate: each measured channel with the transients that none of
  // the block's shaft averages explains taken out (core/dsp/transient_gate.h), into the
  // scratch's `cleaned` rows, which SignalOf() then serves.
  void RemoveTransients(StageContext& ctx, std::span<const double> warp) noexcept;

  // The averager, the per-group grids, the tracker and its warp, the record and the buffers
  // live only within one block: they are the scratch's (ShapeScratch::Condition). Per rate
  // group: 0 where this block's Plan() failed (e.g. less than one revolution in the block).
  std::vector<std::uint8_t> plan_ok_;
  // AnalysisOptions::localisation_tracking without order_tracking: the tracked localisation
  // re-averages the measured channels on the grids after the scored averages.
  bool localisation_only_ = false;
  std::vector<std::vector<std::uint8_t>> exclusive_;  // per group: order line is exclusive
  // signature_slot_[(group * 2 + forces) * kMaxMeshesPerShaft + mesh]: signature slot index.
  std::vector<std::size_t> signature_slot_;
};

}  // namespace gearpath
