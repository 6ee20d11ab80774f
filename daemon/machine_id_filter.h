// MachineIdFilter: the daemon's block reader admits only the blocks of its own machines.
//
// Every daemon on a domain receives every machine's blocks. Without a filter each foreign
// machine id became an instance in the daemon's reader, whose instance limit (256) a peer
// holding 255 ids exhausted: every legitimate publisher then stalled. The filter runs in
// Cyclone's receive path (dds::Topic::SetSampleFilter), before a sample takes a place in the
// reader: foreign blocks are counted and dropped, and acknowledged so their writer goes on.
// Only the daemon's own machines' instances ever exist in the reader, whose instance limit is
// sized from the configured machine count (gearpathd.cc, BlockInstanceLimit): there is no
// fixed machine cap, and foreign ids cannot exhaust the limit however many there are.
#pragma once

#include <array>
#include <atomic>
#include <cstdint>
#include <mutex>
#include <string>
#include <string_view>
#include <vector>

namespace gearpath::daemon {

class MachineIdFilter {
 public:
  // Replaces the admitted ids (reload). Blocks of a machine added by a reload are admitted
  // from this call on.
  void Admit(std::vector<std::string> ids);

  // The filter callback for dds::Topic<gearpath_AccelBlock>::SetSampleFilter (`arg` is the
  // filter). Called on Cyclone's threads; allocation-free.
  static bool Accept(const void* sample, void* arg) noexcept;
  // The same for dds::Topic<gearpath_AccelBlockV2> (blocks with their load).
  static bool AcceptV2(const void* sample, void* arg) noexcept;

  // Foreign blocks dropped since start.
  std::uint64_t dropped() const noexcept { return dropped_.load(std::memory_order_relaxed); }

  // Foreign ids first seen since the last call (the first kRememberedIds only), for the log:
  // a misspelt machine id shows up as a foreign one. A bound on log lines and fixed storage,
  // not on machines: every foreign block is still dropped and counted (dropped()).
  std::vector<std::string> TakeNewForeignIds();

  static constexpr std::size_t kRememberedIds = 64;

 private:
  bool Judge(std::string_view machine_id) noexcept;  // Admits, else counted and remembered
  bool Admits(std::string_view machine_id) noexcept;
  void Remember(std::string_view machine_id) noexcept;

  std::mutex mutex_;
  std::vector<std::string> ids_;  // sorted
  std::atomic<std::uint64_t> dropped_{0};
  // Fixed storage: the callback must not allocate.
  std::array<std::array<char, 65>, kRememberedIds> foreign_{};
  std::size_t foreign_count_ = 0;
  std::size_t foreign_taken_ = 0;
};

}  // namespace gearpath::daemon
