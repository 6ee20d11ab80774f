// OperatingBandStage: which of the machine's operating bands this block is judged against
// (AnalysisOptions::operating_bands; docs/diagnosis.md section 10, "Operating bands").
//
// A baseline holds the machine's response at the speeds and loads it learned at, and a block
// outside them is not comparable with it. With one band (the default) such a block is not
// judged. With more, the block is judged against the learned band that holds its speed and
// load; when none does and no fault is suspected (the machine is no_fault, or has just learned
// and not been judged yet), a new band starts learning there from the blocks that stay at that
// operating point, while the state holds; while a fault is suspected no band learns, not even
// one that had begun. That is the guard: a band learned while a fault is present would take
// the fault for healthy there. At most one band learns at a time; a block outside every band
// and outside the learning one restarts that one where the machine now runs (a band learns
// from one operating point, not from a ramp through many). When every band is taken, a block
// outside them all is not judged, as with one band.
//
// The bands swap in and out of MachineState::band (no allocation: the parked slots are made at
// creation), so the stages after this one read the band in force as they read the only one.
#pragma once

#include "core/pipeline/pipeline_stage.h"

namespace gearpath {

struct MachineState;
struct OperatingBand;

class OperatingBandStage final : public PipelineStage {
 public:
  const char* name() const noexcept override { return "operating_band"; }
  Status Configure(const MachineContext& machine, BlockWorkspace& work) override;
  RejectReason Process(StageContext& ctx) noexcept override;
};

// `band` holds a block at this speed, at this load: within its learned range widened by the
// tolerance (a range it has not learned, or a block without a load, holds any value).
bool BandHoldsSpeed(const OperatingBand& band, double speed_hz, double tolerance) noexcept;
bool BandHoldsLoad(const OperatingBand& band, double load, double tolerance) noexcept;

}  // namespace gearpath
