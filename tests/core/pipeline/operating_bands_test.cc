// A machine whose load moves between operating points learns one baseline per band of speed
// and load (AnalysisOptions::operating_bands, docs/diagnosis.md section 10 "Operating bands").
// The simulated gearbox is excited harder at a higher load (the elastic part of each mesh's
// transmission error grows with the torque it carries); the truth is which band learned which
// blocks, and a tooth fracture at the higher load found against that load's baseline. (That a
// baseline learned at one load flags a healthy machine at another is measured on the evaluation
// families: tests/core/evaluation/evaluation_runner_test.cc, docs/diagnosis.md section 10.)
#include <gtest/gtest.h>

#include <map>
#include <string>
#include <string_view>
#include <utility>

#include "core/pipeline/learned_state_json.h"
#include "tests/core/pipeline/learned_state_round_trip.h"
#include "tests/core/pipeline/simulated_machine.h"

namespace gearpath {
namespace {
using namespace gearpath::testing;

constexpr double kLoad = 100.0;
constexpr double kHighLoad = 150.0;

bool Contains(std::string_view text, std::string_view part) {
  return text.find(part) != std::string_view::npos;
}

// The gearbox at `load` (kLoad = the simulator's default): the elastic part of each mesh's
// transmission error, its fundamental and the loaded deflection, grows with the torque it
// carries; the higher harmonics (profile errors) do not.
GearboxSimulator AtLoad(double load, FaultType type, const std::string& gear,
                        std::uint64_t seed) {
  SimulatorConfig c = MakeSimulator(Table1Machine(), type, gear, seed).config();
  c.excitation.mesh_harmonic_amplitude_m[0] *= load / kLoad;
  c.excitation.deflection_scale_m *= load / kLoad;
  auto sim = GearboxSimulator::Create(Table1Machine().model, Table1Machine().train, c);
  EXPECT_TRUE(sim.ok()) << sim.error();
  return std::move(sim.value());
}

// One gearbox, healthy or with a fault, simulated at each load it is run at.
class Gearbox {
 public:
  Gearbox(FaultType type, std::string gear, std::uint64_t seed)
      : type_(type), gear_(std::move(gear)), seed_(seed) {}
  GearboxSimulator& At(double load) {
    auto it = sims_.find(load);
    if (it == sims_.end()) it = sims_.emplace(load, AtLoad(load, type_, gear_, seed_)).first;
    return it->second;
  }

