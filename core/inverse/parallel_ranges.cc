#include "core/inverse/parallel_ranges.h"

#include <algorithm>
#include <exception>
#include <thread>
#include <vector>

namespace gearpath {

unsigned ThreadsForRanges(std::size_t count, std::size_t min_per_thread,
                          unsigned requested) noexcept {
  const unsigned wanted = requested > 0 ? requested : std::thread::hardware_concurrency();
  const std::size_t by_size = count / std::max<std::size_t>(min_per_thread, 1);
  return static_cast<unsigned>(
      std::max<std::size_t>(1, std::min<std::size_t>(std::max(wanted, 1u), by_size)));
}

void ForEachRangeInParallel(std::size_t count, unsigned threads,
                            const std::function<void(std::size_t, std::size_t)>& body) {
  const std::size_t ranges = std::max<std::size_t>(1, std::min<std::size_t>(threads, count));
  // Range r is [r * count / ranges, (r + 1) * count / ranges): sizes differ by at most one.
  auto begin_of = [&](std::size_t r) { return r * count / ranges; };
  std::vector<std::exception_ptr> failures(ranges);
  auto run = [&](std::size_t r) {
    try {
      body(begin_of(r), begin_of(r + 1));
    } catch (...) {
      failures[r] = std::current_exception();
    }
  };
  std::vector<std::thread> workers;
  workers.reserve(ranges - 1);
  try {
    for (std::size_t r = 1; r < ranges; ++r) workers.emplace_back(run, r);
  } catch (...) {
    // Could not start a thread: the ranges not started run here instead.
    for (std::size_t r = workers.size() + 1; r < ranges; ++r) run(r);
  }
  run(0);
  for (std::thread& t : workers) t.join();
  for (const std::exception_ptr& failure : failures) {
    if (failure) std::rethrow_exception(failure);
  }
}

}  // namespace gearpath
