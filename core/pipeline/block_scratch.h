// BlockScratch: the work areas of BlockProcessor::Process() (buffers, FFT plans, the stages'
// grids; core/pipeline/shape_scratch.h), lent to whichever machine a thread runs. Nothing in
// it carries from one block to the next, so one BlockScratch per worker thread serves any
// number of machines: ~13 MB per thread instead of per machine for the reference workload
// (issue 9's memory bar).
//
// It holds one area per distinct machine shape it has served (block length, channels, sample
// rate, envelope and tracking options); machines of equal shape share one. An area is made by
// BlockProcessor::Prepare(n, scratch) or by the first Process() that needs it (that call then
// allocates); after that, Process() allocates nothing. Areas are kept until the scratch goes.
//
// Concurrency: one BlockScratch is used by one thread at a time (Process() writes into it).
// Different BlockScratch objects share nothing but FFTW's planner, which FftPlan locks.
#pragma once

#include <cstddef>
#include <memory>
#include <vector>

#include "core/common/result.h"

namespace gearpath {

struct MachineContext;
struct ShapeScratch;
struct ShapeScratchKey;

class BlockScratch {
 public:
  BlockScratch();
  BlockScratch(BlockScratch&&) noexcept;
  BlockScratch& operator=(BlockScratch&&) noexcept;
  BlockScratch(const BlockScratch&) = delete;
  BlockScratch& operator=(const BlockScratch&) = delete;
  ~BlockScratch();

  // Work areas held (one per distinct machine shape served).
  std::size_t areas() const noexcept { return areas_.size(); }

 private:
  friend class BlockProcessor;
  // The area serving `machine` (whose key is `key`); null when there is none yet. No allocation.
  ShapeScratch* Find(const ShapeScratchKey& key, const MachineContext& machine) const noexcept;
  // The same, made or grown when missing (allocates; may throw std::bad_alloc).
  Result<ShapeScratch*> Provide(const ShapeScratchKey& key, const MachineContext& machine);

  std::vector<std::unique_ptr<ShapeScratch>> areas_;
};

}  // namespace gearpath
