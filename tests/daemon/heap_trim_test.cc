// HeapTrimmer (daemon/heap_trim.h): freed heap pages go back to the kernel when a trim is due,
// and only then.
#include "daemon/heap_trim.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>
#include <vector>

#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define GEARPATH_SANITIZER_ALLOCATOR 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer)
#define GEARPATH_SANITIZER_ALLOCATOR 1
#endif
#endif

namespace gearpath::daemon {
namespace {

using namespace std::chrono_literals;

TEST(HeapTrimmer, TrimsOnlyOnceItsPeriodHasPassed) {
  const HeapTrimmer::Clock::time_point t0{};
  HeapTrimmer trimmer(30s, t0);
  EXPECT_FALSE(trimmer.MaybeTrim(t0));
  EXPECT_FALSE(trimmer.MaybeTrim(t0 + 29s));
  EXPECT_TRUE(trimmer.MaybeTrim(t0 + 30s));
  EXPECT_FALSE(trimmer.MaybeTrim(t0 + 59s));  // the next one a period after the last trim
  EXPECT_TRUE(trimmer.MaybeTrim(t0 + 60s));
}

TEST(HeapTrimmer, GivesFreedPagesInsideTheHeapBackToTheKernel) {
#ifdef GEARPATH_SANITIZER_ALLOCATOR
  GTEST_SKIP() << "the sanitizer's allocator replaces glibc's malloc, which this test measures";
#else
  // 64 MiB in 4 KiB chunks (below the mmap threshold: on the heap), touched, then all freed
  // but the last, which keeps glibc from shrinking the heap from its top by itself: the freed
  // pages stay resident, as the daemon's freed result samples did.
  constexpr std::size_t kChunks = 16384, kChunk = 4096;
  std::vector<char*> chunks(kChunks);
  for (char*& c : chunks) {
    c = static_cast<char*>(std::malloc(kChunk));
    ASSERT_NE(c, nullptr);
    std::memset(c, 1, kChunk);
  }
  for (std::size_t i = 0; i + 1 < kChunks; ++i) std::free(chunks[i]);
  const long resident = HeapTrimmer::ResidentKb();
  ASSERT_GT(resident, 0);
  const long released = HeapTrimmer::Trim();
  const long after = HeapTrimmer::ResidentKb();
  std::free(chunks.back());
  EXPECT_GE(released, 48 * 1024) << "resident " << resident << " kB, after " << after << " kB";
  EXPECT_LE(after, resident - 48 * 1024);
#endif
}

}  // namespace
}  // namespace gearpath::daemon
