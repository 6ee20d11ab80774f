// Contract version 4 (idl/gearpath.idl; docs/topics.md, "Version 4: the operating load with the
// block"): AccelBlockV2 is written in XCDR1 like every other type, has the documented name,
// QoS class and key, and a block with its load crosses loopback UDP field by field: the view
// the daemon takes of it (dds::ViewOfWireBlock) is the block that was filled, load included.
#include <dds/dds.h>
#include <gtest/gtest.h>

#include <array>
#include <chrono>
#include <string>
#include <vector>

#include "idl/dds/accel_block_wire.h"
#include "idl/dds/gearpath_topics.h"
#include "tests/idl/loopback_test_domains.h"

namespace gearpath::dds {
namespace {

using std::chrono::seconds;

TEST(ContractV4, TheVersionAndTheNewTopicAreThoseDocumented) {
  EXPECT_EQ(gearpath_CONTRACT_VERSION, 4u);
  EXPECT_EQ(TopicTraits<gearpath_AccelBlockV2>::kName, "gearpath/AccelBlockV2");
  EXPECT_EQ(TopicTraits<gearpath_AccelBlockV2>::kClass, TopicClass::kBlockStream);
  const dds_topic_descriptor_t& d = gearpath_AccelBlockV2_desc;
  ASSERT_EQ(d.m_nkeys, 1u);
  EXPECT_STREQ(d.m_keys[0].m_name, "machine_id");
}

TEST(ContractV4, AccelBlockV2IsWrittenInXcdr1) {
  testing::LoopbackPair pair;
  testing::ExpectWrittenInXcdr1<gearpath_AccelBlockV2>(pair.publisher);
}

TEST(ContractV4, ABlockWithItsLoadArrivesAsItWasFilled) {
  AccelBlock block;
  block.machine_id = "gb7";
  block.sequence = 41;
  block.t0_ns = 1'767'225'600'000'000'000;
  block.sample_rate_hz = 8000.0;
  block.speed_hz = 12.5;
  block.speed_source = SpeedSource::kAcquisition;
  block.load = 1234.5;
  block.channels = {{"A1", Axis::kX, "m/s^2", 100.0}, {"A2", Axis::kZ, "m/s^2", 0.0}};
  block.samples_per_channel = 3;
  block.samples = {1.0f, -2.0f, 3.5f, 0.25f, -0.5f, 7.0f};
  Owned<gearpath_AccelBlockV2> sample;
  ASSERT_TRUE(FillWireBlock(block.view(), "N m", *sample).ok());
  EXPECT_FALSE(FillWireBlock(block.view(), "seventeen chars!!", *sample).ok());  // 17 > 16
  ASSERT_TRUE(FillWireBlock(block.view(), "N m", *sample).ok());

  testing::LoopbackPair pair;
  testing::LoopbackLink<gearpath_AccelBlockV2> link(pair);
  ASSERT_TRUE(link.writer.WaitForReaders(1, seconds(10)));
  ASSERT_TRUE(link.writer.Write(*sample));
  std::vector<Owned<gearpath_AccelBlockV2>> got(1);
  std::vector<SampleInfo> infos(1);
  ASSERT_EQ(testing::TakeWithin(link.reader, link.waitset, got, infos, seconds(10)), 1u);
  ASSERT_TRUE(infos[0].valid_data);
  EXPECT_STREQ(got[0]->load_unit, "N m");
  std::vector<ChannelInfo> channels;
  const AccelBlockView v = ViewOfWireBlock(*got[0], channels);
  EXPECT_EQ(v.machine_id, "gb7");
  EXPECT_EQ(v.sequence, 41u);
  EXPECT_EQ(v.t0_ns, block.t0_ns);
  EXPECT_EQ(v.sample_rate_hz, 8000.0);
  EXPECT_EQ(v.speed_hz, 12.5);
  EXPECT_EQ(v.speed_source, SpeedSource::kAcquisition);
  EXPECT_EQ(v.load, 1234.5);
  ASSERT_EQ(v.channels.size(), 2u);
  EXPECT_EQ(v.channels[1].sensor, "A2");
  EXPECT_EQ(v.channels[1].axis, Axis::kZ);
  EXPECT_EQ(v.samples_per_channel, 3u);
  EXPECT_EQ(std::vector<float>(v.samples.begin(), v.samples.end()), block.samples);
}

}  // namespace
}  // namespace gearpath::dds
