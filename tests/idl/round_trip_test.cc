// An AccelBlock published on one domain arrives bit-exact on the other, over loopback UDP.
#include <gtest/gtest.h>

#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <vector>

#include "idl/dds/gearpath_topics.h"
#include "tests/core/io/io_test_util.h"
#include "tests/idl/loopback_test_domains.h"

namespace gearpath::dds {
namespace {

using std::chrono::seconds;

constexpr std::uint32_t kChannels = 8;
constexpr std::uint32_t kSamplesPerChannel = 4096;

// Values that a lossy path would alter: full-mantissa fractions, tiny and huge magnitudes,
// negative zero, subnormals, infinities.
float TestSample(std::uint32_t channel, std::uint32_t n) {
  switch ((n + channel) % 7) {
    case 0:
      return std::sin(0.001F * static_cast<float>(n * (channel + 1))) / 3.0F;
    case 1:
      return -0.0F;
    case 2:
      return std::numeric_limits<float>::denorm_min() * static_cast<float>(n % 97 + 1);
    case 3:
      return std::numeric_limits<float>::max() / static_cast<float>(channel + 1);
    case 4:
      return -std::numeric_limits<float>::infinity();
    case 5:
      return 1.0F + std::numeric_limits<float>::epsilon() * static_cast<float>(n % 13);
    default:
      return static_cast<float>(n) * 1e-7F - static_cast<float>(channel);
  }
}

void FillBlock(gearpath_AccelBlock& block) {
  ASSERT_TRUE(SetString(block.machine_id, "gearbox-7"));
  block.sequence_number = 0xFEDCBA9876543210ULL;
  block.t0_ns = 1'763'769'600'123'456'789LL;
  block.sample_rate_hz = 25600.0;
  block.speed_hz = 24.75;
  block.speed_source = gearpath_SPEED_ACQUISITION_TACHOMETER;
  ASSERT_TRUE(Resize(block.channels, kChannels));
  std::uint32_t c = 0;
  for (gearpath_ChannelInfo& channel : MutableView(block.channels)) {
    ASSERT_TRUE(SetString(channel.sensor_id, "A" + std::to_string(c / 3 + 1)));
    channel.axis = static_cast<gearpath_Axis>(c % 3);
    ASSERT_TRUE(SetString(channel.unit, "m/s^2"));
    channel.sensitivity_mv_per_unit = 10.2 + 0.01 * c;
    ++c;
  }
  block.samples_per_channel = kSamplesPerChannel;
  ASSERT_TRUE(Resize(block.samples, kChannels * kSamplesPerChannel));
  std::span<float> samples = MutableView(block.samples);
  for (std::uint32_t ch = 0; ch < kChannels; ++ch) {
    for (std::uint32_t n = 0; n < kSamplesPerChannel; ++n) {
      samples[ch * kSamplesPerChannel + n] = TestSample(ch, n);  // planar layout
    }
  }
}

TEST(RoundTrip, AccelBlockWithEightChannelsOf4096SamplesArrivesBitExact) {
  testing::LoopbackPair pair;
  testing::LoopbackLink<gearpath_AccelBlock> link(pair);
  Writer<gearpath_AccelBlock>& writer = link.writer;
  Reader<gearpath_AccelBlock>& reader = link.reader;
  WaitSet& waitset = link.waitset;
  ASSERT_TRUE(writer.WaitForReaders(1, seconds(10)));

  Owned<gearpath_AccelBlock> sent;
  FillBlock(*sent);
  ASSERT_TRUE(writer.Write(*sent));

  std::vector<Owned<gearpath_AccelBlock>> received(4);
  std::vector<SampleInfo> infos(4);
  ASSERT_EQ(testing::TakeWithin(reader, waitset, received, infos, seconds(10)), 1U);
  ASSERT_TRUE(infos[0].valid_data);
  EXPECT_EQ(infos[0].instance_state, DDS_IST_ALIVE);

  const gearpath_AccelBlock& got = *received[0];
  EXPECT_EQ(GetString(got.machine_id), "gearbox-7");
  EXPECT_EQ(got.sequence_number, sent->sequence_number);
  EXPECT_EQ(got.t0_ns, sent->t0_ns);
  EXPECT_EQ(got.sample_rate_hz, sent->sample_rate_hz);
  EXPECT_EQ(got.speed_hz, sent->speed_hz);
  EXPECT_EQ(got.speed_source, gearpath_SPEED_ACQUISITION_TACHOMETER);
  ASSERT_EQ(got.channels._length, kChannels);
  for (std::uint32_t ch = 0; ch < kChannels; ++ch) {
    const gearpath_ChannelInfo& a = View(sent->channels)[ch];
    const gearpath_ChannelInfo& b = View(got.channels)[ch];
    EXPECT_EQ(GetString(b.sensor_id), GetString(a.sensor_id));
    EXPECT_EQ(b.axis, a.axis);
    EXPECT_EQ(GetString(b.unit), "m/s^2");
    EXPECT_EQ(b.sensitivity_mv_per_unit, a.sensitivity_mv_per_unit);
  }
  EXPECT_EQ(got.samples_per_channel, kSamplesPerChannel);
  ASSERT_EQ(got.samples._length, kChannels * kSamplesPerChannel);
  // Bit-exact: compare the bytes, so -0.0 vs 0.0 or a changed NaN payload would fail too.
  // SameBytes also takes an empty sequence, whose _buffer may be null (memcmp's may not be).
  EXPECT_TRUE(gearpath::SameBytes(got.samples._buffer, sent->samples._buffer,
                                  std::size_t{kChannels} * kSamplesPerChannel * sizeof(float)));
}

// Take deserialises into the caller's samples and reuses their sequence buffers, so a reader
// that takes into the same vector block after block stops allocating for samples.
TEST(RoundTrip, TakingIntoTheSameSampleAgainReusesItsSampleBuffer) {
  testing::LoopbackPair pair;
  testing::LoopbackLink<gearpath_AccelBlock> link(pair);
  Writer<gearpath_AccelBlock>& writer = link.writer;
  Reader<gearpath_AccelBlock>& reader = link.reader;
  WaitSet& waitset = link.waitset;
  ASSERT_TRUE(writer.WaitForReaders(1, seconds(10)));

  std::vector<Owned<gearpath_AccelBlock>> received(1);
  std::vector<SampleInfo> infos(1);
  auto take_one = [&]() -> std::size_t {
    const auto deadline = std::chrono::steady_clock::now() + seconds(10);
    while (std::chrono::steady_clock::now() < deadline) {
      std::array<dds_attach_t, 1> triggered{};
      if (!waitset.Wait(triggered, seconds(1))) return 0;
      Result<std::size_t> n = reader.Take(received, infos);
      if (!n) return 0;
      if (*n > 0) return *n;
    }
    return 0;
  };

  Owned<gearpath_AccelBlock> sent;
  FillBlock(*sent);
  ASSERT_TRUE(writer.Write(*sent));
  ASSERT_EQ(take_one(), 1U);
  const float* const buffer = received[0]->samples._buffer;

  sent->sequence_number += 1;
  MutableView(sent->samples)[5] = 42.0F;
  ASSERT_TRUE(writer.Write(*sent));
  ASSERT_EQ(take_one(), 1U);
  EXPECT_EQ(received[0]->samples._buffer, buffer);
  EXPECT_EQ(received[0]->sequence_number, sent->sequence_number);
  EXPECT_EQ(View(received[0]->samples)[5], 42.0F);
}

TEST(RoundTrip, WritingMoreChannelsThanTheIdlBoundFailsNamingDdsWrite) {
  testing::LoopbackPair pair;
  Topic<gearpath_AccelBlock> topic(pair.publisher);
  Writer<gearpath_AccelBlock> writer(topic);
  Owned<gearpath_AccelBlock> block;
  ASSERT_TRUE(SetString(block->machine_id, "gearbox-7"));
  ASSERT_TRUE(Resize(block->channels, gearpath_MAX_CHANNELS + 1));
  const Status status = writer.Write(*block);
  ASSERT_FALSE(status);
  EXPECT_NE(status.error().find("dds_write(\"gearpath/AccelBlock\")"), std::string::npos)
      << status.error();
}

}  // namespace
}  // namespace gearpath::dds
