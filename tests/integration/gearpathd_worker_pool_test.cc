// gearpathd's worker pool over loopback DDS: blocks of several machines published interleaved
// are all processed, each machine's results arrive in block order, and Status counts them all.
// Waits are on conditions with deadlines (ctest's TIMEOUT is the outer watchdog).
#include <gtest/gtest.h>

#include <map>
#include <string>
#include <vector>

#include "tests/integration/gearpathd_fixture.h"

namespace gearpath::testing {
namespace {

constexpr int kMachines = 6;
constexpr std::uint64_t kBlocks = 12;  // per machine; below the results' keep-last 32

class GearpathdWorkerPool : public GearpathdOverDds {
 protected:
  void Configure(json& config) override {
    const json one = config["machines"][0];
    config["machines"] = json::array();
    for (int i = 0; i < kMachines; ++i) {
      json m = one;
      m["id"] = MachineId(i);
      config["machines"].push_back(m);
    }
    config["daemon"]["workers"] = 3;
    // Far smaller than the burst of 6 x 12 blocks: the reader waits for room in a full queue
    // (DDS flow control slows the writer), so every block is still processed, in order.
    config["daemon"]["queue_blocks"] = 2;
    config["daemon"]["log_level"] = "info";
  }
  // Machine 0 keeps the fixture's id, whose Status entry SetUp waits for.
  std::string MachineId(int i) const {
    return i == 0 ? machine_id_ : machine_id_ + "_" + std::to_string(i);
  }
};

TEST_F(GearpathdWorkerPool, InterleavedBlocksOfManyMachinesAllArriveInOrderPerMachine) {
  for (std::uint64_t seq = 0; seq < kBlocks; ++seq) {
    for (int i = 0; i < kMachines; ++i) {
      AccelBlock b = NoiseBlock(seq);
      b.machine_id = MachineId(i);
      Publish(b);
    }
  }
  std::map<std::string, std::vector<std::uint64_t>> seen;
  std::size_t total = 0;
  const auto deadline = std::chrono::steady_clock::now() + 300s;
  std::vector<dds::Owned<gearpath_SuspectedGear>> samples(16);
  std::vector<dds::SampleInfo> infos(16);
  while (total < kMachines * kBlocks && std::chrono::steady_clock::now() < deadline) {
    auto n = gear_reader_->Take(samples, infos);
    ASSERT_TRUE(n.ok()) << n.error();
    for (std::size_t k = 0; k < *n; ++k) {
      if (!infos[k].valid_data) continue;
      seen[std::string(dds::GetString(samples[k]->machine_id))].push_back(
          samples[k]->block_sequence);
      ++total;
    }
    if (*n == 0) std::this_thread::sleep_for(20ms);
  }
  ASSERT_EQ(total, kMachines * kBlocks) << "watchdog: results missing; log:\n" << daemon_->Log();
  for (int i = 0; i < kMachines; ++i) {
    const std::vector<std::uint64_t>& got = seen[MachineId(i)];
    ASSERT_EQ(got.size(), kBlocks) << MachineId(i);
    for (std::uint64_t seq = 0; seq < kBlocks; ++seq) EXPECT_EQ(got[seq], seq) << MachineId(i);
  }
  // Status counts every block of every machine, none rejected.
  for (int i = 0; i < kMachines; ++i) {
    EXPECT_TRUE(WaitStatusOf(daemon_id_, MachineId(i),
                             [](const gearpath_MachineStatus& m) {
                               return m.blocks_processed == kBlocks;
                             },
                             60s))
        << MachineId(i) << ": processed " << last_status_.blocks_processed;
    EXPECT_EQ(last_status_.blocks_rejected, 0u);
    EXPECT_EQ(last_status_.blocks_received, kBlocks);
  }
  EXPECT_NE(daemon_->Log().find("processing on 3 worker thread(s)"), std::string::npos);
}

}  // namespace
}  // namespace gearpath::testing
