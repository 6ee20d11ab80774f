// HeapTrimmer: gives the heap memory the process has freed back to the kernel, once a period.
//
// Why: every block's results go through Cyclone DDS, whose dds_write allocates a serialised
// sample in the worker's malloc arena (and grows it by realloc) that a Cyclone thread frees once
// the sample has been acknowledged and left the writer's history. The daemon's own block path
// allocates nothing, and the live heap stays flat (heaptrack over 30 000 soak blocks: the
// smallest live heap of each 100 s window was the same to the byte), yet glibc's arenas kept
// extending: free chunks that did not fit the next request, in pages it keeps. The resident set
// crept by about 20 kB a minute (100 000-block soak: +1.65 % over its second half; issue 10's bar
// is 1 %). glibc returns such pages only from the top of the main heap; malloc_trim(0) returns
// every whole free page of every arena (madvise), which brought 1.6 MB back at once in that soak.
//
// Called from the daemon's housekeeping (its reader thread), never per block: a trim takes the
// arenas' locks in turn, so a worker allocating meanwhile waits for it (well under a millisecond
// at a few MB of heap).
#pragma once

#include <chrono>

namespace gearpath::daemon {

class HeapTrimmer {
 public:
  using Clock = std::chrono::steady_clock;
  static constexpr std::chrono::seconds kDefaultPeriod{30};

  explicit HeapTrimmer(Clock::duration period = kDefaultPeriod,
                       Clock::time_point now = Clock::now());

  // Trims if a period has passed since the last trim (or the construction). Returns whether it
  // trimmed.
  bool MaybeTrim(Clock::time_point now);

  // Trims now: malloc_trim(0). Returns the resident kB it gave back (VmRSS before minus after;
  // negative if the process grew meanwhile).
  static long Trim();

  // This process's resident set, kB (/proc/self/status VmRSS); -1 if unreadable.
  static long ResidentKb();

 private:
  Clock::duration period_;
  Clock::time_point next_;
};

}  // namespace gearpath::daemon
