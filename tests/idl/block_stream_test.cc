// A reliable stream of blocks arrives complete and in order even when the subscriber starts
// taking late: the block profile is keep-all with a per-machine limit of kBlockHistoryDepth on
// both sides, so a full reader history is not acknowledged and the writer waits (flow
// control) instead of anything being overwritten.
#include <gtest/gtest.h>

#include <array>
#include <atomic>
#include <chrono>
#include <future>
#include <thread>
#include <vector>

#include "idl/dds/gearpath_topics.h"
#include "tests/idl/loopback_test_domains.h"

namespace gearpath::dds {
namespace {

using std::chrono::milliseconds;
using std::chrono::seconds;

constexpr std::uint64_t kBlocks = 200;
constexpr std::uint32_t kChannels = 4;
constexpr std::uint32_t kSamplesPerChannel = 1024;

TEST(BlockStream, DeliversEveryBlockInOrderToAReaderThatStartsTakingLate) {
  testing::LoopbackPair pair;
  testing::LoopbackLink<gearpath_AccelBlock> link(pair);
  Writer<gearpath_AccelBlock>& writer = link.writer;
  Reader<gearpath_AccelBlock>& reader = link.reader;
  WaitSet& waitset = link.waitset;
  GuardCondition stop(pair.subscriber);
  waitset.Attach(stop, 2);
  ASSERT_TRUE(writer.WaitForReaders(1, seconds(10)));

  // Whatever happens below (an ASSERT returning early included), stop and join the consumer.
  struct StopAndJoin {
    GuardCondition& stop;
    std::thread& thread;
    ~StopAndJoin() {
      (void)stop.Trigger();
      if (thread.joinable()) thread.join();
    }
  };

  std::promise<void> writer_done;
  std::vector<std::uint64_t> sequences;
  std::vector<bool> payload_ok;
  std::thread consumer([&] {
    // Start late: by now the writer has filled the reader's history several times over if
    // nothing held it back.
    writer_done.get_future().wait_for(milliseconds(500));
    std::vector<Owned<gearpath_AccelBlock>> batch(kBlockHistoryDepth);
    std::vector<SampleInfo> infos(kBlockHistoryDepth);
    const auto deadline = std::chrono::steady_clock::now() + seconds(30);
    while (sequences.size() < kBlocks && std::chrono::steady_clock::now() < deadline) {
      std::array<dds_attach_t, 2> triggered{};
      Result<std::size_t> woke = waitset.Wait(triggered, seconds(1));
      if (!woke) return;
      for (std::size_t i = 0; i < *woke; ++i) {
        if (triggered[i] == 2) return;
      }
      Result<std::size_t> n = reader.Take(batch, infos);
      if (!n) return;
      for (std::size_t i = 0; i < *n; ++i) {
        if (!infos[i].valid_data) continue;
        sequences.push_back(batch[i]->sequence_number);
        const std::span<const float> s = View(batch[i]->samples);
        payload_ok.push_back(s.size() == kChannels * kSamplesPerChannel &&
                             s.front() == static_cast<float>(batch[i]->sequence_number) &&
                             s.back() == -static_cast<float>(batch[i]->sequence_number));
      }
    }
  });
  StopAndJoin stop_and_join{stop, consumer};

  Owned<gearpath_AccelBlock> block;
  ASSERT_TRUE(SetString(block->machine_id, "gearbox-1"));
  block->sample_rate_hz = 25600.0;
  block->samples_per_channel = kSamplesPerChannel;
  ASSERT_TRUE(Resize(block->channels, kChannels));
  ASSERT_TRUE(Resize(block->samples, kChannels * kSamplesPerChannel));
  std::size_t failed_writes = 0;
  std::string first_failure;
  for (std::uint64_t k = 0; k < kBlocks; ++k) {
    block->sequence_number = k;
    MutableView(block->samples).front() = static_cast<float>(k);
    MutableView(block->samples).back() = -static_cast<float>(k);
    // Flow control makes Write wait while the reader's history is full; a write that times
    // out (max_blocking_time 1 s) is retried, as an acquisition bridge would.
    Status status = writer.Write(*block);
    for (int retry = 0; !status && retry < 10; ++retry) {
      if (first_failure.empty()) first_failure = status.error();
      ++failed_writes;
      status = writer.Write(*block);
    }
    ASSERT_TRUE(status) << status.error();
  }
  writer_done.set_value();
  consumer.join();  // it returns once all blocks are in, or after its 30 s deadline

  ASSERT_EQ(sequences.size(), kBlocks) << "first write failure: " << first_failure;
  for (std::uint64_t k = 0; k < kBlocks; ++k) {
    EXPECT_EQ(sequences[k], k);
    EXPECT_TRUE(payload_ok[k]) << "block " << k;
  }
  // Informational: how often the writer had to wait past max_blocking_time.
  RecordProperty("write_timeouts", static_cast<int>(failed_writes));
}

}  // namespace
}  // namespace gearpath::dds
