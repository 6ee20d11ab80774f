// PipelineStage: one arrow of the per-block data flow (DESIGN.md), as a unit with a configure
// step and an allocation-free process step, in the manner of a GNU Radio block.
//
//  - Configure() runs once per machine and block shape (samples per channel): it sizes what the
//    machine keeps, in the stage and in the shared BlockWorkspace. It may allocate and returns
//    an error naming what could not be configured.
//  - Process() runs once per accepted block. It is noexcept and allocates nothing. It reads
//    what earlier stages left in the workspace and the scratch, writes its own part of them and
//    of the BlockResult, and may reject the block (a typed reason plus a one-line message).
//  - Plans and buffers that live only within one Process() call are not the stage's: they are
//    in the ShapeScratch the caller lends (shape_scratch.h), shared with other machines.
//
// The block processor owns the chain and the shared buffers; a stage owns only its math. Adding
// an indicator is adding a stage to BlockProcessor's list.
#pragma once

#include "core/common/accel_block.h"
#include "core/common/result.h"
#include "core/diagnosis/fixed_text.h"
#include "core/pipeline/block_processor.h"
#include "core/pipeline/block_validation.h"

namespace gearpath {

struct MachineContext;
struct MachineState;
struct BlockWorkspace;
struct ShapeScratch;

// Everything a stage sees of one block.
struct StageContext {
  const MachineContext& machine;  // fixed facts about the machine
  MachineState& state;            // what the machine has learned (baselines, alarm state)
  BlockWorkspace& work;           // the machine's per-shape buffers, filled stage by stage
  ShapeScratch& scratch;          // this call's plans and buffers (lent; nothing carries over)
  const AccelBlockView& block;    // the validated block
  BlockResult& out;               // the published result
  MessageText& message;           // rejection message, when a stage rejects
};

class PipelineStage {
 public:
  virtual ~PipelineStage() = default;
  virtual const char* name() const noexcept = 0;
  virtual Status Configure(const MachineContext& machine, BlockWorkspace& work) = 0;
  // kNone = go on; anything else rejects the block (ctx.message says why).
  virtual RejectReason Process(StageContext& ctx) noexcept = 0;
};

}  // namespace gearpath
