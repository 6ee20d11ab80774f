#include "core/pipeline/block_scratch.h"

#include "core/pipeline/shape_scratch.h"

namespace gearpath {

BlockScratch::BlockScratch() = default;
BlockScratch::BlockScratch(BlockScratch&&) noexcept = default;
BlockScratch& BlockScratch::operator=(BlockScratch&&) noexcept = default;
BlockScratch::~BlockScratch() = default;

ShapeScratch* BlockScratch::Find(const ShapeScratchKey& key,
                                 const MachineContext& machine) const noexcept {
  for (const auto& area : areas_) {
    if (area->Serves(key, machine)) return area.get();
  }
  return nullptr;
}

Result<ShapeScratch*> BlockScratch::Provide(const ShapeScratchKey& key,
                                            const MachineContext& machine) {
  if (ShapeScratch* area = Find(key, machine)) return area;
  for (const auto& area : areas_) {
    if (area->key == key) {  // the same shape, fewer grids than this machine needs
      area->Fit(machine);
      return area.get();
    }
  }
  auto area = ShapeScratch::Create(key, machine);
  if (!area) return Error{area.error()};
  areas_.push_back(std::move(area.value()));
  return areas_.back().get();
}

}  // namespace gearpath
