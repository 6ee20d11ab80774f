// LanePool: every item of every lane handled, each lane's in order and never on two workers at
// once; a full lane refuses instead of blocking; a paused pool runs nothing. Tests wait on
// conditions with a watchdog, never on timing (the one short wait below must time out).
#include "daemon/lane_pool.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <memory>
#include <mutex>
#include <vector>

namespace gearpath::daemon {
namespace {

using namespace std::chrono_literals;
constexpr auto kWatchdog = 120s;

struct Item {
  int sequence = -1;
  std::unique_ptr<std::vector<int>> buffer;  // a buffer that circulates as a spare
};

struct TestLane : LanePool<Item>::Lane {
  explicit TestLane(std::size_t capacity) : Lane(capacity) {}
  std::vector<int> seen;             // written by the one worker handling the lane
  std::atomic<int> in_handler{0};    // > 1 would mean two workers at once
  std::atomic<bool> overlapped{false};
};

struct Done {
  std::mutex mutex;
  std::condition_variable cv;
  int handled = 0;
  void Add() {
    {
      std::lock_guard lock(mutex);
      ++handled;
    }
    cv.notify_all();
  }
  bool WaitFor(int n) {
    std::unique_lock lock(mutex);
    return cv.wait_for(lock, kWatchdog, [&] { return handled >= n; });
  }
};

TEST(LanePoolTest, InterleavedItemsOfManyLanesAllArriveInOrderOneWorkerPerLaneAtATime) {
  constexpr int kLanes = 24;
  constexpr int kItems = 200;
  Done done;
  // Lanes before the pool: the pool is destroyed first, so its workers (which touch a lane
  // after its handler returns) are joined while every lane still exists.
  std::vector<std::unique_ptr<TestLane>> lanes;
  LanePool<Item> pool(4, 64, [&](std::size_t, LanePool<Item>::Lane& l, Item& item) {
    auto& lane = static_cast<TestLane&>(l);
    if (lane.in_handler.fetch_add(1) != 0) lane.overlapped = true;
    volatile double spin = 0.0;  // a little work, so lanes overlap in time
    for (int i = 0; i < 2000; ++i) spin = spin + i;
    lane.seen.push_back(item.sequence);
    lane.in_handler.fetch_sub(1);
    done.Add();
  });
  for (int l = 0; l < kLanes; ++l) {
    lanes.push_back(std::make_unique<TestLane>(kItems));  // roomy: nothing is dropped here
    lanes.back()->seen.reserve(kItems);
    pool.Attach(*lanes.back(), kLanes);
  }
  for (int i = 0; i < kItems; ++i) {
    for (int l = 0; l < kLanes; ++l) {  // interleaved, as blocks of many machines arrive
      Item item;
      pool.TakeSpare(item);
      if (!item.buffer) item.buffer = std::make_unique<std::vector<int>>(16);
      item.sequence = i;
      ASSERT_TRUE(pool.Offer(*lanes[static_cast<std::size_t>(l)], item));
    }
  }
  ASSERT_TRUE(done.WaitFor(kLanes * kItems)) << "watchdog: " << done.handled << " handled";
  Item spare;  // handled items' buffers come back for reuse
  pool.TakeSpare(spare);
  EXPECT_TRUE(spare.buffer);
  pool.Stop();
  for (int l = 0; l < kLanes; ++l) {
    const TestLane& lane = *lanes[static_cast<std::size_t>(l)];
    EXPECT_FALSE(lane.overlapped) << "lane " << l;
    ASSERT_EQ(lane.seen.size(), static_cast<std::size_t>(kItems)) << "lane " << l;
    for (int i = 0; i < kItems; ++i) EXPECT_EQ(lane.seen[static_cast<std::size_t>(i)], i);
  }
}

TEST(LanePoolTest, AFullLaneRefusesWithoutBlockingAndAPausedPoolHandlesNothing) {
  Done done;
  TestLane lane(3);
  LanePool<Item> pool(2, 8, [&](std::size_t, LanePool<Item>::Lane&, Item&) { done.Add(); });
  pool.Attach(lane, 1);
  pool.Pause();
  Item item;
  for (int i = 0; i < 3; ++i) {
    item.sequence = i;
    EXPECT_TRUE(pool.Offer(lane, item));
  }
  item.sequence = 3;
  EXPECT_FALSE(pool.Offer(lane, item));  // full: refused at once, item left to the caller
  EXPECT_EQ(item.sequence, 3);
  EXPECT_EQ(done.handled, 0);  // paused
  pool.Resume();
  ASSERT_TRUE(done.WaitFor(3)) << "watchdog";
  item.sequence = 4;
  EXPECT_TRUE(pool.Offer(lane, item));  // room again
  ASSERT_TRUE(done.WaitFor(4)) << "watchdog";
}

TEST(LanePoolTest, WaitForRoomReturnsOnceAWorkerTookAnItemOfTheFullLane) {
  Done done;
  TestLane lane(2);
  LanePool<Item> pool(1, 8, [&](std::size_t, LanePool<Item>::Lane&, Item&) { done.Add(); });
  pool.Attach(lane, 1);
  pool.Pause();
  Item item;
  for (int i = 0; i < 2; ++i) {
    item.sequence = i;
    ASSERT_TRUE(pool.Offer(lane, item));
  }
  // Paused: nothing is taken, so the wait times out and says there is no room.
  EXPECT_FALSE(pool.WaitForRoom(lane, 10ms));
  pool.Resume();
  // The worker takes an item: room, well before the watchdog.
  EXPECT_TRUE(pool.WaitForRoom(lane, kWatchdog)) << "watchdog";
  item.sequence = 2;
  EXPECT_TRUE(pool.Offer(lane, item));
  ASSERT_TRUE(done.WaitFor(3)) << "watchdog";
}

TEST(LanePoolTest, ADetachedLaneGivesBackWhatItHeldAndIsNotServedAnyMore) {
  Done done;
  TestLane kept(4), removed(4);
  LanePool<Item> pool(2, 8, [&](std::size_t, LanePool<Item>::Lane&, Item&) { done.Add(); });
  pool.Attach(kept, 2);
  pool.Attach(removed, 2);
  pool.Pause();
  Item item;
  for (int i = 0; i < 2; ++i) {
    ASSERT_TRUE(pool.Offer(removed, item));
    ASSERT_TRUE(pool.Offer(kept, item));
  }
  EXPECT_EQ(pool.Detach(removed), 2u);
  EXPECT_FALSE(pool.Offer(removed, item));  // detached lanes take nothing
  pool.Resume();
  ASSERT_TRUE(done.WaitFor(2)) << "watchdog";
  pool.Stop();
  EXPECT_EQ(done.handled, 2);
}

}  // namespace
}  // namespace gearpath::daemon