 private:
  FaultType type_;
  std::string gear_;
  std::uint64_t seed_;
  std::map<double, GearboxSimulator> sims_;
};

// `count` blocks at `load`, carrying it; returns the last result.
BlockResult RunAtLoad(BlockProcessor& p, Gearbox& gearbox, int count, std::uint64_t& seq,
                      double load) {
  return RunBlocks(p, gearbox.At(load), count, seq, load);
}

BlockProcessor Processor(int bands) {
  MachineSetup setup = MakeSetup(Table1Machine());
  setup.options.operating_bands = bands;
  auto p = BlockProcessor::Create(setup);
  EXPECT_TRUE(p.ok()) << p.error();
  return std::move(p.value());
}

// Learned at kLoad, then judged there once (the machine is known healthy: no_fault).
BlockProcessor LearnedAtLoad(int bands, std::uint64_t& seq) {
  BlockProcessor p = Processor(bands);
  Gearbox healthy(FaultType::kNone, "", 7);
  RunAtLoad(p, healthy, kBaselineBlocks, seq, kLoad);
  const BlockResult r = RunAtLoad(p, healthy, 1, seq, kLoad);
  EXPECT_TRUE(r.score.judged);
  EXPECT_EQ(r.verdict.state, FaultState::kNoFault) << r.verdict.reason.view();
  return p;
}

TEST(OperatingBandsTest, OneBandDoesNotJudgeAnotherLoad) {
  std::uint64_t seq = 0;
  BlockProcessor p = LearnedAtLoad(1, seq);
  Gearbox healthy(FaultType::kNone, "", 13);
  for (int b = 0; b < kBaselineBlocks + 2; ++b) {
    const BlockResult r = RunAtLoad(p, healthy, 1, seq, kHighLoad);
    EXPECT_EQ(r.score.not_judged, NotJudgedCause::kLoadOutside);
    EXPECT_EQ(r.score.operating_bands, 1);
  }
}

TEST(OperatingBandsTest, AnAddedBandLearnsAtANewLoadThenJudgesThereAndFindsAFault) {
  std::uint64_t seq = 0;
  BlockProcessor p = LearnedAtLoad(2, seq);
  Gearbox healthy(FaultType::kNone, "", 13);
  // The new band learns: the verdict holds no_fault, with confidence 0 and a reason.
  for (int b = 0; b < kBaselineBlocks; ++b) {
    const BlockResult r = RunAtLoad(p, healthy, 1, seq, kHighLoad);
    EXPECT_FALSE(r.score.judged);
    EXPECT_EQ(r.score.not_judged, NotJudgedCause::kLearningBand);
    EXPECT_EQ(r.verdict.state, FaultState::kNoFault);
    EXPECT_EQ(r.verdict.confidence, 0.0);
    EXPECT_EQ(r.score.operating_band, 1);
    EXPECT_EQ(r.score.operating_bands, 2);
    EXPECT_EQ(r.score.baseline_blocks_learned, b + 1);
    EXPECT_TRUE(Contains(r.verdict.reason.view(), "learning the healthy baseline of operating "
                                                  "band 1 (of up to 2)"))
        << r.verdict.reason.view();
  }
  // Learned: healthy blocks at either load are judged against their own band, and pass.
  for (const auto& [load, band] : {std::pair{kHighLoad, 1}, std::pair{kLoad, 0},
                                   std::pair{kHighLoad, 1}}) {
    const BlockResult r = RunAtLoad(p, healthy, 2, seq, load);
    EXPECT_TRUE(r.score.judged) << load << ": " << r.verdict.reason.view();
    EXPECT_EQ(r.score.operating_band, band) << load;
    EXPECT_EQ(r.verdict.state, FaultState::kNoFault) << load << ": " << r.verdict.reason.view();
    EXPECT_DOUBLE_EQ(r.score.baseline_load_lo, load);
    EXPECT_DOUBLE_EQ(r.score.baseline_load_hi, load);
  }
  // A tooth fracture at the higher load is found against that load's baseline.
  Gearbox broken(FaultType::kToothFracture, "G1", 21);
  const BlockResult r = RunAtLoad(p, broken, 4, seq, kHighLoad);
  EXPECT_TRUE(r.score.judged);
  EXPECT_EQ(r.score.operating_band, 1);
  EXPECT_EQ(r.verdict.state, FaultState::kAlarm) << r.verdict.reason.view();
  EXPECT_EQ(r.verdict.gear_name, "G1") << r.verdict.reason.view();
}

TEST(OperatingBandsTest, NoBandIsLearnedWhileTheMachineIsInAlarm) {
  std::uint64_t seq = 0;
  BlockProcessor p = LearnedAtLoad(2, seq);
  Gearbox broken(FaultType::kToothFracture, "G1", 21);
  ASSERT_EQ(RunAtLoad(p, broken, 4, seq, kLoad).verdict.state, FaultState::kAlarm);
  // The fault goes on at a new load: that load is not learned (it would learn the fault).
  for (int b = 0; b < kBaselineBlocks + 2; ++b) {
    const BlockResult r = RunAtLoad(p, broken, 1, seq, kHighLoad);
    EXPECT_EQ(r.score.not_judged, NotJudgedCause::kLoadOutside);
    EXPECT_EQ(r.score.operating_bands, 1);
    EXPECT_EQ(r.verdict.state, FaultState::kAlarm);  // held
  }
}

// A band that had begun to learn before the fault learns nothing more while the fault is
// suspected, even at its own operating point.
TEST(OperatingBandsTest, ALearningBandStopsLearningWhileTheMachineIsInAlarm) {
  std::uint64_t seq = 0;
  BlockProcessor p = LearnedAtLoad(2, seq);
  Gearbox healthy(FaultType::kNone, "", 13);
  EXPECT_EQ(RunAtLoad(p, healthy, 2, seq, kHighLoad).score.baseline_blocks_learned, 2);
  Gearbox broken(FaultType::kToothFracture, "G1", 21);
  ASSERT_EQ(RunAtLoad(p, broken, 4, seq, kLoad).verdict.state, FaultState::kAlarm);
  for (int b = 0; b < kBaselineBlocks; ++b) {
    const BlockResult r = RunAtLoad(p, broken, 1, seq, kHighLoad);
    EXPECT_EQ(r.score.not_judged, NotJudgedCause::kLoadOutside) << b;
    EXPECT_EQ(r.score.operating_band, 0) << b;
    EXPECT_EQ(r.verdict.state, FaultState::kAlarm);  // held
  }
  const LearnedState saved = p.ExportLearnedState();
  ASSERT_EQ(saved.parked_bands.size(), 1u);
  EXPECT_EQ(saved.parked_bands[0].indicator_baseline.count, 2);
}

TEST(OperatingBandsTest, ALearningBandRestartsWhereTheMachineNowRuns) {
  std::uint64_t seq = 0;
  BlockProcessor p = LearnedAtLoad(3, seq);
  Gearbox healthy(FaultType::kNone, "", 13);
  EXPECT_EQ(RunAtLoad(p, healthy, 3, seq, kHighLoad).score.baseline_blocks_learned, 3);
  // At 200 % before the 150 % band completed: the learning band starts again there.
  const BlockResult r = RunAtLoad(p, healthy, 1, seq, 200.0);
  EXPECT_EQ(r.score.not_judged, NotJudgedCause::kLearningBand);
  EXPECT_EQ(r.score.baseline_blocks_learned, 1);
  EXPECT_EQ(r.score.operating_band, 1);
  EXPECT_EQ(r.score.operating_bands, 2);
  // The learned band still judges its own load meanwhile.
  const BlockResult back = RunAtLoad(p, healthy, 1, seq, kLoad);
  EXPECT_TRUE(back.score.judged);
  EXPECT_EQ(back.score.operating_band, 0);
}

// A band is one of speed as well as load: a machine stepped to 10 % more speed (far outside
// speed_tolerance) learns a band there and judges there, as after a load step.
TEST(OperatingBandsTest, AnAddedBandLearnsAtANewSpeed) {
  std::uint64_t seq = 0;
  BlockProcessor p = Processor(2);
  GearboxSimulator slow = MakeSimulator(Table1Machine(), FaultType::kNone, "", 7);
  RunBlocks(p, slow, kBaselineBlocks + 1, seq);
  GearboxSimulator fast = MakeSimulator(Table1Machine(), FaultType::kNone, "", 13, true, kBlock,
                                        /*input_speed_hz=*/11.0);
  for (int b = 0; b < kBaselineBlocks; ++b) {
    const BlockResult r = RunBlocks(p, fast, 1, seq);
    EXPECT_EQ(r.score.not_judged, NotJudgedCause::kLearningBand) << b;
  }
  const BlockResult r = RunBlocks(p, fast, 2, seq);
  EXPECT_TRUE(r.score.judged) << r.verdict.reason.view();
  EXPECT_EQ(r.score.operating_band, 1);
  EXPECT_NEAR(r.score.baseline_speed_lo_hz, fast.speed_hz(), 1e-9);
  EXPECT_EQ(r.verdict.state, FaultState::kNoFault) << r.verdict.reason.view();
  const BlockResult back = RunBlocks(p, slow, 1, seq);
  EXPECT_TRUE(back.score.judged);
  EXPECT_EQ(back.score.operating_band, 0);
}

TEST(OperatingBandsTest, EveryBandTravelsWithTheState) {
  std::uint64_t seq = 0;
  BlockProcessor p = LearnedAtLoad(2, seq);
  Gearbox healthy(FaultType::kNone, "", 13);
  RunAtLoad(p, healthy, kBaselineBlocks + 1, seq, kHighLoad);  // band 1 learned and in use
  const LearnedState saved = ThroughJson(p.ExportLearnedState());
  EXPECT_EQ(saved.band_id, 1);
  ASSERT_EQ(saved.parked_bands.size(), 1u);
  EXPECT_EQ(saved.parked_bands[0].band_id, 0);
  EXPECT_DOUBLE_EQ(saved.parked_bands[0].baseline_load_lo, kLoad);

  BlockProcessor resumed = Processor(2);
  ASSERT_TRUE(resumed.ImportLearnedState(saved).ok());
  EXPECT_EQ(resumed.operating_bands_dropped(), 0u);
  for (const auto& [load, band] : {std::pair{kLoad, 0}, std::pair{kHighLoad, 1}}) {
    const BlockResult r = RunAtLoad(resumed, healthy, 1, seq, load);
    EXPECT_TRUE(r.score.judged) << load;
    EXPECT_EQ(r.score.operating_band, band);
    EXPECT_EQ(r.verdict.state, FaultState::kNoFault) << r.verdict.reason.view();
  }

  // A configuration with one band keeps the band in use and counts the other.
  BlockProcessor one = Processor(1);
  ASSERT_TRUE(one.ImportLearnedState(saved).ok());
  EXPECT_EQ(one.operating_bands_dropped(), 1u);
  EXPECT_TRUE(RunAtLoad(one, healthy, 1, seq, kHighLoad).score.judged);
  EXPECT_EQ(RunAtLoad(one, healthy, 1, seq, kLoad).score.not_judged,
            NotJudgedCause::kLoadOutside);
}

TEST(OperatingBandsTest, AStateSavedWhileABandLearnedResumesJudgingAtALearnedOne) {
  std::uint64_t seq = 0;
  BlockProcessor p = LearnedAtLoad(2, seq);
  Gearbox healthy(FaultType::kNone, "", 13);
  RunAtLoad(p, healthy, 2, seq, kHighLoad);  // band 1 learning, in use
  const LearnedState saved = ThroughJson(p.ExportLearnedState());
  EXPECT_TRUE(saved.learning);

  // With one band the learned one is kept, not the learning one.
  BlockProcessor one = Processor(1);
  ASSERT_TRUE(one.ImportLearnedState(saved).ok());
  EXPECT_EQ(one.operating_bands_dropped(), 1u);
  const BlockResult r = RunAtLoad(one, healthy, 1, seq, kLoad);
  EXPECT_TRUE(r.score.judged) << r.verdict.reason.view();
  EXPECT_EQ(r.verdict.state, FaultState::kNoFault);

  // With two, the learning band goes on from its two blocks.
  BlockProcessor two = Processor(2);
  ASSERT_TRUE(two.ImportLearnedState(saved).ok());
  EXPECT_EQ(RunAtLoad(two, healthy, 1, seq, kHighLoad).score.baseline_blocks_learned, 3);
}

TEST(OperatingBandsTest, AStateWithAMalformedBandIsRefusedAndNamesIt) {
  std::uint64_t seq = 0;
  BlockProcessor p = LearnedAtLoad(2, seq);
  Gearbox healthy(FaultType::kNone, "", 13);
  RunAtLoad(p, healthy, kBaselineBlocks + 1, seq, kHighLoad);
  LearnedState saved = p.ExportLearnedState();
  saved.parked_bands[0].baseline_load_lo = 300.0;  // above its high end
  BlockProcessor resumed = Processor(2);
  const Status st = resumed.ImportLearnedState(saved);
  ASSERT_FALSE(st.ok());
  EXPECT_TRUE(Contains(st.error(), "operating band 0: baseline load range 300-100"))
      << st.error();
}

TEST(OperatingBandsTest, ACountOutsideOneToSixteenIsRefused) {
  for (const int bands : {0, kMaxOperatingBands + 1}) {
    MachineSetup setup = MakeSetup(Table1Machine());
    setup.options.operating_bands = bands;
    const auto p = BlockProcessor::Create(setup);
    ASSERT_FALSE(p.ok());
    EXPECT_TRUE(Contains(p.error(), "options.operating_bands must be in [1, 16], got " +
                                        std::to_string(bands)))
        << p.error();
  }
}

}  // namespace
}  // namespace gearpath
