// Hot standby: two daemons judge the same machine; while the primary lives only its results
// are published (one result per block), and when it is killed the standby's results take over
// within the takeover time (standby.takeover_after_s = 1.5 status periods).
#include "tests/integration/gearpathd_fixture.h"

namespace gearpath::testing {
namespace {

constexpr double kStatusPeriod = 0.5;  // s, both daemons

class GearpathdStandby : public GearpathdOverDds {
 protected:
  void Configure(json& config) override { config["daemon"]["status_period_s"] = kStatusPeriod; }

  void StartStandby() {
    standby_id_ = daemon_id_ + "_standby";
    json c = config_;
    c["daemon"]["id"] = standby_id_;
    c["standby"]["primary"] = daemon_id_;
    const std::string path = (dir_ / "standby.json").string();
    std::ofstream(path) << c.dump(2);
    standby_ = std::make_unique<ChildProcess>(
        GEARPATHD_PATH, std::vector<std::string>{"--config", path},
        (dir_ / "standby.log").string());
    ASSERT_TRUE(standby_->started());
    ASSERT_TRUE(WaitStatusOf(standby_id_, machine_id_, [](const auto&) { return true; }, 90s))
        << standby_->Log();
    ASSERT_TRUE(block_writer_->WaitForReaders(2, 30s).ok()) << standby_->Log();
  }

  void TearDown() override {
    if (standby_ && standby_->running()) {
      standby_->Signal(SIGTERM);
      (void)standby_->WaitExit(5s);
    }
    if (HasFailure() && standby_) std::cerr << "standby log:\n" << standby_->Log() << "\n";
    standby_.reset();
    GearpathdOverDds::TearDown();
  }

  // Every SuspectedGear received so far, counted by block.
  void CountResults(std::map<std::uint64_t, int>& per_block) {
    std::vector<dds::Owned<gearpath_SuspectedGear>> samples(32);
    std::vector<dds::SampleInfo> infos(32);
    for (auto n = gear_reader_->Take(samples, infos); n.ok() && *n > 0;
         n = gear_reader_->Take(samples, infos)) {
      for (std::size_t i = 0; i < *n; ++i) {
        if (infos[i].valid_data) ++per_block[samples[i]->block_sequence];
      }
    }
  }

  std::string standby_id_;
  std::unique_ptr<ChildProcess> standby_;
};

TEST_F(GearpathdStandby, OneResultPerBlockWhileBothLiveAndTheStandbyTakesOverAfterAKill) {
  StartStandby();
  // The standby gives the primary one takeover period to show itself; make sure it has seen it
  // before blocks flow (on a loaded host discovery may take longer than that period).
  const auto seen_by = std::chrono::steady_clock::now() + 60s;
  while (standby_->Log().find("seen: standing by") == std::string::npos) {
    ASSERT_LT(std::chrono::steady_clock::now(), seen_by) << standby_->Log();
    std::this_thread::sleep_for(20ms);
  }

  // Both live: every block judged by both daemons, published once.
  constexpr std::uint64_t kBlocks = 8;
  for (std::uint64_t seq = 1; seq <= kBlocks; ++seq) Publish(NoiseBlock(seq));
  auto both_processed = [&](const auto& m) { return m.blocks_processed == kBlocks; };
  ASSERT_TRUE(WaitStatus(both_processed, 60s)) << "primary processed "
                                               << last_status_.blocks_processed;
  ASSERT_TRUE(WaitStatusOf(standby_id_, machine_id_, both_processed, 60s))
      << "standby processed " << last_status_.blocks_processed << "\n" << standby_->Log();
  // Results are written before the Status that counts their block: all are here or on the way.
  std::map<std::uint64_t, int> per_block;
  const auto all_in = std::chrono::steady_clock::now() + 20s;
  while (per_block.size() < kBlocks && std::chrono::steady_clock::now() < all_in) {
    CountResults(per_block);
    std::this_thread::sleep_for(20ms);
  }
  std::this_thread::sleep_for(std::chrono::duration<double>(kStatusPeriod));  // stragglers
  CountResults(per_block);
  for (std::uint64_t seq = 1; seq <= kBlocks; ++seq) {
    EXPECT_EQ(per_block[seq], 1) << "results of block " << seq;
  }

  // The primary dies; blocks keep coming, one every 0.25 s (the block writer buffers them for
  // the dead reader until its lease expires: 3 s, config/cyclonedds-loopback.xml).
  daemon_->Signal(SIGKILL);
  ASSERT_TRUE(daemon_->WaitExit(30s));
  const auto killed = std::chrono::steady_clock::now();
  std::uint64_t seq = kBlocks;
  std::optional<std::chrono::steady_clock::duration> takeover;
  while (!takeover && std::chrono::steady_clock::now() - killed < 30s) {
    Publish(NoiseBlock(++seq));
    const auto until = std::chrono::steady_clock::now() + 250ms;
    while (!takeover && std::chrono::steady_clock::now() < until) {
      std::map<std::uint64_t, int> after;
      CountResults(after);
      for (const auto& [s, n] : after) {
        if (s > kBlocks) takeover = std::chrono::steady_clock::now() - killed;
      }
      std::this_thread::sleep_for(10ms);
    }
  }
  ASSERT_TRUE(takeover.has_value()) << standby_->Log();
  const double seconds = std::chrono::duration<double>(*takeover).count();
  std::printf("standby results %.2f s after the kill (takeover after %.2f s of silence)\n",
              seconds, 1.5 * kStatusPeriod);
  // Design: silence detected within 1.5 + 0.375 periods of the last Status; the first result
  // then follows the next block (one every 0.25 s here). Generous for a loaded CI host.
  EXPECT_LT(seconds, 6 * kStatusPeriod);
  EXPECT_NE(standby_->Log().find("publishing results from now on"), std::string::npos);
}

}  // namespace
}  // namespace gearpath::testing
