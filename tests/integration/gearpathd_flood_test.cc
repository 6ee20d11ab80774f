// A peer that floods the block topic with foreign machine ids cannot stop a legitimate
// machine: the daemon's block reader admits only its own machines (daemon/machine_id_filter.h),
// so 10 000 registered foreign instances take no place in it and its instance limit (256)
// stays free for the machines it judges.
#include "tests/integration/gearpathd_fixture.h"

namespace gearpath::testing {
namespace {

using GearpathdFlood = GearpathdOverDds;

TEST_F(GearpathdFlood, TenThousandForeignMachineIdsDoNotStopALegitimateMachine) {
  // The flooder: its own writer, keeping every instance it wrote registered (keep-last 1, no
  // resource limits), tiny blocks.
  dds::Qos flood_qos;
  flood_qos.Reliable(std::chrono::seconds(1)).Volatile().KeepLast(1);
  dds::Writer<gearpath_AccelBlock> flooder(*block_topic_, flood_qos);
  ASSERT_TRUE(flooder.WaitForReaders(1, 30s).ok());
  AccelBlock tiny = NoiseBlock(1);
  tiny.channels.resize(1);
  tiny.samples_per_channel = 16;
  tiny.samples.resize(16);
  constexpr int kForeign = 10'000;
  int written = 0;
  for (int i = 0; i < kForeign; ++i) {
    tiny.machine_id = "foreign_" + std::to_string(i);
    dds::Owned<gearpath_AccelBlock> sample;
    ASSERT_TRUE(ToWire(tiny, sample));
    if (flooder.Write(*sample).ok()) ++written;
  }
  EXPECT_EQ(written, kForeign) << "the daemon's reader held up the flooder";

  // The legitimate machine's blocks still go through and are processed.
  for (std::uint64_t seq = 1; seq <= 3; ++seq) Publish(NoiseBlock(seq));
  ASSERT_TRUE(WaitStatus([](const auto& m) { return m.blocks_processed == 3; }, 60s))
      << "processed " << last_status_.blocks_processed << ", rejected "
      << last_status_.blocks_rejected << "\n"
      << daemon_->Log();
  // And the foreign blocks were counted, not silently lost (throughput summary, every 1 s).
  const auto deadline = std::chrono::steady_clock::now() + 30s;
  while (daemon_->Log().find("of other machines ignored") == std::string::npos) {
    ASSERT_LT(std::chrono::steady_clock::now(), deadline) << daemon_->Log();
    std::this_thread::sleep_for(50ms);
  }
}

}  // namespace
}  // namespace gearpath::testing
