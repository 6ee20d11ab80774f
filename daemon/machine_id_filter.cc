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

void MachineIdFilter::Remember(std::string_view id) noexcept {
  std::lock_guard lock(mutex_);
  if (foreign_count_ == kRememberedIds) return;
  for (std::size_t i = 0; i < foreign_count_; ++i) {
    if (std::string_view(foreign_[i].data()) == id) return;
  }
  const std::size_t n = std::min(id.size(), foreign_[foreign_count_].size() - 1);
  std::copy_n(id.data(), n, foreign_[foreign_count_].data());
  foreign_[foreign_count_][n] = '\0';
  ++foreign_count_;
}

std::vector<std::string> MachineIdFilter::TakeNewForeignIds() {
  std::lock_guard lock(mutex_);
  std::vector<std::string> out;
  for (; foreign_taken_ < foreign_count_; ++foreign_taken_) {
    out.emplace_back(foreign_[foreign_taken_].data());
  }
  return out;
}

bool MachineIdFilter::Judge(std::string_view id) noexcept {
  if (Admits(id)) return true;
  dropped_.fetch_add(1, std::memory_order_relaxed);
  Remember(id);
  return false;
}

bool MachineIdFilter::Accept(const void* sample, void* arg) noexcept {
  const auto* block = static_cast<const gearpath_AccelBlock*>(sample);
  return static_cast<MachineIdFilter*>(arg)->Judge(dds::GetString(block->machine_id));
}

bool MachineIdFilter::AcceptV2(const void* sample, void* arg) noexcept {
  const auto* block = static_cast<const gearpath_AccelBlockV2*>(sample);
  return static_cast<MachineIdFilter*>(arg)->Judge(dds::GetString(block->machine_id));
}

}  // namespace gearpath::daemon
