// gearpathd over loopback DDS: bad blocks, other machines' blocks, late subscribers, reload,
// stop. The daemon is the real binary in a child process.
#include <cstring>
#include <limits>

#include "core/pipeline/block_validation.h"
#include "tests/integration/gearpathd_fixture.h"

namespace gearpath::testing {
namespace {

bool StartsWith(const char* text, std::string_view prefix) {
  return std::string_view(text).substr(0, prefix.size()) == prefix;
}

TEST_F(GearpathdOverDds, ProcessesAGoodBlockAndPublishesEveryResultTopic) {
  Publish(NoiseBlock(1));
  ASSERT_TRUE(WaitStatus([](const auto& m) { return m.blocks_processed == 1; }, 30s));
  EXPECT_EQ(last_status_.blocks_received, 1u);
  EXPECT_EQ(last_status_.blocks_rejected, 0u);
  EXPECT_GE(last_status_.latency_last_ms, 0.0);
  EXPECT_EQ(last_state_, gearpath_RUNNING);
  auto is_first = [](const auto& r) { return r.block_sequence == 1; };
  auto dominant = WaitResult<gearpath_DominantPath>(*dominant_reader_, is_first, 10s);
  ASSERT_TRUE(dominant.has_value());
  double total = 0.0;
  for (const auto& p : dds::View((*dominant)->paths)) total += p.share;
  EXPECT_NEAR(total, 1.0, 1e-9);  // the shares of all paths sum to one
  ASSERT_LT((*dominant)->path_index, (*dominant)->paths._length);
  EXPECT_EQ(dds::GetString((*dominant)->path_name),
            dds::GetString((*dominant)->paths._buffer[(*dominant)->path_index].name));
  EXPECT_TRUE(WaitResult<gearpath_SuspectedGear>(*gear_reader_, is_first, 10s).has_value());
  auto indicators =
      WaitResult<gearpath_EnvelopeIndicators>(*indicators_reader_, is_first, 10s);
  ASSERT_TRUE(indicators.has_value());
  EXPECT_EQ((*indicators)->shafts._length, 3u);  // Table 1: input, intermediate, output
  EXPECT_EQ((*indicators)->speed_hz, 10.0);
}

// A publisher writes the moment the daemon's block reader matches it, while the start-up may
// still be preparing the machines: that block is the machine's, not a foreign one (it was dropped
// once, and the demo's baseline then took in a faulty block).
class GearpathdAtStartUp : public GearpathdOverDds {
 protected:
  GearpathdAtStartUp() { wait_until_ready_ = false; }
};

TEST_F(GearpathdAtStartUp, ABlockWrittenTheMomentTheReaderMatchesIsProcessed) {
  ASSERT_TRUE(block_writer_->WaitForReaders(1, 90s).ok()) << daemon_->Log();
  Publish(NoiseBlock(1));
  ASSERT_TRUE(WaitStatus([](const auto& m) { return m.blocks_processed >= 1; }, 60s))
      << daemon_->Log();
  EXPECT_EQ(last_status_.blocks_processed, 1u);
  EXPECT_EQ(last_status_.blocks_received, 1u);
  EXPECT_EQ(daemon_->Log().find("ignoring blocks of machine"), std::string::npos)
      << daemon_->Log();
}

struct BadBlock {
  const char* what;
  RejectReason reason;
  std::function<void(AccelBlock&)> spoil;
};

TEST_F(GearpathdOverDds, RejectsEveryKindOfBadBlockWithItsReasonAndProcessesTheNextGoodOne) {
  const std::vector<BadBlock> kinds = {
      {"no channels", RejectReason::kEmpty,
       [](AccelBlock& b) {
         b.channels.clear();
         b.samples.clear();
       }},
      {"a channel missing", RejectReason::kWrongChannelCount,
       [](AccelBlock& b) {
         b.channels.pop_back();
         b.samples.resize(b.channels.size() * b.samples_per_channel);
       }},
      {"two channels swapped", RejectReason::kWrongChannelLayout,
       [](AccelBlock& b) { std::swap(b.channels.front(), b.channels.back()); }},
      {"8192 Hz instead of 8000 Hz", RejectReason::kWrongSampleRate,
       [](AccelBlock& b) { b.sample_rate_hz = 8192.0; }},
      {"NaN sample", RejectReason::kNonFinite,
       [](AccelBlock& b) { b.samples[1234] = std::numeric_limits<float>::quiet_NaN(); }},
      {"infinite sample", RejectReason::kNonFinite,
       [](AccelBlock& b) { b.samples.back() = std::numeric_limits<float>::infinity(); }},
      {"samples inconsistent with the layout", RejectReason::kBadLength,
       [](AccelBlock& b) { b.samples.pop_back(); }},
      {"too short", RejectReason::kBadLength,
       [](AccelBlock& b) {
         b.samples_per_channel = 512;
         b.samples.resize(b.channels.size() * 512);
       }},
      {"oversized (longer than the machine's maximum)", RejectReason::kOversized,
       [](AccelBlock& b) {
         b.samples_per_channel = 2 * kBlockLength;
         b.samples.resize(b.channels.size() * 2 * kBlockLength, 0.5f);
       }},
  };
  std::uint64_t seq = 1;
  std::uint64_t processed = 0;
  std::uint64_t rejected = 0;
  Publish(NoiseBlock(seq++));
  ++processed;
  for (const BadBlock& kind : kinds) {
    SCOPED_TRACE(kind.what);
    AccelBlock bad = NoiseBlock(seq++);
    kind.spoil(bad);
    Publish(bad);
    ++rejected;
    const std::string reason(ToString(kind.reason));
    ASSERT_TRUE(WaitStatus(
        [&](const auto& m) {
          return m.blocks_rejected == rejected && StartsWith(m.last_rejection_reason, reason);
        },
        20s))
        << "last rejection: " << last_status_.last_rejection_reason;
    Publish(NoiseBlock(seq++));  // the daemon carries on with the next block
    ++processed;
    ASSERT_TRUE(WaitStatus([&](const auto& m) { return m.blocks_processed == processed; }, 20s));
  }
  // Sequence numbers: a repeat and a late block are rejected; a gap is accepted and counted.
  const std::uint64_t last = seq - 1;
  Publish(NoiseBlock(last));
  ++rejected;
  ASSERT_TRUE(WaitStatus(
      [&](const auto& m) {
        return m.blocks_rejected == rejected &&
               StartsWith(m.last_rejection_reason, ToString(RejectReason::kDuplicateSequence));
      },
      20s))
      << last_status_.last_rejection_reason;
  Publish(NoiseBlock(last - 3));
  ++rejected;
  ASSERT_TRUE(WaitStatus(
      [&](const auto& m) {
        return m.blocks_rejected == rejected &&
               StartsWith(m.last_rejection_reason, ToString(RejectReason::kOutOfOrderSequence));
      },
      20s))
      << last_status_.last_rejection_reason;
  Publish(NoiseBlock(last + 5));  // four blocks lost upstream
  ++processed;
  ASSERT_TRUE(WaitStatus([&](const auto& m) { return m.blocks_processed == processed; }, 20s));
  EXPECT_EQ(last_status_.blocks_received, processed + rejected);
  EXPECT_TRUE(daemon_->WaitForLog("4 block(s) missing before block " + std::to_string(last + 5),
                                  5s));
  // The numbers of the rejected blocks are not reported as lost: only the real gap is.
  EXPECT_EQ(daemon_->Log().find("1 block(s) missing"), std::string::npos) << daemon_->Log();
  // One log line per rejected block, with its reason.
  EXPECT_TRUE(daemon_->WaitForLog("rejected (wrong_sample_rate): sample rate 8192 Hz", 5s));
  EXPECT_TRUE(daemon_->running());
}

TEST_F(GearpathdOverDds, IgnoresBlocksOfMachinesItDoesNotWatchWithoutRejectingThem) {
  AccelBlock foreign = NoiseBlock(1);
  foreign.machine_id = "someone_elses_" + suffix_;
  Publish(foreign);
  Publish(NoiseBlock(1));
  ASSERT_TRUE(WaitStatus([](const auto& m) { return m.blocks_processed == 1; }, 30s));
  EXPECT_EQ(last_status_.blocks_received, 1u);
  EXPECT_EQ(last_status_.blocks_rejected, 0u);
  EXPECT_TRUE(daemon_->WaitForLog("ignoring blocks of machine \"someone_elses_" + suffix_, 5s));
}

TEST_F(GearpathdOverDds, ALateSubscriberReceivesTheLatestResultOfTheMachine) {
  for (std::uint64_t s = 1; s <= 3; ++s) Publish(NoiseBlock(s));
  ASSERT_TRUE(WaitStatus([](const auto& m) { return m.blocks_processed == 3; }, 60s));
  // A dashboard that starts now: its own participant, readers created after the results.
  dds::Participant late(*domain_);
  dds::Topic<gearpath_DominantPath> topic(late);
  dds::Reader<gearpath_DominantPath> reader(topic);
  dds::Topic<gearpath_SuspectedGear> gear_topic(late);
  dds::Reader<gearpath_SuspectedGear> gear_reader(gear_topic);
  // The result history (keep-last 32, docs/topics.md) reaches the late reader, the latest
  // included: it must arrive.
  auto latest = [](const auto& r) { return r.block_sequence == 3u; };
  auto dominant = WaitResult<gearpath_DominantPath>(reader, latest, 10s);
  ASSERT_TRUE(dominant.has_value());
  auto gear = WaitResult<gearpath_SuspectedGear>(gear_reader, latest, 10s);
  ASSERT_TRUE(gear.has_value());
}

TEST_F(GearpathdOverDds, ReloadWithABrokenConfigurationKeepsTheRunningOne) {
  Publish(NoiseBlock(1));
  ASSERT_TRUE(WaitStatus([](const auto& m) { return m.blocks_processed == 1; }, 30s));
  {
    std::ofstream(config_path_) << "{\"daemon\": {\"id\": ";  // truncated file
  }
  daemon_->Signal(SIGHUP);
  EXPECT_TRUE(daemon_->WaitForLog("reload failed, still running the previous configuration",
                                  20s));
  EXPECT_TRUE(daemon_->WaitForLog(config_path_ + ": not valid JSON", 1s));
  // A valid file with an invalid value: refused too, naming the key.
  json invalid = config_;
  invalid["machines"][0]["analysis"]["inverse"]["method"] = "mwii";
  WriteConfig(invalid);
  daemon_->Signal(SIGHUP);
  EXPECT_TRUE(daemon_->WaitForLog("machines[0].analysis.inverse.method: expected one of", 20s));
  EXPECT_TRUE(WaitStatus([&](const auto&) { return last_state_ == gearpath_DEGRADED; }, 5s))
      << "state " << last_state_;
  // Still running the old configuration: the next block is processed.
  Publish(NoiseBlock(2));
  ASSERT_TRUE(WaitStatus([](const auto& m) { return m.blocks_processed == 2; }, 30s));
  // A good configuration reloads and the state is back to running; counters carry over.
  json good = config_;
  good["machines"][0]["analysis"]["inverse"]["method"] = "tikhonov";
  WriteConfig(good);
  daemon_->Signal(SIGHUP);
  EXPECT_TRUE(daemon_->WaitForLog("reload: now running 1 machine(s)", 60s));
  Publish(NoiseBlock(3));
  ASSERT_TRUE(WaitStatus(
      [&](const auto& m) { return m.blocks_processed == 3 && last_state_ == gearpath_RUNNING; },
      30s))
      << "state " << last_state_;
  EXPECT_EQ(last_status_.blocks_received, 3u);
}

TEST_F(GearpathdOverDds, SigtermStopsWithExitCodeZeroWithinTwoSeconds) {
  Publish(NoiseBlock(1));
  ASSERT_TRUE(WaitStatus([](const auto& m) { return m.blocks_processed == 1; }, 30s));
  for (std::uint64_t s = 2; s <= 4; ++s) Publish(NoiseBlock(s));  // blocks in flight
  const auto t0 = std::chrono::steady_clock::now();
  daemon_->Signal(SIGTERM);
  const auto code = daemon_->WaitExit(2s);
  const auto elapsed = std::chrono::steady_clock::now() - t0;
  ASSERT_TRUE(code.has_value()) << "still running 2 s after SIGTERM";
  EXPECT_EQ(*code, 0);
  EXPECT_LT(elapsed, 2s);
  // Its last Status said so.
  ASSERT_TRUE(WaitStatus([&](const auto&) { return last_state_ == gearpath_STOPPING; }, 5s));
}

TEST_F(GearpathdOverDds, SigintStopsLikeSigterm) {
  daemon_->Signal(SIGINT);
  const auto code = daemon_->WaitExit(2s);
  ASSERT_TRUE(code.has_value());
  EXPECT_EQ(*code, 0);
}

}  // namespace
}  // namespace gearpath::testing
