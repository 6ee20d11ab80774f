// gearpathd end to end over loopback DDS: the simulated Table-1 gearbox (core/simulation) with a
// fractured tooth on one gear is published block by block; the daemon's result topics must name
// that gear and a bearing of its mesh. The truth is the fault the simulator was given and the
// gear train's topology, never a number computed by the daemon.
#include "tests/integration/gearpathd_fixture.h"

namespace gearpath::testing {
namespace {

constexpr int kBaselineBlocks = 6;

class GearpathdFaultTracing : public GearpathdOverDds {
 protected:
  void Configure(json& config) override {
    config["machines"][0]["analysis"]["baseline"]["learning_blocks"] = kBaselineBlocks;
  }
};

TEST_F(GearpathdFaultTracing, AFracturedToothOnTheInputGearIsTracedToThatGearAndItsMesh) {
  const GearTrain train = GearTrain::Table1();
  const std::string faulty = "G1";
  std::uint64_t seq = 1;
  AccelBlock block;
  GearboxSimulator healthy = Table1Simulator(FaultType::kNone, "", 7);
  for (int i = 0; i < kBaselineBlocks; ++i) {
    healthy.NextBlock(block);
    block.sequence = seq++;
    Publish(block);
  }
  GearboxSimulator broken = Table1Simulator(FaultType::kToothFracture, faulty, 21);
  for (int i = 0; i < 2; ++i) {
    broken.NextBlock(block);
    block.sequence = seq++;
    Publish(block);
  }
  const std::uint64_t last = seq - 1;
  ASSERT_TRUE(WaitStatus([&](const auto& m) { return m.blocks_processed == last; }, 60s))
      << "processed " << last_status_.blocks_processed << ", rejected "
      << last_status_.blocks_rejected << ": " << last_status_.last_rejection_reason;

  auto is_last = [&](const auto& r) { return r.block_sequence == last; };
  auto gear = WaitResult<gearpath_SuspectedGear>(*gear_reader_, is_last, 10s);
  ASSERT_TRUE(gear.has_value());
  SCOPED_TRACE(std::string("verdict: ") + (*gear)->reason);
  EXPECT_NE((*gear)->state, gearpath_NO_FAULT);
  EXPECT_EQ(dds::GetString((*gear)->gear_name), faulty);
  // The shaft the faulty gear sits on, and that shaft's rate at 10 Hz input (Table 6: f1).
  const int shaft = train.ShaftOfGear(faulty);
  EXPECT_EQ(dds::GetString((*gear)->shaft_name), train.shafts[static_cast<std::size_t>(shaft)].name);
  EXPECT_NEAR((*gear)->characteristic_frequency_hz, 10.0, 0.01);
  EXPECT_GT((*gear)->confidence, 0.0);

  // The dominant path is a bearing of the faulty gear's mesh (G1-G2: bearings B1 and B2, which
  // carry G1 and G2), since a mesh force loads both shafts of the pair.
  auto dominant = WaitResult<gearpath_DominantPath>(*dominant_reader_, is_last, 10s);
  ASSERT_TRUE(dominant.has_value());
  const std::string path(dds::GetString((*dominant)->path_name));
  EXPECT_TRUE(path == "B1x" || path == "B2x") << "dominant path " << path;

  // The envelope indicators of the input shaft are enhanced by the reconstruction.
  auto indicators = WaitResult<gearpath_EnvelopeIndicators>(*indicators_reader_, is_last, 10s);
  ASSERT_TRUE(indicators.has_value());
  ASSERT_GE((*indicators)->shafts._length, 1u);
  EXPECT_EQ(dds::GetString((*indicators)->shafts._buffer[0].shaft_name), "input");
  EXPECT_NEAR((*indicators)->shafts._buffer[0].characteristic_frequency_hz, 10.0, 0.01);
}

}  // namespace
}  // namespace gearpath::testing
