#include "daemon/machine_id_filter.h"

#include <algorithm>
#include <string_view>

#include "idl/dds/gearpath_topics.h"
#include "idl/dds/sequence.h"

namespace gearpath::daemon {

void MachineIdFilter::Admit(std::vector<std::string> ids) {
  std::sort(ids.begin(), ids.end());
  std::lock_guard lock(mutex_);
  ids_ = std::move(ids);
}

bool MachineIdFilter::Admits(std::string_view id) noexcept {
  std::lock_guard lock(mutex_);
  return std::binary_search(ids_.begin(), ids_.end(), id,
                            [](const auto& a, const auto& b) { return a < b; });
}

bool MachineIdFilter::Accept(const void* sample, void* arg) noexcept {
  auto* self = static_cast<MachineIdFilter*>(arg);
  const auto* block = static_cast<const gearpath_AccelBlock*>(sample);
  if (self->Admits(dds::GetString(block->machine_id))) return true;
  self->dropped_.fetch_add(1, std::memory_order_relaxed);
  return false;
}

}  // namespace gearpath::daemon
