#include "core/io/recording.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <bit>
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>

#include "core/io/npy.h"
#include "tests/core/io/io_test_util.h"

namespace gearpath {
namespace {

namespace fs = std::filesystem;

class RecordingTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("gearpath_recording_test_" + std::to_string(getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  // Three blocks, two channels, five samples each; values that are not round in decimal, the
  // extremes of float, a negative zero and a NaN with a payload, so any text or double detour
  // would show.
  static Recording Sample() {
    Recording r;
    r.layout.machine_id = "gearbox-7";
    r.layout.sample_rate_hz = 25600.0 / 3.0;
    r.layout.channels = {{"A1", Axis::kX, "m/s^2", 100.3}, {"A2", Axis::kZ, "g", 0.1}};
    r.layout.samples_per_channel = 5;
    r.blocks = {{18446744073709551615ull - 2, -5, 0.1, SpeedSource::kAcquisition},
                {18446744073709551615ull - 1, 1700000000123456789, 25.000000000000004,
                 SpeedSource::kConfiguration},
                {18446744073709551615ull, 1700000000123456790, 0.0, SpeedSource::kUnknown}};
    for (int i = 0; i < 30; ++i) r.samples.push_back(static_cast<float>(i) / 7.0f - 1.3f);
    r.samples[3] = std::numeric_limits<float>::max();
    r.samples[4] = std::numeric_limits<float>::denorm_min();
    r.samples[5] = -0.0f;
    r.samples[6] = std::bit_cast<float>(0x7fc01234u);
    return r;
  }

  fs::path dir_;
};

TEST_F(RecordingTest, RoundTripsEveryBlockBitForBit) {
  const Recording in = Sample();
  ASSERT_TRUE(WriteRecording(in, dir_).ok());
  Result<Recording> out = ReadRecording(dir_);
  ASSERT_TRUE(out.ok()) << out.error();
  EXPECT_EQ(out->layout.machine_id, in.layout.machine_id);
  EXPECT_EQ(std::bit_cast<std::uint64_t>(out->layout.sample_rate_hz),
            std::bit_cast<std::uint64_t>(in.layout.sample_rate_hz));
  ASSERT_EQ(out->layout.channels.size(), 2u);
  EXPECT_EQ(out->layout.channels[1].sensor, "A2");
  EXPECT_EQ(out->layout.channels[1].axis, Axis::kZ);
  EXPECT_EQ(out->layout.channels[1].unit, "g");
  EXPECT_EQ(out->layout.channels[0].sensitivity, 100.3);
  ASSERT_EQ(out->block_count(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(out->blocks[i].sequence, in.blocks[i].sequence);
    EXPECT_EQ(out->blocks[i].t0_ns, in.blocks[i].t0_ns);
    EXPECT_EQ(std::bit_cast<std::uint64_t>(out->blocks[i].speed_hz),
              std::bit_cast<std::uint64_t>(in.blocks[i].speed_hz));
    EXPECT_EQ(out->blocks[i].speed_source, in.blocks[i].speed_source);
  }
  ASSERT_EQ(out->samples.size(), in.samples.size());
  EXPECT_TRUE(SameBytes(out->samples.data(), in.samples.data(), in.samples.size() * 4));
}

TEST_F(RecordingTest, BlockViewIsThePlanarSliceOfItsBlock) {
  const Recording r = Sample();
  const AccelBlockView v = r.block(1);
  EXPECT_EQ(v.sequence, r.blocks[1].sequence);
  // Block 1, channel 1, sample 2 is element [1][1][2] of the C-order array.
  EXPECT_EQ(v.channel(1)[2], r.samples[1 * 10 + 1 * 5 + 2]);
}

TEST_F(RecordingTest, SamplesFileIsAStandardNpyArrayOfBlocksChannelsSamples) {
  const Recording in = Sample();
  ASSERT_TRUE(WriteRecording(in, dir_).ok());
  Result<NpyHeader> header = ReadNpyHeader(dir_ / "samples.npy");
  ASSERT_TRUE(header.ok()) << header.error();
  EXPECT_EQ(header->descr, "<f4");
  EXPECT_FALSE(header->fortran_order);
  EXPECT_EQ(header->shape, (std::vector<std::size_t>{3, 2, 5}));
  EXPECT_EQ(header->data_offset % 64, 0u);
  const std::string bytes = ReadFileBytes(dir_ / "samples.npy");
  ASSERT_EQ(bytes.size(), header->data_offset + in.samples.size() * 4);
  EXPECT_TRUE(
      SameBytes(bytes.data() + header->data_offset, in.samples.data(), in.samples.size() * 4));
}

TEST_F(RecordingTest, StreamingWriterRefusesABlockOfAnotherLayout) {
  Recording r = Sample();
  auto writer = RecordingWriter::Open(dir_, r.layout);
  ASSERT_TRUE(writer.ok()) << writer.error();
  ASSERT_TRUE((*writer)->Append(r.block(0)).ok());
  AccelBlockView other = r.block(1);
  other.samples_per_channel = 4;
  Status st = (*writer)->Append(other);
  ASSERT_FALSE(st.ok());
  EXPECT_TRUE(Contains(st.error(), "samples_per_channel 4 differs"));
  AccelBlockView foreign = r.block(1);
  foreign.machine_id = "gearbox-8";
  st = (*writer)->Append(foreign);
  ASSERT_FALSE(st.ok());
  EXPECT_TRUE(Contains(st.error(), "machine_id \"gearbox-8\" differs"));
  ASSERT_TRUE((*writer)->Close().ok());
  Result<Recording> out = ReadRecording(dir_);
  ASSERT_TRUE(out.ok()) << out.error();
  EXPECT_EQ(out->block_count(), 1u);
}

TEST_F(RecordingTest, EmptyRecordingReadsBackWithNoBlocks) {
  Recording r = Sample();
  r.blocks.clear();
  r.samples.clear();
  ASSERT_TRUE(WriteRecording(r, dir_).ok());
  Result<Recording> out = ReadRecording(dir_);
  ASSERT_TRUE(out.ok()) << out.error();
  EXPECT_EQ(out->block_count(), 0u);
}

TEST_F(RecordingTest, RefusesToOverwriteAnExistingRecording) {
  ASSERT_TRUE(WriteRecording(Sample(), dir_).ok());
  Status st = WriteRecording(Sample(), dir_);
  ASSERT_FALSE(st.ok());
  EXPECT_TRUE(Contains(st.error(), "already holds a recording"));
}

TEST_F(RecordingTest, RefusesANonUtf8ChannelNameBeforeWritingAnyFile) {
  Recording r = Sample();
  r.layout.channels[1].sensor = "A\xE9";  // Latin-1 "Aé"
  Status st = WriteRecording(r, dir_);
  ASSERT_FALSE(st.ok());
  EXPECT_EQ(st.error(),
            "recording layout: channels[1].sensor is not UTF-8: incomplete UTF-8 string; last "
            "byte: 0xE9");
  EXPECT_FALSE(fs::exists(dir_));  // nothing half-written
}

TEST_F(RecordingTest, RejectsAManifestWithAnOverflowingNumberOrDeepNesting) {
  ASSERT_TRUE(WriteRecording(Sample(), dir_).ok());
  std::string text = ReadFileBytes(dir_ / "manifest.json");
  const auto at = text.find("\"sample_rate_hz\":");
  ASSERT_NE(at, std::string::npos);
  WriteFileBytes(dir_ / "manifest.json",
                 text.substr(0, at) + "\"sample_rate_hz\": 1e999, \"x\":" + text.substr(at + 17));
  Result<Recording> r = ReadRecording(dir_);
  ASSERT_FALSE(r.ok());
  EXPECT_TRUE(Contains(r.error(), "manifest.json: not valid JSON: line "));
  EXPECT_TRUE(Contains(r.error(), "number overflow parsing '1e999'"));
  EXPECT_FALSE(IsRecordingDirectory(dir_));

  WriteFileBytes(dir_ / "manifest.json",
                 "{\"format\": \"gearpath-recording\", \"x\": " + std::string(100'000, '[') + "}");
  r = ReadRecording(dir_);
  ASSERT_FALSE(r.ok());
  EXPECT_TRUE(Contains(r.error(), "nested deeper than 64 levels"));
  EXPECT_FALSE(IsRecordingDirectory(dir_));
}

TEST_F(RecordingTest, RejectsADirectoryWithoutManifest) {
  fs::create_directories(dir_);
  Result<Recording> r = ReadRecording(dir_);
  ASSERT_FALSE(r.ok());
  EXPECT_TRUE(Contains(r.error(), "missing manifest"));
  EXPECT_FALSE(IsRecordingDirectory(dir_));
}

TEST_F(RecordingTest, RejectsAnotherFormatByName) {
  fs::create_directories(dir_);
  WriteFileBytes(dir_ / "manifest.json", R"({"format": "gearpath-frf-set", "format_version": 1})");
  Result<Recording> r = ReadRecording(dir_);
  ASSERT_FALSE(r.ok());
  EXPECT_TRUE(
      Contains(r.error(), "format: expected \"gearpath-recording\", got \"gearpath-frf-set\""));
}

TEST_F(RecordingTest, RejectsSamplesWhoseShapeDisagreesWithTheManifest) {
  ASSERT_TRUE(WriteRecording(Sample(), dir_).ok());
  std::vector<float> wrong(2 * 2 * 5, 0.0f);
  ASSERT_TRUE(WriteNpy<float>(dir_ / "samples.npy", wrong, {2, 2, 5}).ok());
  Result<Recording> r = ReadRecording(dir_);
  ASSERT_FALSE(r.ok());
  EXPECT_TRUE(
      Contains(r.error(), "shape (2, 2, 5) does not match the manifest: expected (3, 2, 5)"));
}

TEST_F(RecordingTest, RejectsPerBlockListsOfTheWrongLengthNamingTheKey) {
  ASSERT_TRUE(WriteRecording(Sample(), dir_).ok());
  auto m = nlohmann::json::parse(ReadFileBytes(dir_ / "manifest.json"));
  m["blocks"]["t0_ns"].erase(0);
  WriteFileBytes(dir_ / "manifest.json", m.dump());
  Result<Recording> r = ReadRecording(dir_);
  ASSERT_FALSE(r.ok());
  EXPECT_TRUE(Contains(r.error(), "blocks.t0_ns has 2 entries but blocks.count is 3"));
}

TEST_F(RecordingTest, RejectsAnUnknownAxisNamingTheChannel) {
  ASSERT_TRUE(WriteRecording(Sample(), dir_).ok());
  auto m = nlohmann::json::parse(ReadFileBytes(dir_ / "manifest.json"));
  m["channels"][1]["axis"] = "w";
  WriteFileBytes(dir_ / "manifest.json", m.dump());
  Result<Recording> r = ReadRecording(dir_);
  ASSERT_FALSE(r.ok());
  EXPECT_TRUE(Contains(r.error(), "channels[1].axis"));
}

// Blocks that came with their load (AccelBlockV2): version 2 keeps the unit and every load,
// a NaN included (stored as null, as the speed's), and the block view carries it to replay.
TEST_F(RecordingTest, KeepsEachBlocksLoadAndItsUnitAsVersion2) {
  Recording in = Sample();
  in.layout.load_unit = "N m";
  in.blocks[0].load = 1234.5678901234567;
  in.blocks[1].load = std::numeric_limits<double>::quiet_NaN();
  in.blocks[2].load = 0.0;
  ASSERT_TRUE(in.carries_load());
  ASSERT_TRUE(WriteRecording(in, dir_).ok());
  const auto m = nlohmann::json::parse(ReadFileBytes(dir_ / "manifest.json"));
  EXPECT_EQ(m["format_version"], 2);
  EXPECT_EQ(m["load_unit"], "N m");
  EXPECT_EQ(m["blocks"]["load"], nlohmann::json::parse("[1234.5678901234567, null, 0.0]"));
  Result<Recording> out = ReadRecording(dir_);
  ASSERT_TRUE(out.ok()) << out.error();
  EXPECT_EQ(out->layout.load_unit, "N m");
  EXPECT_EQ(std::bit_cast<std::uint64_t>(out->blocks[0].load),
            std::bit_cast<std::uint64_t>(in.blocks[0].load));
  EXPECT_TRUE(std::isnan(out->blocks[1].load));
  EXPECT_EQ(out->blocks[2].load, 0.0);
  EXPECT_EQ(out->block(0).load, in.blocks[0].load);
  EXPECT_TRUE(out->carries_load());
}

// Without a load the manifest is the version-1 one, byte for byte what earlier builds wrote, so
// that they keep reading what this build records from plain AccelBlocks.
TEST_F(RecordingTest, BlocksWithoutALoadStayVersion1) {
  ASSERT_FALSE(Sample().carries_load());
  ASSERT_TRUE(WriteRecording(Sample(), dir_).ok());
  const auto m = nlohmann::json::parse(ReadFileBytes(dir_ / "manifest.json"));
  EXPECT_EQ(m["format_version"], 1);
  EXPECT_FALSE(m.contains("load_unit"));
  EXPECT_FALSE(m["blocks"].contains("load"));
  Result<Recording> out = ReadRecording(dir_);
  ASSERT_TRUE(out.ok()) << out.error();
  EXPECT_FALSE(out->carries_load());
  EXPECT_EQ(out->block(2).load, 0.0);
}

// A load without a unit (what `gearpath evaluate` feeds) is still a load: kept, as version 2.
TEST_F(RecordingTest, ALoadWithoutAUnitIsKept) {
  Recording in = Sample();
  in.blocks[1].load = 1.1;
  ASSERT_TRUE(WriteRecording(in, dir_).ok());
  Result<Recording> out = ReadRecording(dir_);
  ASSERT_TRUE(out.ok()) << out.error();
  EXPECT_EQ(out->layout.load_unit, "");
  EXPECT_EQ(out->blocks[1].load, 1.1);
  EXPECT_TRUE(out->carries_load());
}

TEST_F(RecordingTest, RejectsAVersion2ManifestWithABadLoadNamingTheKey) {
  Recording in = Sample();
  in.layout.load_unit = "kW";
  in.blocks[0].load = 7.0;
  ASSERT_TRUE(WriteRecording(in, dir_).ok());
  const auto good = nlohmann::json::parse(ReadFileBytes(dir_ / "manifest.json"));
  auto refused = [&](nlohmann::json m, const std::string& why) {
    WriteFileBytes(dir_ / "manifest.json", m.dump());
    Result<Recording> r = ReadRecording(dir_);
    ASSERT_FALSE(r.ok()) << why;
    EXPECT_TRUE(Contains(r.error(), why)) << r.error();
  };
  auto m = good;
  m["blocks"]["load"][2] = "heavy";
  refused(m, "blocks.load[2] is not a number");
  m = good;
  m["blocks"]["load"].erase(0);
  refused(m, "blocks.load has 2 entries but blocks.count is 3");
  m = good;
  m["blocks"].erase("load");
  refused(m, "missing key \"blocks.load\"");
  m = good;
  m.erase("load_unit");
  refused(m, "missing key \"load_unit\"");
  m = good;
  m["format_version"] = 3;
  refused(m, "format_version 3 is not supported (this build reads 1 to 2)");
}

TEST_F(RecordingTest, RefusesANonUtf8LoadUnitBeforeWritingAnyFile) {
  Recording r = Sample();
  r.layout.load_unit = "N\xB7m";  // Latin-1 middle dot
  Status st = WriteRecording(r, dir_);
  ASSERT_FALSE(st.ok());
  EXPECT_TRUE(Contains(st.error(), "load_unit is not UTF-8")) << st.error();
  EXPECT_FALSE(fs::exists(dir_));
}

}  // namespace
}  // namespace gearpath
