// A publisher that sends nothing but bad blocks cannot flood the daemon's log: each machine
// logs at most 10 rejection lines per throughput period, and the summary counts the rest.
#include "tests/integration/gearpathd_fixture.h"

namespace gearpath::testing {
namespace {

class GearpathdLogRate : public GearpathdOverDds {
 protected:
  void Configure(json& config) override {
    config["daemon"]["throughput_log_period_s"] = 3600.0;  // one period for the whole test
  }
};

TEST_F(GearpathdLogRate, SixtyBadBlocksGiveTenLinesAndACountOfTheRest) {
  constexpr int kBad = 60;
  for (int i = 1; i <= kBad; ++i) {
    AccelBlock bad = NoiseBlock(static_cast<std::uint64_t>(i));
    bad.sample_rate_hz = 8192.0;  // the machine expects 8000 Hz
    Publish(bad);
  }
  ASSERT_TRUE(WaitStatus([](const auto& m) { return m.blocks_rejected == kBad; }, 60s))
      << "rejected " << last_status_.blocks_rejected;
  daemon_->Signal(SIGTERM);
  ASSERT_TRUE(daemon_->WaitExit(30s).has_value());
  const std::string log = daemon_->Log();
  int lines = 0;
  for (std::size_t at = log.find("rejected (wrong_sample_rate)"); at != std::string::npos;
       at = log.find("rejected (wrong_sample_rate)", at + 1)) {
    ++lines;
  }
  EXPECT_EQ(lines, 10) << log;
  // The final summary at stop counts every rejection and the lines left out.
  EXPECT_NE(log.find("60 rejected (wrong_sample_rate 60)"), std::string::npos) << log;
  EXPECT_NE(log.find("(50 rejection lines not logged)"), std::string::npos) << log;
}

}  // namespace
}  // namespace gearpath::testing
