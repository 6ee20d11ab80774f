#include "core/pipeline/block_validation.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <string>
#include <string_view>

namespace gearpath {
namespace {

class BlockValidationTest : public ::testing::Test {
 protected:
  void SetUp() override {
    expected_.machine_id = "gb1";
    expected_.channels = {{"A1", Axis::kX}, {"A1", Axis::kY}};
    expected_.sample_rate_hz = 8000.0;
    expected_.sample_rate_tolerance = 1e-4;
    expected_.min_samples_per_channel = 16;
    expected_.max_samples_per_channel = 64;
    expected_.max_total_samples = 1000;
    block_.machine_id = "gb1";
    block_.sequence = 7;
    block_.sample_rate_hz = 8000.0;
    block_.channels = {{"A1", Axis::kX, "m/s^2", 0.0}, {"A1", Axis::kY, "m/s^2", 0.0}};
    block_.samples_per_channel = 32;
    // A live-looking signal: every channel varies (a flat channel is rejected).
    for (int i = 0; i < 64; ++i) block_.samples.push_back(0.25f * static_cast<float>(i % 7) - 0.5f);
  }

  RejectReason Validate() { return ValidateBlock(block_.view(), expected_, message_); }
  std::string Message() const { return std::string(message_.view()); }

  BlockExpectations expected_;
  AccelBlock block_;
  MessageText message_;
};

TEST_F(BlockValidationTest, AcceptsABlockThatMatchesItsMachine) {
  EXPECT_EQ(Validate(), RejectReason::kNone);
  EXPECT_TRUE(message_.empty());
}

TEST_F(BlockValidationTest, RejectsBlockOfAnotherMachineNamingBoth) {
  block_.machine_id = "gb2";
  EXPECT_EQ(Validate(), RejectReason::kUnknownMachine);
  EXPECT_EQ(Message(), "block is for machine 'gb2' but this processor watches machine 'gb1'");
}

TEST_F(BlockValidationTest, RejectsOversizedBlockBeforeReadingIt) {
  block_.samples.assign(1001, 0.0f);
  EXPECT_EQ(Validate(), RejectReason::kOversized);
  EXPECT_EQ(Message(), "block of machine 'gb1' carries 1001 samples, over the cap of 1000");
}

TEST_F(BlockValidationTest, RejectsEmptyBlock) {
  block_.samples.clear();
  block_.samples_per_channel = 0;
  EXPECT_EQ(Validate(), RejectReason::kEmpty);
  EXPECT_EQ(Message(),
            "block 7 of machine 'gb1' is empty (2 channels, 0 samples per channel, 0 samples)");
}

TEST_F(BlockValidationTest, RejectsBlockWithWrongChannelCount) {
  block_.channels.push_back({"A2", Axis::kZ, "m/s^2", 0.0});
  block_.samples.assign(96, 0.0f);
  EXPECT_EQ(Validate(), RejectReason::kWrongChannelCount);
  EXPECT_EQ(Message(), "block has 3 channels but machine 'gb1' has 2");
}

TEST_F(BlockValidationTest, RejectsBlockWhoseChannelLayoutDiffersNamingTheChannel) {
  block_.channels[1].axis = Axis::kZ;
  EXPECT_EQ(Validate(), RejectReason::kWrongChannelLayout);
  EXPECT_EQ(Message(), "channel 1 is A1/z but machine 'gb1' expects A1/y there");
}

TEST_F(BlockValidationTest, RejectsBlockWhoseSampleRateDiffersFromTheMachine) {
  block_.sample_rate_hz = 8192.0;
  EXPECT_EQ(Validate(), RejectReason::kWrongSampleRate);
  EXPECT_EQ(Message(),
            "sample rate 8192 Hz does not match machine 'gb1' (expects 8000 Hz +/- 0.01 %)");
}

TEST_F(BlockValidationTest, AcceptsSampleRateWithinTolerance) {
  block_.sample_rate_hz = 8000.0 * (1.0 + 0.5e-4);
  EXPECT_EQ(Validate(), RejectReason::kNone);
}

TEST_F(BlockValidationTest, RejectsNonFiniteSampleRate) {
  block_.sample_rate_hz = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(Validate(), RejectReason::kWrongSampleRate);
  EXPECT_EQ(Message(),
            "sample rate nan Hz does not match machine 'gb1' (expects 8000 Hz +/- 0.01 %)");
}

TEST_F(BlockValidationTest, RejectsBlockWhoseSizeIsInconsistentWithItsLayout) {
  block_.samples.assign(63, 0.0f);
  EXPECT_EQ(Validate(), RejectReason::kBadLength);
  EXPECT_EQ(Message(), "block carries 63 samples but 2 channels x 32 samples per channel = 64");
}

TEST_F(BlockValidationTest, RejectsTooShortBlock) {
  block_.samples_per_channel = 8;
  block_.samples.assign(16, 0.0f);
  EXPECT_EQ(Validate(), RejectReason::kBadLength);
  EXPECT_EQ(Message(),
            "block has 8 samples per channel, too short for machine 'gb1' (at least 16)");
}

TEST_F(BlockValidationTest, RejectsTooLongBlock) {
  block_.samples_per_channel = 128;
  block_.samples.assign(256, 0.0f);
  EXPECT_EQ(Validate(), RejectReason::kBadLength);
  EXPECT_EQ(Message(),
            "block has 128 samples per channel, too long for machine 'gb1' (at most 64)");
}

TEST_F(BlockValidationTest, RejectsNaNNamingSampleAndChannel) {
  block_.samples[32 + 5] = std::numeric_limits<float>::quiet_NaN();
  EXPECT_EQ(Validate(), RejectReason::kNonFinite);
  EXPECT_EQ(Message(), "sample 5 of channel 1 (A1/y) is NaN");
}

TEST_F(BlockValidationTest, RejectsInfinity) {
  block_.samples[3] = -std::numeric_limits<float>::infinity();
  EXPECT_EQ(Validate(), RejectReason::kNonFinite);
  EXPECT_EQ(Message(), "sample 3 of channel 0 (A1/x) is infinite");
}

TEST_F(BlockValidationTest, AcceptsAnUnknownSpeedOfZeroAndASpeedInRange) {
  expected_.min_speed_hz = 4.0;
  expected_.max_speed_hz = 24.0;
  block_.speed_hz = 0.0;
  EXPECT_EQ(Validate(), RejectReason::kNone);
  block_.speed_hz = -0.0;
  EXPECT_EQ(Validate(), RejectReason::kNone);
  for (double v : {4.0, 10.0, 24.0}) {
    block_.speed_hz = v;
    EXPECT_EQ(Validate(), RejectReason::kNone) << v;
  }
}

TEST_F(BlockValidationTest, RejectsASpeedOf1e300NamingTheValueAndTheRange) {
  expected_.min_speed_hz = 4.0;
  expected_.max_speed_hz = 24.0;
  block_.speed_hz = 1e300;
  EXPECT_EQ(Validate(), RejectReason::kImplausibleSpeed);
  EXPECT_EQ(Message(),
            "speed 1e+300 Hz of block 7 is outside the plausible range of machine 'gb1' "
            "(4..24 Hz)");
  block_.speed_hz = 600.0;  // r/min sent as Hz
  EXPECT_EQ(Validate(), RejectReason::kImplausibleSpeed);
  block_.speed_hz = 1.0;  // below
  EXPECT_EQ(Validate(), RejectReason::kImplausibleSpeed);
}

TEST_F(BlockValidationTest, AcceptsAnyFiniteLoadAndRejectsANaNOrNegativeOneByName) {
  for (double v : {0.0, 0.5, 1e6, 1e300}) {  // 0: not carried; a large one is only a reading
    block_.load = v;
    EXPECT_EQ(Validate(), RejectReason::kNone) << v;
  }
  block_.load = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(Validate(), RejectReason::kImplausibleLoad);
  EXPECT_EQ(Message(), "load nan of block 7 is not a load (finite and > 0, or 0 when unknown)");
  for (double v :
       {-1.0, -std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()}) {
    block_.load = v;
    EXPECT_EQ(Validate(), RejectReason::kImplausibleLoad) << v;
  }
}

TEST_F(BlockValidationTest, RejectsANonFiniteOrNegativeSpeedEvenWithoutARange) {
  for (double v :
       {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(), -10.0}) {
    block_.speed_hz = v;
    EXPECT_EQ(Validate(), RejectReason::kImplausibleSpeed) << v;
  }
  block_.speed_hz = std::numeric_limits<double>::quiet_NaN();
  (void)Validate();
  EXPECT_EQ(Message(),
            "speed nan Hz of block 7 is not a shaft speed (finite and > 0 Hz, or 0 when unknown)");
  block_.speed_hz = 1e300;  // no range configured: only finiteness and sign are checked
  EXPECT_EQ(Validate(), RejectReason::kNone);
}

TEST_F(BlockValidationTest, RejectsAnAllZeroBlock) {
  block_.samples.assign(64, 0.0f);
  EXPECT_EQ(Validate(), RejectReason::kFlatChannel);
  EXPECT_EQ(Message(), "every sample of all 2 channels is zero: sensors or bridge dead?");
}

TEST_F(BlockValidationTest, RejectsOneDeadChannelNamingIt) {
  std::fill(block_.samples.begin() + 32, block_.samples.end(), -0.0f);
  block_.samples[40] = 0.0f;  // +0 and -0 are the same silence
  EXPECT_EQ(Validate(), RejectReason::kFlatChannel);
  EXPECT_EQ(Message(), "every sample of channel 1 (A1/y) is zero: sensor or bridge dead?");
}

TEST_F(BlockValidationTest, RejectsAStuckChannelNamingItsValue) {
  std::fill(block_.samples.begin(), block_.samples.begin() + 32, 2.5f);
  EXPECT_EQ(Validate(), RejectReason::kFlatChannel);
  EXPECT_EQ(Message(),
            "every sample of channel 0 (A1/x) is 2.5: a flat signal, sensor stuck or saturated?");
}

TEST_F(BlockValidationTest, AcceptsAChannelThatVariesInItsLastSampleOnly) {
  std::fill(block_.samples.begin(), block_.samples.begin() + 32, 0.0f);
  block_.samples[31] = 1e-30f;
  EXPECT_EQ(Validate(), RejectReason::kNone);
}

TEST_F(BlockValidationTest, NonFiniteWinsOverFlat) {
  block_.samples.assign(64, 0.0f);
  block_.samples[40] = std::numeric_limits<float>::quiet_NaN();
  EXPECT_EQ(Validate(), RejectReason::kNonFinite);
}

TEST(RejectReasonTest, EveryReasonHasADistinctStableName) {
  EXPECT_EQ(ToString(RejectReason::kWrongSampleRate), "wrong_sample_rate");
  EXPECT_EQ(ToString(RejectReason::kOutOfOrderSequence), "out_of_order_sequence");
  EXPECT_EQ(ToString(RejectReason::kImplausibleSpeed), "implausible_speed");
  EXPECT_EQ(ToString(RejectReason::kFlatChannel), "flat_channel");
  EXPECT_EQ(ToString(RejectReason::kNoSignalInBand), "no_signal_in_band");
  EXPECT_EQ(ToString(RejectReason::kImplausibleLoad), "implausible_load");
  EXPECT_NE(ToString(RejectReason::kBadLength), ToString(RejectReason::kEmpty));
  std::set<std::string_view> names;
  for (int r = 0; r <= static_cast<int>(RejectReason::kImplausibleLoad); ++r) {
    const std::string_view name = ToString(static_cast<RejectReason>(r));
    EXPECT_NE(name, "unknown") << r;
    EXPECT_TRUE(names.insert(name).second) << name;
  }
}

TEST(SequenceTrackerTest, AcceptsTheFirstBlockWhateverItsNumber) {
  SequenceTracker tracker;
  MessageText message;
  const auto v = tracker.Observe(1234, "gb1", message);
  EXPECT_EQ(v.reason, RejectReason::kNone);
  EXPECT_EQ(v.gap, 0u);
  EXPECT_EQ(tracker.last(), 1234u);
}

TEST(SequenceTrackerTest, RejectsDuplicateWithItsMessage) {
  SequenceTracker tracker;
  MessageText message;
  (void)tracker.Observe(5, "gb1", message);
  const auto v = tracker.Observe(5, "gb1", message);
  EXPECT_EQ(v.reason, RejectReason::kDuplicateSequence);
  EXPECT_EQ(std::string(message.view()),
            "block 5 of machine 'gb1' repeats the last accepted sequence number");
}

TEST(SequenceTrackerTest, RejectsLateBlockWithItsMessage) {
  SequenceTracker tracker;
  MessageText message;
  (void)tracker.Observe(5, "gb1", message);
  (void)tracker.Observe(6, "gb1", message);
  const auto v = tracker.Observe(4, "gb1", message);
  EXPECT_EQ(v.reason, RejectReason::kOutOfOrderSequence);
  EXPECT_EQ(std::string(message.view()),
            "block 4 of machine 'gb1' arrived after block 6 (out of order)");
  EXPECT_EQ(tracker.last(), 6u);
}

TEST(SequenceTrackerTest, AcceptsAGapAndReportsHowManyBlocksWereLost) {
  SequenceTracker tracker;
  MessageText message;
  (void)tracker.Observe(10, "gb1", message);
  const auto v = tracker.Observe(14, "gb1", message);
  EXPECT_EQ(v.reason, RejectReason::kNone);
  EXPECT_EQ(v.gap, 3u);
  EXPECT_EQ(tracker.total_gap(), 3u);
  EXPECT_TRUE(message.empty());
}

TEST(SequenceTrackerTest, ResynchronisesAfterAContiguousRunOfBackwardBlocks) {
  SequenceTracker tracker(3);
  MessageText message;
  (void)tracker.Observe(1000, "gb1", message);
  EXPECT_EQ(tracker.Observe(0, "gb1", message).reason, RejectReason::kOutOfOrderSequence);
  EXPECT_EQ(tracker.Observe(1, "gb1", message).reason, RejectReason::kOutOfOrderSequence);
  const auto v = tracker.Observe(2, "gb1", message);
  EXPECT_EQ(v.reason, RejectReason::kNone);
  EXPECT_TRUE(v.restarted);
  EXPECT_EQ(tracker.last(), 2u);
  EXPECT_EQ(tracker.Observe(3, "gb1", message).reason, RejectReason::kNone);
}

TEST(SequenceTrackerTest, ScatteredLateBlocksNeverResynchronise) {
  SequenceTracker tracker(3);
  MessageText message;
  (void)tracker.Observe(100, "gb1", message);
  for (std::uint64_t s : {50u, 20u, 70u, 10u}) {
    EXPECT_EQ(tracker.Observe(s, "gb1", message).reason, RejectReason::kOutOfOrderSequence);
  }
  EXPECT_EQ(tracker.last(), 100u);
}

constexpr std::uint64_t kMaxU64 = std::numeric_limits<std::uint64_t>::max();

TEST(SequenceTrackerTest, SequenceTwoToTheSixtyFourMinusOneIsARestartNotTwoToTheSixtyFourLost) {
  // Issue 10: 2^64-1 after normal blocks made the lost counter 18 446 744 073 709 551 586 and
  // the next two good blocks were rejected.
  SequenceTracker tracker;
  MessageText message;
  for (std::uint64_t s = 1; s <= 30; ++s) {
    ASSERT_EQ(tracker.Observe(s, "gb1", message).reason, RejectReason::kNone);
  }
  auto v = tracker.Observe(kMaxU64, "gb1", message);
  EXPECT_EQ(v.reason, RejectReason::kNone);
  EXPECT_EQ(v.gap, 0u);
  EXPECT_TRUE(v.restarted);
  // The next good blocks are accepted at once: far below 2^64-1 is a restart, not "late".
  v = tracker.Observe(31, "gb1", message);
  EXPECT_EQ(v.reason, RejectReason::kNone);
  EXPECT_EQ(v.gap, 0u);
  EXPECT_TRUE(v.restarted);
  v = tracker.Observe(32, "gb1", message);
  EXPECT_EQ(v.reason, RejectReason::kNone);
  EXPECT_EQ(v.gap, 0u);
  EXPECT_FALSE(v.restarted);
  EXPECT_EQ(tracker.total_gap(), 0u);
}

TEST(SequenceTrackerTest, FromTwoToTheSixtyFourMinusOneToZeroIsARestart) {
  SequenceTracker tracker;
  MessageText message;
  (void)tracker.Observe(kMaxU64 - 1, "gb1", message);
  EXPECT_EQ(tracker.Observe(kMaxU64, "gb1", message).gap, 0u);
  const auto v = tracker.Observe(0, "gb1", message);
  EXPECT_EQ(v.reason, RejectReason::kNone);
  EXPECT_TRUE(v.restarted);
  EXPECT_EQ(tracker.Observe(1, "gb1", message).gap, 0u);
  EXPECT_EQ(tracker.total_gap(), 0u);
}

TEST(SequenceTrackerTest, CountsAGapUpToMaxGapAndTakesALongerJumpAsARestart) {
  SequenceTracker tracker(3, /*max_gap=*/1000, /*reorder_window=*/10);
  MessageText message;
  (void)tracker.Observe(100, "gb1", message);
  auto v = tracker.Observe(1101, "gb1", message);  // exactly 1000 missing
  EXPECT_EQ(v.gap, 1000u);
  EXPECT_FALSE(v.restarted);
  v = tracker.Observe(2103, "gb1", message);  // 1001 missing: a renumbering
  EXPECT_EQ(v.reason, RejectReason::kNone);
  EXPECT_EQ(v.gap, 0u);
  EXPECT_TRUE(v.restarted);
  EXPECT_EQ(tracker.total_gap(), 1000u);
}

TEST(SequenceTrackerTest, AJumpFarBackIsAnImmediateRestartAndANearOneIsLate) {
  SequenceTracker tracker(3, SequenceTracker::kDefaultMaxGap, /*reorder_window=*/10);
  MessageText message;
  (void)tracker.Observe(100, "gb1", message);
  EXPECT_EQ(tracker.Observe(90, "gb1", message).reason, RejectReason::kOutOfOrderSequence);
  const auto v = tracker.Observe(89, "gb1", message);  // 11 back: beyond the window
  EXPECT_EQ(v.reason, RejectReason::kNone);
  EXPECT_TRUE(v.restarted);
  EXPECT_EQ(tracker.last(), 89u);
  EXPECT_EQ(tracker.Observe(90, "gb1", message).gap, 0u);
}

}  // namespace
}  // namespace gearpath
