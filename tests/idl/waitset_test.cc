// A worker blocked on a WaitSet with no data wakes when the shutdown guard condition is
// triggered, and its thread joins.
#include <gtest/gtest.h>

#include <array>
#include <chrono>
#include <future>
#include <thread>

#include "idl/dds/gearpath_topics.h"
#include "tests/idl/loopback_test_domains.h"

namespace gearpath::dds {
namespace {

using std::chrono::seconds;

constexpr dds_attach_t kDataToken = 1;
constexpr dds_attach_t kShutdownToken = 2;

TEST(WaitSet, GuardConditionWakesAWorkerWaitingForDataSoItsThreadJoins) {
  testing::LoopbackPair pair;
  Topic<gearpath_AccelBlock> topic(pair.subscriber);
  Reader<gearpath_AccelBlock> reader(topic);
  ReadCondition data(reader);
  GuardCondition shutdown(pair.subscriber);
  WaitSet waitset(pair.subscriber);
  waitset.Attach(data, kDataToken);
  waitset.Attach(shutdown, kShutdownToken);

  std::promise<void> waiting;
  // The worker waits far longer than the test's deadline, so only the guard can end it.
  std::future<dds_attach_t> woke_by = std::async(std::launch::async, [&]() -> dds_attach_t {
    waiting.set_value();
    std::array<dds_attach_t, 2> triggered{};
    Result<std::size_t> n = waitset.Wait(triggered, seconds(3600));
    if (!n || *n == 0) return 0;
    return triggered[0];
  });
  waiting.get_future().wait();
  ASSERT_TRUE(shutdown.Trigger());

  if (woke_by.wait_for(seconds(10)) != std::future_status::ready) {
    // Release the worker so the test fails now instead of hanging in ~future: deleting the
    // waitset ends its wait with an error.
    (void)dds_delete(waitset.handle());
    FAIL() << "the worker did not wake on the guard condition";
  }
  EXPECT_EQ(woke_by.get(), kShutdownToken);
  Result<bool> was_triggered = shutdown.TakeTriggered();
  ASSERT_TRUE(was_triggered) << was_triggered.error();
  EXPECT_TRUE(*was_triggered);
  Result<bool> still_triggered = shutdown.TakeTriggered();
  ASSERT_TRUE(still_triggered);
  EXPECT_FALSE(*still_triggered);
}

TEST(WaitSet, TimesOutWithNothingTriggered) {
  testing::LoopbackPair pair;
  GuardCondition guard(pair.subscriber);
  WaitSet waitset(pair.subscriber);
  waitset.Attach(guard, kShutdownToken);
  std::array<dds_attach_t, 1> triggered{};
  Result<std::size_t> n = waitset.Wait(triggered, std::chrono::milliseconds(20));
  ASSERT_TRUE(n) << n.error();
  EXPECT_EQ(*n, 0U);
}

}  // namespace
}  // namespace gearpath::dds
