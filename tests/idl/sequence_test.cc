// The sequence and bounded-string helpers keep idlc samples in the state Owned<T> frees.
#include <gtest/gtest.h>

#include <array>
#include <string>
#include <vector>

#include "idl/dds/gearpath_topics.h"

namespace gearpath::dds {
namespace {

TEST(Sequence, AssignCopiesTheValuesAndTheSampleOwnsTheBuffer) {
  Owned<gearpath_AccelBlock> block;
  const std::array<float, 5> values{1.0F, -2.5F, 3.25F, 0.0F, 1e-30F};
  ASSERT_TRUE(Assign(block->samples, std::span<const float>(values)));
  EXPECT_TRUE(block->samples._release);
  const std::span<const float> view = View(block->samples);
  ASSERT_EQ(view.size(), values.size());
  EXPECT_TRUE(std::equal(view.begin(), view.end(), values.begin()));
}

TEST(Sequence, ShrinkingKeepsTheCapacitySoRegrowingDoesNotReallocate) {
  Owned<gearpath_AccelBlock> block;
  ASSERT_TRUE(Resize(block->samples, 1000));
  float* const buffer = block->samples._buffer;
  ASSERT_TRUE(Resize(block->samples, 10));
  EXPECT_EQ(block->samples._length, 10U);
  ASSERT_TRUE(Resize(block->samples, 1000));
  EXPECT_EQ(block->samples._buffer, buffer);
  EXPECT_EQ(block->samples._maximum, 1000U);
}

TEST(Sequence, GrowingZeroesTheNewElements) {
  Owned<gearpath_DominantPath> result;
  ASSERT_TRUE(Resize(result->paths, 3));
  for (const gearpath_PathShare& p : View(result->paths)) {
    EXPECT_EQ(p.share, 0.0);
    EXPECT_EQ(GetString(p.name), "");
  }
}

TEST(Sequence, RefusesToReallocateABorrowedBuffer) {
  std::array<float, 4> mine{};
  Owned<gearpath_AccelBlock> block;
  block->samples._buffer = mine.data();
  block->samples._maximum = 4;
  block->samples._length = 4;
  block->samples._release = false;  // the sample does not own it: dds_sample_free skips it
  EXPECT_FALSE(Resize(block->samples, 8));
  EXPECT_EQ(block->samples._buffer, mine.data());
  EXPECT_TRUE(Resize(block->samples, 2));  // within capacity: only the length changes
}

TEST(BoundedString, SetStringRefusesAnIdentifierLongerThanTheBound) {
  gearpath_AccelBlock block{};
  const std::string fits(gearpath_ID_LENGTH, 'm');
  EXPECT_TRUE(SetString(block.machine_id, fits));
  EXPECT_EQ(GetString(block.machine_id), fits);
  EXPECT_FALSE(SetString(block.machine_id, fits + "x"));
  EXPECT_EQ(GetString(block.machine_id), fits);  // unchanged
}

TEST(BoundedString, SetStringRefusesAnEmbeddedNul) {
  gearpath_ChannelInfo channel{};
  EXPECT_FALSE(SetString(channel.unit, std::string_view("m/s\0^2", 6)));
}

TEST(Owned, MovingTransfersTheBuffersAndLeavesTheSourceEmpty) {
  Owned<gearpath_AccelBlock> a;
  ASSERT_TRUE(Resize(a->samples, 16));
  float* const buffer = a->samples._buffer;
  Owned<gearpath_AccelBlock> b(std::move(a));
  EXPECT_EQ(b->samples._buffer, buffer);
  EXPECT_EQ(a->samples._buffer, nullptr);  // NOLINT(bugprone-use-after-move): checked on purpose
  Owned<gearpath_AccelBlock> c;
  ASSERT_TRUE(Resize(c->samples, 4));
  c = std::move(b);  // c's old buffer is freed (leak-checked under valgrind)
  EXPECT_EQ(c->samples._buffer, buffer);
}

}  // namespace
}  // namespace gearpath::dds
