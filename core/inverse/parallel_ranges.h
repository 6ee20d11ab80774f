// Splits configuration-time work over independent indices (FRF bins) across threads.
//
// [0, count) is cut into contiguous ranges, one per thread; the calling thread takes the first.
// Threads are started for this call and joined before it returns: no pool, no global state.
// The caller's body must make each index's result independent of the range it falls in, so
// the result is the same for any thread count (IdentificationOperator builds each bin alone).
#pragma once

#include <cstddef>
#include <functional>

namespace gearpath {

// Threads used for `count` indices: `requested` (0 = std::thread::hardware_concurrency(), at
// least 1), but no more than one per `min_per_thread` indices, so small sets stay on the caller.
unsigned ThreadsForRanges(std::size_t count, std::size_t min_per_thread,
                          unsigned requested) noexcept;

// Calls body(begin, end) once per range. If bodies throw, every thread is still joined and the
// exception of the lowest range is rethrown.
void ForEachRangeInParallel(std::size_t count, unsigned threads,
                            const std::function<void(std::size_t, std::size_t)>& body);

}  // namespace gearpath
