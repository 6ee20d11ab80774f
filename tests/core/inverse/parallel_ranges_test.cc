#include "core/inverse/parallel_ranges.h"

#include <gtest/gtest.h>

#include <atomic>
#include <mutex>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace gearpath {
namespace {

TEST(ParallelRanges, EveryIndexRunsExactlyOnceInContiguousRanges) {
  for (const std::size_t count :
       {std::size_t{0}, std::size_t{1}, std::size_t{7}, std::size_t{1000}}) {
    for (const unsigned threads : {1u, 2u, 3u, 16u}) {
      std::vector<std::atomic<int>> hits(count);
      std::mutex mutex;
      std::vector<std::pair<std::size_t, std::size_t>> ranges;
      ForEachRangeInParallel(count, threads, [&](std::size_t begin, std::size_t end) {
        for (std::size_t i = begin; i < end; ++i) hits[i].fetch_add(1);
        const std::lock_guard<std::mutex> lock(mutex);
        ranges.emplace_back(begin, end);
      });
      for (std::size_t i = 0; i < count; ++i) EXPECT_EQ(hits[i].load(), 1) << i;
      std::size_t covered = 0;
      for (const auto& [begin, end] : ranges) {
        EXPECT_LE(begin, end);
        covered += end - begin;
      }
      EXPECT_EQ(covered, count);
      EXPECT_LE(ranges.size(), std::max<std::size_t>(1, std::min<std::size_t>(threads, count)));
    }
  }
}

TEST(ParallelRanges, ThreadCountFollowsTheRequestButNotBelowTheMinimumPerThread) {
  EXPECT_EQ(ThreadsForRanges(8001, 32, 2), 2u);
  EXPECT_EQ(ThreadsForRanges(8001, 32, 1), 1u);
  EXPECT_EQ(ThreadsForRanges(40, 32, 4), 1u);   // too few indices for a second thread
  EXPECT_EQ(ThreadsForRanges(100, 32, 8), 3u);  // at most one thread per 32 indices
  EXPECT_EQ(ThreadsForRanges(0, 32, 4), 1u);
  EXPECT_GE(ThreadsForRanges(1u << 20, 1, 0), 1u);  // 0: the hardware's count (at least 1)
}

TEST(ParallelRanges, AThrowingRangeIsRethrownAfterEveryThreadJoined) {
  std::atomic<int> finished{0};
  try {
    ForEachRangeInParallel(400, 4, [&](std::size_t begin, std::size_t) {
      if (begin == 100) throw std::runtime_error("range at 100");
      finished.fetch_add(1);
    });
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()), "range at 100");
  }
  EXPECT_EQ(finished.load(), 3);
}

}  // namespace
}  // namespace gearpath
