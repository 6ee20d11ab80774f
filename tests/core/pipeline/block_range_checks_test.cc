// Range checks through the whole processor (issue 10's odd-but-accepted blocks): a speed of
// 1e300 Hz, a NaN speed, an all-zero block and sequence number 2^64-1 on the simulated
// Table-1 gearbox. Each is rejected with its reason, or (the sequence) accepted without
// corrupting the loss count, and the good blocks around them are processed normally.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "core/pipeline/block_processor.h"
#include "tests/core/pipeline/simulated_machine.h"

namespace gearpath {
namespace {
using namespace gearpath::testing;

class BlockRangeChecksTest : public ::testing::Test {
 protected:
  void SetUp() override {
    auto p = BlockProcessor::Create(MakeSetup(Table1Machine()));
    ASSERT_TRUE(p.ok()) << p.error();
    processor_.emplace(std::move(p.value()));
  }

  AccelBlock NextBlock(std::uint64_t sequence) {
    AccelBlock block;
    sim_.NextBlock(block);
    block.sequence = sequence;
    return block;
  }

  ProcessOutcome Process(const AccelBlock& block) {
    return processor_->Process(block.view(), result_);
  }

  GearboxSimulator sim_ = MakeSimulator(Table1Machine(), FaultType::kNone, "", 11);
  std::optional<BlockProcessor> processor_;
  BlockResult result_;
};

TEST_F(BlockRangeChecksTest, RejectsASpeedOf1e300AndProcessesTheNextBlock) {
  AccelBlock block = NextBlock(1);
  block.speed_hz = 1e300;
  ProcessOutcome o = Process(block);
  EXPECT_EQ(o.reason, RejectReason::kImplausibleSpeed);
  // Nominal 10 Hz, search range +/-20 %: plausible 4..24 Hz.
  EXPECT_EQ(o.message.view(),
            "speed 1e+300 Hz of block 1 is outside the plausible range of machine 'sim' "
            "(4..24 Hz)");
  o = Process(NextBlock(2));
  ASSERT_TRUE(o.accepted()) << o.message.view();
  EXPECT_EQ(result_.speed_hz, 10.0);
  EXPECT_FALSE(result_.dominant_path_name.empty());
}

TEST_F(BlockRangeChecksTest, RejectsANaNSpeedButTakesZeroAsUnknown) {
  AccelBlock block = NextBlock(1);
  block.speed_hz = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(Process(block).reason, RejectReason::kImplausibleSpeed);
  block.speed_hz = 0.0;  // unknown: the nominal speed is used
  const ProcessOutcome o = Process(block);
  ASSERT_TRUE(o.accepted()) << o.message.view();
  EXPECT_EQ(result_.speed_hz, 10.0);
  EXPECT_EQ(result_.speed_source, SpeedSource::kConfiguration);
}

TEST_F(BlockRangeChecksTest, RejectsAnAllZeroBlockSoNoResultNamesAnEmptyPath) {
  AccelBlock block = NextBlock(1);
  std::fill(block.samples.begin(), block.samples.end(), 0.0f);
  const ProcessOutcome o = Process(block);
  EXPECT_EQ(o.reason, RejectReason::kFlatChannel);
  EXPECT_EQ(o.message.view(), "every sample of all 3 channels is zero: sensors or bridge dead?");
  const ProcessOutcome next = Process(NextBlock(2));
  ASSERT_TRUE(next.accepted()) << next.message.view();
  EXPECT_GE(result_.dominant_path, 0);
  EXPECT_FALSE(result_.dominant_path_name.empty());
}

TEST_F(BlockRangeChecksTest, SequenceTwoToTheSixtyFourMinusOneLosesNothingAndRejectsNothing) {
  for (std::uint64_t s = 1; s <= 3; ++s) ASSERT_TRUE(Process(NextBlock(s)).accepted());
  const std::uint64_t huge = std::numeric_limits<std::uint64_t>::max();
  for (std::uint64_t s : {huge, std::uint64_t{4}, std::uint64_t{5}}) {
    SCOPED_TRACE(s);
    const ProcessOutcome o = Process(NextBlock(s));
    ASSERT_TRUE(o.accepted()) << o.message.view();
    EXPECT_EQ(result_.sequence, s);
    EXPECT_EQ(result_.sequence_gap, 0u);  // what the daemon adds to its lost counter
    EXPECT_EQ(result_.sequence_restarted, s != 5);
  }
}

}  // namespace
}  // namespace gearpath
