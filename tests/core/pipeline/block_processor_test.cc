// End to end: the Table-1 lumped gearbox, simulated (core/simulation), diagnosed block by
// block. The truth is the fault the simulator was given; nothing below is a number computed by
// the code under test and pasted back.
#include "core/pipeline/block_processor.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <new>
#include <string>
#include <utility>
#include <vector>

#include "core/diagnosis/train_layout.h"
#include "core/pipeline/block_scratch.h"
#include "tests/core/counting_operator_new.h"
#include "tests/core/pipeline/simulated_machine.h"

// Counting allocator: proves Process() allocates nothing once the block shape is configured.
namespace {
std::atomic<long> g_allocations{0};
}  // namespace
void counting_new::OnAllocation() noexcept {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
}

namespace gearpath {
namespace {
using namespace gearpath::testing;

TEST(BlockProcessorCreateTest, RejectsSetupWithoutDecoupledFrf) {
  MachineSetup s = MakeSetup(Table1Machine());
  s.frf_set.decoupled = FrfMatrix{};
  const auto p = BlockProcessor::Create(s);
  ASSERT_FALSE(p.ok());
  EXPECT_EQ(p.error(),
            "machine 'sim': frf_set has no decoupled FRF matrix (run `gearpath decouple` first)");
}

TEST(BlockProcessorCreateTest, RejectsPathNamingAGearOutsideTheTrain) {
  MachineSetup s = MakeSetup(Table1Machine());
  s.frf_set.paths[1].gears = {"G9"};
  const auto p = BlockProcessor::Create(s);
  ASSERT_FALSE(p.ok());
  EXPECT_EQ(p.error(),
            "machine 'sim': frf_set.paths[1] (B2x) names gear 'G9', which is not in "
            "the gear train");
}

TEST(BlockProcessorCreateTest, RejectsBlockChannelWithoutFrfRow) {
  MachineSetup s = MakeSetup(Table1Machine());
  s.block_channels = {{"p1", Axis::kX}, {"p2", Axis::kX}, {"p9", Axis::kX}};
  const auto p = BlockProcessor::Create(s);
  ASSERT_FALSE(p.ok());
  EXPECT_EQ(p.error(), "machine 'sim': block_channels[2] (p9/x) has no row in the FRF set");
}

TEST(BlockProcessorCreateTest, RejectsMissingSampleRate) {
  MachineSetup s = MakeSetup(Table1Machine());
  s.options.sample_rate_hz = 0.0;
  const auto p = BlockProcessor::Create(s);
  ASSERT_FALSE(p.ok());
  EXPECT_EQ(p.error(), "machine 'sim': options.sample_rate_hz must be > 0, got 0");
}

TEST(BlockProcessorTest, RejectsBlockOfWrongSampleRateWithItsMessage) {
  auto p = BlockProcessor::Create(MakeSetup(Table1Machine()));
  ASSERT_TRUE(p.ok()) << p.error();
  GearboxSimulator sim = MakeSimulator(Table1Machine(), FaultType::kNone, "", 1);
  AccelBlock block;
  sim.NextBlock(block);
  block.sample_rate_hz = 8192.0;
  BlockResult r;
  const ProcessOutcome o = p->Process(block.view(), r);
  EXPECT_EQ(o.reason, RejectReason::kWrongSampleRate);
  EXPECT_EQ(o.message.view(),
            "sample rate 8192 Hz does not match machine 'sim' (expects 8000 Hz +/- 0.01 %)");
}

TEST(BlockProcessorTest, ContributionsOfAllPathsReproduceTheMeasuredChannel) {
  // Seed Eq. 45: the response is the sum of the path contributions (up to the identification
  // residual, reported with the result).
  auto p = BlockProcessor::Create(MakeSetup(Table1Machine()));
  ASSERT_TRUE(p.ok()) << p.error();
  GearboxSimulator sim = MakeSimulator(Table1Machine(), FaultType::kNone, "", 3);
  AccelBlock block;
  sim.NextBlock(block);
  BlockResult r;
  ASSERT_TRUE(p->Process(block.view(), r).accepted());
  std::vector<double> sum(kBlock, 0.0), one(kBlock);
  for (std::size_t path = 0; path < 3; ++path) {
    ASSERT_TRUE(p->PathSignal(path, 0, one));
    for (std::size_t i = 0; i < kBlock; ++i) sum[i] += one[i];
  }
  double err = 0.0, ref = 0.0;
  for (std::size_t i = 0; i < kBlock; ++i) {
    const double x = block.samples[i];
    err += (sum[i] - x) * (sum[i] - x);
    ref += x * x;
  }
  // The square, well-conditioned Table-1 system is solved almost exactly; what is left is the
  // out-of-range DC bin and the noise-floor regularisation.
  EXPECT_LT(std::sqrt(err / ref), 0.05);
  EXPECT_LT(r.regularisation.relative_residual, 0.05);
  EXPECT_EQ(r.regularisation.bins_outside_frf, 1u);  // the DC bin
  // The dominant path's published time signal is that path's contribution.
  ASSERT_GE(r.dominant_path, 0);
  ASSERT_TRUE(p->PathSignal(static_cast<std::size_t>(r.dominant_path), 1, one));
  const std::span<const double> dominant = p->DominantPathSignal(1);
  ASSERT_EQ(dominant.size(), kBlock);
  for (std::size_t i = 0; i < kBlock; ++i) EXPECT_DOUBLE_EQ(dominant[i], one[i]);
  EXPECT_TRUE(p->DominantPathSignal(3).empty());  // no such channel
  // Every channel on request, one at a time (each call for another channel makes its signal).
  for (std::size_t c : {0, 2, 1}) {
    ASSERT_TRUE(p->PathSignal(static_cast<std::size_t>(r.dominant_path), c, one));
    const std::span<const double> at = p->DominantPathSignal(c);
    ASSERT_EQ(at.size(), kBlock);
    for (std::size_t i = 0; i < kBlock; ++i) ASSERT_DOUBLE_EQ(at[i], one[i]) << c << " " << i;
  }
  double shares = 0.0;
  for (const BlockPathShare& s : r.paths) shares += s.share;
  EXPECT_NEAR(shares, 1.0, 1e-12);
  EXPECT_EQ(r.speed_source, SpeedSource::kAcquisition);
}

TEST(BlockProcessorTest, AllocatesNothingOnceTheBlockShapeIsConfigured) {
  // A learned baseline and a faulty stream, so the measured block runs every stage: condition
  // indicators, scoring, localisation and the alarm model in its alarm state.
  std::uint64_t seq = 0;
  BlockProcessor p = LearnedProcessor(Table1Machine(), seq);
  GearboxSimulator sim = MakeSimulator(Table1Machine(), FaultType::kToothFracture, "G1", 5);
  AccelBlock block;
  BlockResult r;
  for (int i = 0; i < 3; ++i) {
    sim.NextBlock(block);
    block.sequence = seq++;
    ASSERT_TRUE(p.Process(block.view(), r).accepted());
  }
  sim.NextBlock(block);
  block.sequence = seq++;
  const long before = g_allocations.load();
  const ProcessOutcome o = p.Process(block.view(), r);
  const long after = g_allocations.load();
  EXPECT_TRUE(o.accepted());
  EXPECT_GT(r.score.limit_z, 0.0);
  EXPECT_EQ(r.verdict.state, FaultState::kAlarm) << r.verdict.reason.view();
  EXPECT_EQ(after - before, 0);
}

// Operating bands (operating_band_stage.h): a new band's start and every swap between bands
// take slots made with the processor, so neither allocates.
TEST(BlockProcessorTest, AllocatesNothingToStartOrSwitchAnOperatingBand) {
  MachineSetup setup = MakeSetup(Table1Machine());
  setup.options.operating_bands = 2;
  auto p = BlockProcessor::Create(setup);
  ASSERT_TRUE(p.ok()) << p.error();
  GearboxSimulator sim = MakeSimulator(Table1Machine(), FaultType::kNone, "", 5);
  AccelBlock block;
  BlockResult r;
  std::uint64_t seq = 0;
  const auto run = [&](double load) {
    sim.NextBlock(block);
    block.sequence = seq++;
    block.load = load;
    const long before = g_allocations.load();
    EXPECT_TRUE(p->Process(block.view(), r).accepted());
    return g_allocations.load() - before;
  };
  for (int i = 0; i < kBaselineBlocks + 1; ++i) run(100.0);
  EXPECT_EQ(r.score.operating_bands, 1);
  EXPECT_EQ(run(200.0), 0) << "a new band";
  EXPECT_EQ(r.score.not_judged, NotJudgedCause::kLearningBand);
  EXPECT_EQ(r.score.operating_bands, 2);
  EXPECT_EQ(run(100.0), 0) << "back to the first band";
  EXPECT_EQ(r.score.operating_band, 0);
  EXPECT_TRUE(r.score.judged);
  EXPECT_EQ(run(200.0), 0) << "on to the learning band";
  EXPECT_EQ(r.score.operating_band, 1);
}

// Prepare() does all of a shape's configuring (what the daemon runs at load, before READY=1):
// a machine's very first block after it allocates nothing either, given a result that has been
// filled before (a BlockResult sizes its own vectors on its first use, by any processor of the
// same machine).
TEST(BlockProcessorTest, AllocatesNothingInTheFirstBlockAfterPrepare) {
  const MachineSetup setup = MakeSetup(Table1Machine());
  GearboxSimulator sim = MakeSimulator(Table1Machine(), FaultType::kNone, "", 3);
  AccelBlock block;
  sim.NextBlock(block);
  block.sequence = 1;
  BlockResult r;
  {
    auto earlier = BlockProcessor::Create(setup);
    ASSERT_TRUE(earlier.ok()) << earlier.error();
    ASSERT_TRUE(earlier->Process(block.view(), r).accepted());
  }
  auto p = BlockProcessor::Create(setup);
  ASSERT_TRUE(p.ok()) << p.error();
  ASSERT_TRUE(p->Prepare(kBlock).ok());
  ASSERT_TRUE(p->configured_for(kBlock));
  const long before = g_allocations.load();
  const ProcessOutcome o = p->Process(block.view(), r);
  const long after = g_allocations.load();
  EXPECT_TRUE(o.accepted()) << o.message.view();
  EXPECT_EQ(r.verdict.state, FaultState::kLearning);
  EXPECT_EQ(after - before, 0);
}

// --- Scratch lent by the caller (block_scratch.h): a daemon worker's one scratch serves every
// machine it runs.

// Independent truth: each processor on its own scratch. Three machines take turns on one lent
// scratch: two of one shape (one area, whatever the other left in it) and one of another shape
// and gear train; through learning into faults, every result is the own-scratch run's, bit for
// bit, and so are the signals made after the last block.
TEST(BlockScratchTest, ProcessorsTakingTurnsOnOneScratchGiveTheirOwnScratchResults) {
  const Machine& table1 = Table1Machine();
  const Machine distinct = MakeMachine(/*distinct=*/true);
  constexpr std::uint32_t kShortBlock = 4096;
  struct Run {
    const Machine* machine;
    std::uint32_t n;
    FaultType fault;
    std::string gear;
    std::uint64_t seed;
  };
  const std::vector<Run> runs = {{&table1, kBlock, FaultType::kToothFracture, "G1", 5},
                                 {&table1, kBlock, FaultType::kToothFracture, "G3", 11},
                                 {&distinct, kShortBlock, FaultType::kToothFracture, "G2", 17}};
  std::vector<BlockProcessor> own, lent;
  std::vector<GearboxSimulator> healthy, faulty;
  for (const Run& run : runs) {
    for (auto* list : {&own, &lent}) {
      auto p = BlockProcessor::Create(MakeSetup(*run.machine));
      ASSERT_TRUE(p.ok()) << p.error();
      list->push_back(std::move(p.value()));
    }
    healthy.push_back(MakeSimulator(*run.machine, FaultType::kNone, "", run.seed, true, run.n));
    faulty.push_back(MakeSimulator(*run.machine, run.fault, run.gear, run.seed + 1, true, run.n));
  }
  BlockScratch scratch;
  std::vector<BlockResult> own_results(runs.size()), lent_results(runs.size());
  AccelBlock block;
  for (int b = 0; b < kBaselineBlocks + 5; ++b) {
    for (std::size_t i = 0; i < runs.size(); ++i) {
      (b < kBaselineBlocks ? healthy : faulty)[i].NextBlock(block);
      block.sequence = static_cast<std::uint64_t>(b);
      const ProcessOutcome o = own[i].Process(block.view(), own_results[i]);
      const ProcessOutcome l = lent[i].Process(block.view(), lent_results[i], scratch);
      ASSERT_TRUE(o.accepted()) << o.message.view();
      ASSERT_TRUE(l.accepted()) << l.message.view();
      ExpectSameResult(own_results[i], lent_results[i],
                       "machine " + std::to_string(i) + " block " + std::to_string(b));
    }
  }
  EXPECT_EQ(scratch.areas(), 2u);  // one per shape
  EXPECT_NE(lent_results[0].verdict.state, FaultState::kLearning);
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const std::size_t n = runs[i].n;
    std::vector<double> a(n), b(n), fa(n / 2 + 1), fb(n / 2 + 1);
    ASSERT_TRUE(own[i].PathSignal(0, 0, a));
    ASSERT_TRUE(lent[i].PathSignal(0, 0, b));
    EXPECT_EQ(a, b);
    ASSERT_TRUE(own[i].ForceAmplitude(1, fa));
    ASSERT_TRUE(lent[i].ForceAmplitude(1, fb));
    EXPECT_EQ(fa, fb);
    const auto da = own[i].DominantPathSignal(1);
    const auto db = lent[i].DominantPathSignal(1);
    ASSERT_EQ(da.size(), n);
    EXPECT_TRUE(std::equal(da.begin(), da.end(), db.begin(), db.end()));
  }
}

// What the daemon also does: a machine's blocks go to whichever worker is free, so one machine
// alternates between the workers' scratches. Nothing a block leaves for the next may live in a
// scratch: through learning into a fault, every result equals the own-scratch run's, and the
// fault is alarmed on its gear (independent truth: the seeded fracture on G1).
TEST(BlockScratchTest, AMachineMovingBetweenWorkersGivesItsOwnScratchResults) {
  const Machine& table1 = Table1Machine();
  auto own = BlockProcessor::Create(MakeSetup(table1));
  auto moving = BlockProcessor::Create(MakeSetup(table1));
  ASSERT_TRUE(own.ok() && moving.ok());
  std::array<BlockScratch, 2> workers;
  ASSERT_TRUE(own->Prepare(kBlock).ok());
  for (BlockScratch& w : workers) ASSERT_TRUE(moving->Prepare(kBlock, w).ok());
  GearboxSimulator healthy = MakeSimulator(table1, FaultType::kNone, "", 5);
  GearboxSimulator faulty = MakeSimulator(table1, FaultType::kToothFracture, "G1", 6);
  AccelBlock block;
  BlockResult r_own, r_moving;
  bool alarmed = false;
  for (std::uint64_t seq = 1; seq <= 30; ++seq) {
    (seq <= 22 ? healthy : faulty).NextBlock(block);
    block.sequence = seq;
    ASSERT_TRUE(own->Process(block.view(), r_own).accepted());
    ASSERT_TRUE(moving->Process(block.view(), r_moving, workers[seq % 2]).accepted());
    ExpectSameResult(r_own, r_moving, "block " + std::to_string(seq));
    alarmed = alarmed || (r_moving.verdict.state == FaultState::kAlarm &&
                          r_moving.verdict.gear_name == "G1");
  }
  EXPECT_TRUE(alarmed) << "the fracture on G1 was never alarmed on G1";
}

// What the daemon does: Prepare(n, scratch) of every machine at load, then blocks of machines
// of different shapes taking turns on the one scratch. No block allocates, the first of each
// machine included (given results filled before: a BlockResult sizes itself on first use).
TEST(BlockScratchTest, MachinesOfDifferentShapesTakingTurnsAllocateNothingAfterPrepare) {
  const Machine& table1 = Table1Machine();
  const Machine distinct = MakeMachine(/*distinct=*/true);
  constexpr std::uint32_t kShortBlock = 4096;
  const MachineSetup setup_a = MakeSetup(table1);
  MachineSetup setup_b = MakeSetup(distinct);
  setup_b.options.order_tracking = false;  // a different scratch key besides the length
  setup_b.options.localisation_tracking = false;
  GearboxSimulator sim_a = MakeSimulator(table1, FaultType::kNone, "", 3, true, kBlock);
  GearboxSimulator sim_b = MakeSimulator(distinct, FaultType::kNone, "", 4, true, kShortBlock);
  AccelBlock block_a, block_b;
  BlockResult r_a, r_b;
  {  // fill the results once, as a machine's previous processor would have
    auto a = BlockProcessor::Create(setup_a);
    auto b = BlockProcessor::Create(setup_b);
    ASSERT_TRUE(a.ok() && b.ok());
    sim_a.NextBlock(block_a);
    sim_b.NextBlock(block_b);
    ASSERT_TRUE(a->Process(block_a.view(), r_a).accepted());
    ASSERT_TRUE(b->Process(block_b.view(), r_b).accepted());
  }
  auto a = BlockProcessor::Create(setup_a);
  auto b = BlockProcessor::Create(setup_b);
  ASSERT_TRUE(a.ok()) << a.error();
  ASSERT_TRUE(b.ok()) << b.error();
  BlockScratch scratch;
  ASSERT_TRUE(a->Prepare(kBlock, scratch).ok());
  ASSERT_TRUE(b->Prepare(kShortBlock, scratch).ok());
  EXPECT_EQ(scratch.areas(), 2u);
  for (std::uint64_t seq = 1; seq <= 4; ++seq) {
    sim_a.NextBlock(block_a);
    sim_b.NextBlock(block_b);
    block_a.sequence = seq;
    block_b.sequence = seq;
    const long before = g_allocations.load();
    const ProcessOutcome oa = a->Process(block_a.view(), r_a, scratch);
    const ProcessOutcome ob = b->Process(block_b.view(), r_b, scratch);
    const long after = g_allocations.load();
    EXPECT_TRUE(oa.accepted()) << oa.message.view();
    EXPECT_TRUE(ob.accepted()) << ob.message.view();
    EXPECT_EQ(after - before, 0) << "blocks " << seq;
  }
  EXPECT_EQ(scratch.areas(), 2u);
}

TEST(BlockProcessorTest, EstimatesTheSpeedFromTheMeshLinesWhenNothingGivesIt) {
  MachineSetup s = MakeSetup(Table1Machine());
  s.options.nominal_speed_hz = 0.0;
  s.options.speed_search_lo_hz = 5.0;
  s.options.speed_search_hi_hz = 15.0;
  auto p = BlockProcessor::Create(s);
  ASSERT_TRUE(p.ok()) << p.error();
  GearboxSimulator sim = MakeSimulator(Table1Machine(), FaultType::kNone, "", 9, false);
  AccelBlock block;
  sim.NextBlock(block);
  BlockResult r;
  ASSERT_TRUE(p->Process(block.view(), r).accepted());
  EXPECT_EQ(r.speed_source, SpeedSource::kEstimated);
  EXPECT_NEAR(r.speed_hz, sim.speed_hz(), 0.002 * sim.speed_hz());
}

TEST(BlockProcessorTest, ReportsSequenceGapsAndRejectsDuplicatesWithoutAdvancing) {
  auto p = BlockProcessor::Create(MakeSetup(Table1Machine()));
  ASSERT_TRUE(p.ok()) << p.error();
  GearboxSimulator sim = MakeSimulator(Table1Machine(), FaultType::kNone, "", 1, false);
  AccelBlock block;
  BlockResult r;
  sim.NextBlock(block);
  block.sequence = 10;
  ASSERT_TRUE(p->Process(block.view(), r).accepted());
  EXPECT_EQ(r.sequence_gap, 0u);
  // No speed in the block: the configured nominal speed is used and reported as such.
  EXPECT_EQ(r.speed_source, SpeedSource::kConfiguration);
  EXPECT_DOUBLE_EQ(r.speed_hz, 10.0);
  const ProcessOutcome dup = p->Process(block.view(), r);
  EXPECT_EQ(dup.reason, RejectReason::kDuplicateSequence);
  EXPECT_EQ(dup.message.view(),
            "block 10 of machine 'sim' repeats the last accepted sequence number");
  sim.NextBlock(block);
  block.sequence = 13;
  ASSERT_TRUE(p->Process(block.view(), r).accepted());
  EXPECT_EQ(r.sequence, 13u);
  EXPECT_EQ(r.sequence_gap, 2u);
}

TEST(BlockProcessorTest, HealthyGearboxGivesNoFaultAgainstItsLearnedBaseline) {
  std::uint64_t seq = 0;
  BlockProcessor p = LearnedProcessor(Table1Machine(), seq);
  GearboxSimulator healthy = MakeSimulator(Table1Machine(), FaultType::kNone, "", 11);
  for (int i = 0; i < 3; ++i) {
    const BlockResult r = RunBlocks(p, healthy, 1, seq);
    EXPECT_EQ(r.verdict.state, FaultState::kNoFault) << r.verdict.reason.view();
  }
}

// The score is taken over two blocks (docs/diagnosis.md section 10), but a knock on the housing
// in one block must raise that block only: the previous block's z is clipped before it is
// carried. The knock scores several limits; carried unclipped, it alone would put the next
// healthy block over the limit as well.
// A healthy block with a 3 ms half-sine knock at 30 x each channel's RMS (not tied to any
// shaft: one knock in the block).
AccelBlock HealthyBlockWithAKnock(GearboxSimulator& healthy, std::uint64_t& seq) {
  AccelBlock block;
  healthy.NextBlock(block);
  block.sequence = seq++;
  for (std::size_t c = 0; c < block.channels.size(); ++c) {
    float* x = block.samples.data() + c * block.samples_per_channel;
    double rms = 0.0;
    for (std::uint32_t n = 0; n < block.samples_per_channel; ++n) rms += x[n] * x[n];
    rms = std::sqrt(rms / block.samples_per_channel);
    for (int n = 0; n < 24; ++n) {
      x[1000 + n] += static_cast<float>(30.0 * rms * std::sin(M_PI * n / 24.0));
    }
  }
  return block;
}

// A learned Table-1 machine, two healthy blocks, then the block with a knock.
struct KnockRun {
  BlockProcessor processor;
  GearboxSimulator healthy;
  std::uint64_t seq = 0;
  BlockResult knocked;
};
KnockRun RunAKnock(bool transient_gate) {
  std::uint64_t seq = 0;
  KnockRun run{LearnedProcessor(Table1Machine(), seq, transient_gate),
               MakeSimulator(Table1Machine(), FaultType::kNone, "", 11), 0, {}};
  const BlockResult before = RunBlocks(run.processor, run.healthy, 2, seq);
  EXPECT_LT(before.score.score, 1.0);
  const AccelBlock block = HealthyBlockWithAKnock(run.healthy, seq);
  EXPECT_TRUE(run.processor.Process(block.view(), run.knocked).accepted());
  run.seq = seq;
  return run;
}

// The two-block score: a block that stands out does not carry into the next one. Without the
// transient gate, which would take the knock out of the averages (next test).
TEST(BlockProcessorTest, AKnockInOneBlockDoesNotCarryIntoTheNextBlocksScore) {
  KnockRun run = RunAKnock(/*transient_gate=*/false);
  // Over the limit (it raised NA4 past three limits until the floor became the amplitude's).
  EXPECT_GT(run.knocked.score.score, 1.0)
      << "the knock should stand out: " << run.knocked.score.indicator;
  for (const BlockConditionIndicators& c : run.knocked.condition) {
    EXPECT_EQ(c.transient_samples, 0) << c.signal;
  }
  const BlockResult r = RunBlocks(run.processor, run.healthy, 1, run.seq);
  EXPECT_LT(r.score.score, 1.0) << r.score.indicator;
  EXPECT_EQ(r.verdict.state, FaultState::kNoFault) << r.verdict.reason.view();
}

// With the transient gate (the default) the same knock is taken out before the averages: the
// healthy machine's block scores as healthy.
TEST(BlockProcessorTest, TheTransientGateTakesAKnockOutOfTheAverages) {
  const KnockRun run = RunAKnock(/*transient_gate=*/true);
  EXPECT_LT(run.knocked.score.score, 1.0)
      << "the knock was left in: " << run.knocked.score.indicator;
  EXPECT_EQ(run.knocked.verdict.state, FaultState::kNoFault)
      << run.knocked.verdict.reason.view();
  // The result says so: every measured channel's sets count the samples taken out (the knock's
  // 3 ms and more: its ring-down into the noise), the contributions and forces none.
  for (const BlockConditionIndicators& c : run.knocked.condition) {
    if (c.source == ConditionSource::kMeasured) {
      EXPECT_GE(c.transient_samples, 24) << c.signal;
    } else {
      EXPECT_EQ(c.transient_samples, 0) << c.signal;
    }
  }
}

TEST(BlockProcessorTest, ConfiguredEnvelopeThresholdsArePublishedWhileTheBaselineIsLearned) {
  // Configured envelope thresholds are in force (and published) from the first block; the
  // verdict still waits for the machine's own condition-indicator baseline.
  MachineSetup s = MakeSetup(Table1Machine());
  s.options.raw_thresholds = {1.0, 1.0, 1.0};
  s.options.reconstructed_thresholds = {1.0, 1.0, 1.0};
  auto p = BlockProcessor::Create(s);
  ASSERT_TRUE(p.ok()) << p.error();
  EXPECT_EQ(p->baseline_blocks_needed(), kBaselineBlocks);
  std::uint64_t seq = 0;
  GearboxSimulator healthy = MakeSimulator(Table1Machine(), FaultType::kNone, "", 11);
  BlockResult r = RunBlocks(p.value(), healthy, 1, seq);
  EXPECT_EQ(r.verdict.state, FaultState::kLearning) << r.verdict.reason.view();
  EXPECT_DOUBLE_EQ(r.shafts[0].raw_threshold, 1.0);
  EXPECT_DOUBLE_EQ(r.score.limit_z, 0.0);
  r = RunBlocks(p.value(), healthy, kBaselineBlocks, seq);
  EXPECT_EQ(r.verdict.state, FaultState::kNoFault) << r.verdict.reason.view();
  EXPECT_GT(r.score.limit_z, 0.0);
}

TEST(BlockProcessorCreateTest, RejectsThresholdListsOfTheWrongLength) {
  MachineSetup s = MakeSetup(Table1Machine());
  s.options.raw_thresholds = {1.0, 1.0};
  s.options.reconstructed_thresholds = {1.0, 1.0, 1.0};
  const auto p = BlockProcessor::Create(s);
  ASSERT_FALSE(p.ok());
  EXPECT_EQ(p.error(),
            "machine 'sim': options.raw_thresholds and reconstructed_thresholds need 3 "
            "values each (one per shaft), got 2 and 3");
}

struct Expectation {
  const char* gear;
  std::vector<std::string> candidates;
};

void ExpectDiagnosis(const Machine& m, FaultType type, const Expectation& e) {
  std::uint64_t seq = 0;
  BlockProcessor p = LearnedProcessor(m, seq);
  GearboxSimulator sim = MakeSimulator(m, type, e.gear, 21);
  const BlockResult r = RunBlocks(p, sim, 2, seq);
  SCOPED_TRACE(std::string(FaultTypeName(type)) + " on " + e.gear + ": " +
               std::string(r.verdict.reason.view()));
  EXPECT_NE(r.verdict.state, FaultState::kNoFault);
  ASSERT_EQ(r.verdict.candidate_names.size(), e.candidates.size());
  for (std::size_t i = 0; i < e.candidates.size(); ++i) {
    EXPECT_EQ(r.verdict.candidate_names[i], e.candidates[i]);
  }
  const int shaft = m.train.ShaftOfGear(e.gear);
  EXPECT_NEAR(r.verdict.characteristic_hz,
              r.shafts[static_cast<std::size_t>(shaft)].characteristic_hz, 1e-9);
  EXPECT_GT(r.verdict.confidence, 0.0);
  // The dominant path is a bearing of the faulty gear's mesh (a mesh force loads both shafts).
  ASSERT_GE(r.dominant_path, 0);
  const auto& near = m.frf.paths[static_cast<std::size_t>(r.dominant_path)].gears;
  const int stage = [&] {
    for (std::size_t s = 0; s < m.train.stages.size(); ++s) {
      if (m.train.stages[s].driver == e.gear || m.train.stages[s].driven == e.gear) {
        return static_cast<int>(s);
      }
    }
    return -1;
  }();
  bool on_mesh = false;
  for (const std::string& g : near) {
    on_mesh = on_mesh || g == m.train.stages[static_cast<std::size_t>(stage)].driver ||
              g == m.train.stages[static_cast<std::size_t>(stage)].driven;
  }
  EXPECT_TRUE(on_mesh) << "dominant path " << r.dominant_path_name;
}

TEST(BlockProcessorEndToEndTest, ChippedToothOnEachTable1GearIsTracedToItsGear) {
  const Machine& m = Table1Machine();
  ExpectDiagnosis(m, FaultType::kChippedTooth, {"G1", {"G1"}});
  ExpectDiagnosis(m, FaultType::kChippedTooth, {"G2", {"G2"}});
  ExpectDiagnosis(m, FaultType::kChippedTooth, {"G3", {"G3", "G4"}});
  ExpectDiagnosis(m, FaultType::kChippedTooth, {"G4", {"G3", "G4"}});
}

TEST(BlockProcessorEndToEndTest, WithDistinctToothCountsEveryGearIsToldApart) {
  const Machine m = MakeMachine(true);
  for (const char* g : {"G1", "G2", "G3", "G4"}) {
    ExpectDiagnosis(m, FaultType::kChippedTooth, {g, {g}});
  }
}

// Every dominant-path criterion and every inverse method traces a chipped G1 (10 Hz, mesh 1).
TEST(BlockProcessorEndToEndTest, EveryCriterionAndInverseMethodTracesAChippedGear1) {
  const Machine& m = Table1Machine();
  using Criterion = AnalysisOptions::DominantCriterion;
  for (Criterion criterion :
       {Criterion::kSidebandEnergy, Criterion::kBandEnergy, Criterion::kIndicator}) {
    for (InverseMethod method :
         {InverseMethod::kMwi, InverseMethod::kTikhonov, InverseMethod::kLeastSquares}) {
      MachineSetup s = MakeSetup(m);
      s.options.criterion = criterion;
      s.options.identification.method = method;
      auto p = BlockProcessor::Create(s);
      ASSERT_TRUE(p.ok()) << p.error();
      std::uint64_t seq = 0;
      GearboxSimulator healthy = MakeSimulator(m, FaultType::kNone, "", 7);
      (void)RunBlocks(p.value(), healthy, kBaselineBlocks, seq);
      GearboxSimulator sim = MakeSimulator(m, FaultType::kChippedTooth, "G1", 21);
      const BlockResult r = RunBlocks(p.value(), sim, 3, seq);
      SCOPED_TRACE(std::string(ToString(method)) + " criterion " +
                   std::to_string(static_cast<int>(criterion)) + ": " +
                   std::string(r.verdict.reason.view()));
      EXPECT_EQ(r.criterion, criterion);
      EXPECT_EQ(r.verdict.gear_name, "G1");
      // A mesh force loads both shafts of its pair: B1x or B2x, never B3x (mesh 2 only).
      EXPECT_TRUE(r.dominant_path_name == "B1x" || r.dominant_path_name == "B2x")
          << r.dominant_path_name;
    }
  }
}

// The figures for the lead's note: per fault type and gear on the simulated Table-1 gearbox,
// a fresh machine each (baseline, then three faulty blocks). Prints a table; asserts that
// every chipped-tooth and tooth-fracture case was flagged.
TEST(BlockProcessorEndToEndTest, PrintsTheDiagnosisTableOfTheSimulatedGearbox) {
  const Machine& m = Table1Machine();
  std::printf("\n%-9s %-4s %-5s %-9s %-9s %-5s %-6s %-26s %-11s %-11s %-9s\n", "fault", "gear",
              "dom", "state", "suspected", "conf", "score", "by", "raw", "recon", "enh[%]");
  const auto print = [&](const char* type, const char* gear, const BlockResult& r) {
    std::string suspects;
    for (std::string_view c : r.verdict.candidate_names) {
      suspects += (suspects.empty() ? "" : "/") + std::string(c);
    }
    const int shaft = gear[0] == '-' ? 0 : m.train.ShaftOfGear(gear);
    const auto& sh = r.shafts[static_cast<std::size_t>(shaft)];
    const std::string by = std::string(r.score.indicator) + "@" + std::string(r.score.signal);
    std::printf("%-9s %-4s %-5.*s %-9s %-9s %-5.2f %-6.2f %-26s %-11.4g %-11.4g %-9.0f\n", type,
                gear, static_cast<int>(r.dominant_path_name.size()), r.dominant_path_name.data(),
                std::string(ToString(r.verdict.state)).c_str(),
                suspects.empty() ? "-" : suspects.c_str(), r.verdict.confidence, r.score.score,
                by.c_str(), sh.raw, sh.reconstructed, sh.enhancement_percent);
  };
  for (FaultType type :
       {FaultType::kChippedTooth, FaultType::kLocalizedWear, FaultType::kToothFracture}) {
    for (const char* gear : {"G1", "G2", "G3", "G4"}) {
      std::uint64_t seq = 0;
      BlockProcessor p = LearnedProcessor(m, seq);
      GearboxSimulator sim = MakeSimulator(m, type, gear, 31);
      const BlockResult r = RunBlocks(p, sim, 3, seq);
      print(FaultTypeName(type), gear, r);
      // The simulator's localized wear at severity 1 (a smooth 1.25 um pulse) stays within the
      // healthy spread of a 6-block baseline: printed, not asserted (docs/diagnosis.md).
      if (type != FaultType::kLocalizedWear) {
        EXPECT_NE(r.verdict.state, FaultState::kNoFault)
            << FaultTypeName(type) << " on " << gear << ": " << r.verdict.reason.view();
      }
    }
  }
  std::uint64_t seq = 0;
  BlockProcessor p = LearnedProcessor(m, seq);
  GearboxSimulator healthy = MakeSimulator(m, FaultType::kNone, "", 41);
  const BlockResult r = RunBlocks(p, healthy, 3, seq);
  print("none", "-", r);
  EXPECT_EQ(r.verdict.state, FaultState::kNoFault) << r.verdict.reason.view();
}

}  // namespace
}  // namespace gearpath
