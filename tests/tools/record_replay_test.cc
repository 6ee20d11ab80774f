// `gearpath record` and `gearpath replay`, end to end over loopback DDS and on files.
#include <gtest/gtest.h>
#include <unistd.h>

#include <bit>
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <random>
#include <type_traits>

#include "core/io/npy.h"
#include "core/io/recording.h"
#include "core/io/uff58.h"
#include "idl/dds/accel_block_wire.h"
#include "idl/dds/gearpath_topics.h"
#include "tests/core/io/io_test_util.h"
#include "tests/tools/tool_process.h"

namespace gearpath::tools {
namespace {

namespace fs = std::filesystem;
using testing::ReadText;
using testing::RunTool;
using testing::TestDomainId;
using testing::ToolProcess;

class RecordReplay : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("gearpath_tools_test_" + std::to_string(getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    if (!HasFailure()) fs::remove_all(dir_);
  }

  // Blocks of two machines with awkward float values, 64-bit extremes and every speed source
  // the wire can carry.
  static std::vector<AccelBlock> MakeBlocks(std::size_t per_machine) {
    std::mt19937 rng(1234);
    std::normal_distribution<float> noise(0.0f, 3.0f);
    std::vector<AccelBlock> blocks;
    const SpeedSource sources[] = {SpeedSource::kAcquisition, SpeedSource::kConfiguration,
                                   SpeedSource::kUnknown};
    for (std::size_t i = 0; i < per_machine; ++i) {
      for (int m = 0; m < 2; ++m) {
        AccelBlock b;
        b.machine_id = m == 0 ? "gearbox-1" : "line 2/gearbox";
        b.sequence = (m == 0 ? 18446744073709551000ull : 7ull) + i;
        b.sample_rate_hz = m == 0 ? 25600.0 : 10000.0 / 3.0;
        b.t0_ns = 1700000000000000000ll + static_cast<std::int64_t>(i) * 160000000ll + m;
        b.speed_hz = 24.7 + 0.001 * static_cast<double>(i) / 3.0;
        b.speed_source = sources[i % 3];
        b.channels = {{"A1", Axis::kX, "m/s^2", 100.3},
                      {"A1", Axis::kY, "m/s^2", 99.7},
                      {"A2", Axis::kZ, "g", 0.0}};
        b.samples_per_channel = m == 0 ? 256 : 100;
        for (std::size_t k = 0; k < b.channels.size() * b.samples_per_channel; ++k) {
          b.samples.push_back(noise(rng));
        }
        b.samples[1] = -0.0f;
        b.samples[2] = std::numeric_limits<float>::denorm_min();
        blocks.push_back(std::move(b));
      }
    }
    return blocks;
  }

  static void ExpectSameBlock(const AccelBlockView& a, const AccelBlockView& b) {
    EXPECT_EQ(a.machine_id, b.machine_id);
    EXPECT_EQ(a.sequence, b.sequence);
    EXPECT_EQ(a.t0_ns, b.t0_ns);
    EXPECT_EQ(std::bit_cast<std::uint64_t>(a.sample_rate_hz),
              std::bit_cast<std::uint64_t>(b.sample_rate_hz));
    EXPECT_EQ(std::bit_cast<std::uint64_t>(a.speed_hz), std::bit_cast<std::uint64_t>(b.speed_hz));
    EXPECT_EQ(a.speed_source, b.speed_source);
    ASSERT_EQ(a.channels.size(), b.channels.size());
    for (std::size_t c = 0; c < a.channels.size(); ++c) {
      EXPECT_EQ(a.channels[c].sensor, b.channels[c].sensor);
      EXPECT_EQ(a.channels[c].axis, b.channels[c].axis);
      EXPECT_EQ(a.channels[c].unit, b.channels[c].unit);
      EXPECT_EQ(std::bit_cast<std::uint64_t>(a.channels[c].sensitivity),
                std::bit_cast<std::uint64_t>(b.channels[c].sensitivity));
    }
    ASSERT_EQ(a.samples_per_channel, b.samples_per_channel);
    ASSERT_EQ(a.samples.size(), b.samples.size());
    // SameBytes also takes a block without samples, whose data() is null (memcmp's may not be).
    EXPECT_TRUE(SameBytes(a.samples.data(), b.samples.data(), a.samples.size_bytes()));
  }

  std::string Domain() const { return std::to_string(TestDomainId()); }

  // Replays the recordings under rec1 (`blocks` in all) while recording them into rec2, and
  // expects the same files in each of `recordings`: what replay sends is what was recorded.
  void ExpectReplayRecordsTheSame(std::initializer_list<const char*> recordings,
                                  std::size_t blocks) {
    ToolProcess rec2({"record", "--domain", Domain(), "--out", (dir_ / "rec2").string(), "--count",
                      std::to_string(blocks)},
                     dir_, "rec2");
    ASSERT_TRUE(rec2.WaitForStderr("subscribed", std::chrono::seconds(10))) << rec2.Err();
    std::string out, err;
    ASSERT_EQ(RunTool({"replay", (dir_ / "rec1").string(), "--fast", "--domain", Domain()}, dir_,
                      "replay", &out, &err),
              0)
        << err;
    EXPECT_NE(out.find("sent " + std::to_string(blocks) + " blocks"), std::string::npos) << out;
    ASSERT_EQ(rec2.Wait(std::chrono::seconds(15)), 0) << rec2.Err();
    for (const char* m : recordings) {
      EXPECT_EQ(ReadText(dir_ / "rec1" / m / "samples.npy"),
                ReadText(dir_ / "rec2" / m / "samples.npy"))
          << m;
      EXPECT_EQ(ReadText(dir_ / "rec1" / m / "manifest.json"),
                ReadText(dir_ / "rec2" / m / "manifest.json"))
          << m;
    }
  }

  fs::path dir_;
};

// Publishes `blocks` from this process on the test domain, reliably, waiting for one reader:
// as AccelBlocks, or with `load_unit` as AccelBlockV2s carrying their load.
void PublishFromTest(const std::vector<AccelBlock>& blocks,
                     std::optional<std::string> load_unit = std::nullopt) {
  dds::Domain domain(TestDomainId(), testing::TestDomainConfig(), dds::EnvironmentConfig::kIgnore);
  dds::Participant participant(domain);
  auto publish = [&](auto wire) {
    using Wire = decltype(wire);
    dds::Topic<Wire> topic(participant);
    dds::Writer<Wire> writer(topic);
    ASSERT_TRUE(writer.WaitForReaders(1, std::chrono::seconds(10)).ok());
    dds::Owned<Wire> sample;
    for (const AccelBlock& b : blocks) {
      if constexpr (std::is_same_v<Wire, gearpath_AccelBlockV2>) {
        ASSERT_TRUE(dds::FillWireBlock(b.view(), *load_unit, *sample).ok());
      } else {
        ASSERT_TRUE(dds::FillWireBlock(b.view(), *sample).ok());
      }
      ASSERT_TRUE(writer.Write(*sample).ok());
    }
    ASSERT_GE(dds_wait_for_acks(writer.handle(), DDS_SECS(10)), 0);
  };
  if (load_unit) {
    publish(gearpath_AccelBlockV2{});
  } else {
    publish(gearpath_AccelBlock{});
  }
}

TEST_F(RecordReplay, RecordThenReplayReproducesEveryBlockBitForBit) {
  const std::vector<AccelBlock> sent = MakeBlocks(5);
  // 1. Record what this test publishes.
  ToolProcess rec1(
      {"record", "--domain", Domain(), "--out", (dir_ / "rec1").string(), "--count", "10"}, dir_,
      "rec1");
  ASSERT_TRUE(rec1.WaitForStderr("subscribed", std::chrono::seconds(10))) << rec1.Err();
  PublishFromTest(sent);
  ASSERT_EQ(rec1.Wait(std::chrono::seconds(15)), 0) << rec1.Err();

  const fs::path m1 = dir_ / "rec1" / "gearbox-1";
  const fs::path m2 = dir_ / "rec1" / "line_2_gearbox";  // id sanitised into a directory name
  Result<Recording> r1 = ReadRecording(m1);
  Result<Recording> r2 = ReadRecording(m2);
  ASSERT_TRUE(r1.ok()) << r1.error();
  ASSERT_TRUE(r2.ok()) << r2.error();
  ASSERT_EQ(r1->block_count(), 5u);
  ASSERT_EQ(r2->block_count(), 5u);
  for (std::size_t i = 0; i < 5; ++i) {
    ExpectSameBlock(r1->block(i), sent[2 * i].view());
    ExpectSameBlock(r2->block(i), sent[2 * i + 1].view());
  }

  // 2. Replay the recording (both machines) and record it again: same bytes on disk.
  ExpectReplayRecordsTheSame({"gearbox-1", "line_2_gearbox"}, 10);
}

// Blocks that came with their load (AccelBlockV2) keep it through record and replay: one
// machine sends plain AccelBlocks and then switches to AccelBlockV2 (a new part, since the
// unit is part of the layout), the other sends AccelBlockV2 only. Replaying the recordings
// publishes each on its own topic again, and recording that gives the same files.
TEST_F(RecordReplay, RecordAndReplayKeepEachBlocksLoad) {
  std::vector<AccelBlock> blocks = MakeBlocks(4);
  std::vector<AccelBlock> plain, first_loaded, second_loaded;
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    AccelBlock& b = blocks[i];
    const bool machine1 = i % 2 == 0;
    b.load = machine1 ? 0.0 : 1000.0 / 3.0 + static_cast<double>(i);
    if (machine1 && i < 4) {
      plain.push_back(b);
    } else if (machine1) {
      b.load = 55.5 + static_cast<double>(i);
      second_loaded.push_back(b);
    } else {
      first_loaded.push_back(b);
    }
  }
  ToolProcess rec1(
      {"record", "--domain", Domain(), "--out", (dir_ / "rec1").string(), "--count", "8"}, dir_,
      "rec1");
  ASSERT_TRUE(rec1.WaitForStderr("subscribed", std::chrono::seconds(10))) << rec1.Err();
  // Each call waits for its blocks to be acknowledged: machine 1's plain blocks are in the
  // recorder before its loaded ones are written.
  PublishFromTest(plain);
  PublishFromTest(first_loaded, "kW");
  PublishFromTest(second_loaded, "N m");
  ASSERT_EQ(rec1.Wait(std::chrono::seconds(15)), 0) << rec1.Err();
  EXPECT_NE(rec1.Err().find("gearbox-1: block 18446744073709551002 changes the layout (channels, "
                            "rate, length or load unit); starting part 2"),
            std::string::npos)
      << rec1.Err();

  Result<Recording> before = ReadRecording(dir_ / "rec1" / "gearbox-1");
  Result<Recording> after = ReadRecording(dir_ / "rec1" / "gearbox-1.part2");
  Result<Recording> other = ReadRecording(dir_ / "rec1" / "line_2_gearbox");
  ASSERT_TRUE(before.ok()) << before.error();
  ASSERT_TRUE(after.ok()) << after.error();
  ASSERT_TRUE(other.ok()) << other.error();
  EXPECT_FALSE(before->carries_load());
  EXPECT_EQ(nlohmann::json::parse(
                ReadText(dir_ / "rec1" / "gearbox-1" / "manifest.json"))["format_version"],
            1);
  ASSERT_EQ(after->block_count(), 2u);
  EXPECT_EQ(after->layout.load_unit, "N m");
  ASSERT_EQ(other->block_count(), 4u);
  EXPECT_EQ(other->layout.load_unit, "kW");
  for (std::size_t i = 0; i < 2; ++i) {
    ExpectSameBlock(after->block(i), second_loaded[i].view());
    EXPECT_EQ(after->blocks[i].load, second_loaded[i].load);
  }
  for (std::size_t i = 0; i < 4; ++i) {
    ExpectSameBlock(other->block(i), first_loaded[i].view());
    EXPECT_EQ(std::bit_cast<std::uint64_t>(other->blocks[i].load),
              std::bit_cast<std::uint64_t>(first_loaded[i].load));
  }

  ExpectReplayRecordsTheSame({"gearbox-1", "gearbox-1.part2", "line_2_gearbox"}, 8);
}

// A text export has no load column: --load sends one with every block, in --load-unit.
TEST_F(RecordReplay, ReplayGivesAContinuousInputTheLoadItIsToldOf) {
  std::ofstream(dir_ / "export.txt") << "Sample rate: 100 Hz\nA1-X\nm/s^2\n1\n2\n3\n4\n";
  std::string out, err;
  ASSERT_EQ(RunTool({"replay", (dir_ / "export.txt").string(), "--block-length", "2", "--load",
                     "72.5", "--load-unit", "%", "--write-recording", (dir_ / "rec").string()},
                    dir_, "replay", &out, &err),
            0)
      << err;
  Result<Recording> r = ReadRecording(dir_ / "rec");
  ASSERT_TRUE(r.ok()) << r.error();
  EXPECT_EQ(r->layout.load_unit, "%");
  ASSERT_EQ(r->block_count(), 2u);
  EXPECT_EQ(r->blocks[0].load, 72.5);
  EXPECT_EQ(r->blocks[1].load, 72.5);
}

TEST_F(RecordReplay, RecordStopsCleanlyOnSigintAndKeepsWhatItGot) {
  const std::vector<AccelBlock> sent = MakeBlocks(2);
  ToolProcess rec(
      {"record", "--domain", Domain(), "--out", (dir_ / "rec").string(), "--machine", "gearbox-1"},
      dir_, "rec");
  ASSERT_TRUE(rec.WaitForStderr("subscribed", std::chrono::seconds(10))) << rec.Err();
  PublishFromTest(sent);
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  rec.Signal(SIGINT);
  ASSERT_EQ(rec.Wait(std::chrono::seconds(10)), 0) << rec.Err();
  EXPECT_NE(rec.Err().find("stopped by signal"), std::string::npos) << rec.Err();
  EXPECT_NE(rec.Err().find("2 of other machines ignored"), std::string::npos) << rec.Err();
  Result<Recording> r = ReadRecording(dir_ / "rec" / "gearbox-1");
  ASSERT_TRUE(r.ok()) << r.error();
  ASSERT_EQ(r->block_count(), 2u);
  ExpectSameBlock(r->block(1), sent[2].view());
}

TEST_F(RecordReplay, RecordReportsAMachineThatSentNothing) {
  std::string out, err;
  EXPECT_EQ(RunTool({"record", "--domain", Domain(), "--out", (dir_ / "rec").string(), "--machine",
                     "ghost", "--duration", "0.5"},
                    dir_, "rec", &out, &err),
            1);
  EXPECT_NE(err.find("no block from machine \"ghost\""), std::string::npos) << err;
}

TEST_F(RecordReplay, RecordRefusesAnOutputDirectoryThatIsNotEmpty) {
  fs::create_directories(dir_ / "busy");
  std::ofstream(dir_ / "busy" / "file") << "x";
  std::string err;
  EXPECT_EQ(RunTool({"record", "--out", (dir_ / "busy").string()}, dir_, "rec", nullptr, &err), 2);
  EXPECT_NE(err.find("already exists and is not an empty directory"), std::string::npos) << err;
}

TEST_F(RecordReplay, ReplayRejectsAMissingInput) {
  std::string err;
  EXPECT_EQ(RunTool({"replay", (dir_ / "nothing").string()}, dir_, "replay", nullptr, &err), 2);
  EXPECT_NE(err.find("no such file or directory"), std::string::npos) << err;
}

TEST_F(RecordReplay, ReplayRejectsADirectoryOfAnotherFormat) {
  fs::create_directories(dir_ / "frf");
  std::ofstream(dir_ / "frf" / "manifest.json") << R"({"format": "gearpath-frf-set"})";
  std::string err;
  EXPECT_EQ(RunTool({"replay", (dir_ / "frf").string()}, dir_, "replay", nullptr, &err), 2);
  EXPECT_NE(err.find("format: expected \"gearpath-recording\""), std::string::npos) << err;
}

TEST_F(RecordReplay, ReplayRejectsSamplesOfTheWrongShape) {
  Recording r;
  AccelBlock b = MakeBlocks(1)[0];
  r.layout = LayoutOf(b.view());
  r.blocks = {{b.sequence, b.t0_ns, b.speed_hz, b.speed_source}};
  r.samples = b.samples;
  ASSERT_TRUE(WriteRecording(r, dir_ / "rec").ok());
  ASSERT_TRUE(WriteNpy<float>(dir_ / "rec" / "samples.npy", b.samples, {1, 256, 3}).ok());
  std::string err;
  EXPECT_EQ(RunTool({"replay", (dir_ / "rec").string()}, dir_, "replay", nullptr, &err), 2);
  EXPECT_NE(err.find("shape (1, 256, 3) does not match the manifest: expected (1, 3, 256)"),
            std::string::npos)
      << err;
}

TEST_F(RecordReplay, ReplayRejectsAnUnknownMachine) {
  for (const AccelBlock& b : MakeBlocks(1)) {
    Recording r;
    r.layout = LayoutOf(b.view());
    r.blocks = {{b.sequence, b.t0_ns, b.speed_hz, b.speed_source}};
    r.samples = b.samples;
    ASSERT_TRUE(WriteRecording(r, dir_ / "recs" / b.machine_id.substr(0, 4)).ok());
  }
  std::string err;
  EXPECT_EQ(RunTool({"replay", (dir_ / "recs").string(), "--select", "gearbox-9"}, dir_, "replay",
                    nullptr, &err),
            2);
  EXPECT_NE(err.find("unknown machine \"gearbox-9\""), std::string::npos) << err;
}

TEST_F(RecordReplay, ReplayCutsATextExportWithDecimalCommaIntoBlocks) {
  // 10 samples at 100 Hz, decimal comma, semicolons, units row in g: blocks of 4 (2 blocks, the
  // last 2 samples dropped), values scaled to m/s^2.
  std::string text = "Sample rate: 100 Hz\nA1-X;A2-Y\ng;m/s^2\n";
  for (int k = 0; k < 10; ++k) {
    text += std::to_string(k) + ",25;-" + std::to_string(k) + ",5\n";
  }
  std::ofstream(dir_ / "export.txt") << text;
  std::string out, err;
  ASSERT_EQ(RunTool({"replay", (dir_ / "export.txt").string(), "--block-length", "4", "--machine",
                     "gb", "--write-recording", (dir_ / "rec").string()},
                    dir_, "replay", &out, &err),
            0)
      << err;
  EXPECT_NE(err.find("the last 2 samples per channel do not fill a block"), std::string::npos)
      << err;
  Result<Recording> r = ReadRecording(dir_ / "rec");
  ASSERT_TRUE(r.ok()) << r.error();
  EXPECT_EQ(r->layout.machine_id, "gb");
  EXPECT_EQ(r->layout.sample_rate_hz, 100.0);
  ASSERT_EQ(r->block_count(), 2u);
  EXPECT_EQ(r->blocks[1].sequence, 1u);
  EXPECT_EQ(r->blocks[1].t0_ns - r->blocks[0].t0_ns, 40000000);  // 4 samples at 100 Hz
  const AccelBlockView b1 = r->block(1);
  EXPECT_EQ(b1.channels[0].sensor, "A1");
  EXPECT_EQ(b1.channels[1].axis, Axis::kY);
  EXPECT_EQ(b1.channel(0)[0], static_cast<float>(4.25 * 9.80665));
  EXPECT_EQ(b1.channel(1)[3], -7.5f);
}

TEST_F(RecordReplay, ReplayReadsUffTimeHistoriesSampleForSample) {
  // Two time responses (function type 1) at 512 Hz, the second measured along -Z.
  std::vector<Uff58Record> records(2);
  for (int c = 0; c < 2; ++c) {
    Uff58Record& rec = records[static_cast<std::size_t>(c)];
    rec.function_type = kUffTimeResponse;
    rec.response_node = 11 + c;
    rec.response_direction = c == 0 ? 1 : -3;
    rec.complex_ordinate = false;
    rec.double_precision = true;
    rec.abscissa_start = 0.0;
    rec.abscissa_increment = 1.0 / 512.0;
    rec.ordinate_axis.unit_label = "m/s^2";
    for (int k = 0; k < 300; ++k) {
      rec.ordinate.emplace_back(std::sin(0.1 * k + c) + 0.001 * k, 0.0);
    }
  }
  ASSERT_TRUE(WriteUff58(dir_ / "th.unv", records, UffEncoding::kAscii).ok());
  std::string err;
  ASSERT_EQ(RunTool({"replay", (dir_ / "th.unv").string(), "--block-length", "128",
                     "--write-recording", (dir_ / "rec").string()},
                    dir_, "replay", nullptr, &err),
            0)
      << err;
  // Read back the file independently of replay: the ASCII file holds the values as printed.
  Result<std::vector<Uff58Record>> reread = ReadUff58(dir_ / "th.unv");
  ASSERT_TRUE(reread.ok()) << reread.error();
  Result<Recording> r = ReadRecording(dir_ / "rec");
  ASSERT_TRUE(r.ok()) << r.error();
  EXPECT_EQ(r->layout.machine_id, "th");
  EXPECT_NEAR(r->layout.sample_rate_hz, 512.0, 512.0 * 1e-5);
  ASSERT_EQ(r->block_count(), 2u);
  ASSERT_EQ(r->layout.channels.size(), 2u);
  EXPECT_EQ(r->layout.channels[0].sensor, "11");
  EXPECT_EQ(r->layout.channels[0].axis, Axis::kX);
  EXPECT_EQ(r->layout.channels[1].axis, Axis::kZ);
  for (std::size_t b = 0; b < 2; ++b) {
    for (std::size_t k = 0; k < 128; ++k) {
      const std::size_t n = b * 128 + k;
      ASSERT_EQ(r->block(b).channel(0)[k], static_cast<float>((*reread)[0].ordinate[n].real()));
      // -Z becomes +Z with the sign flipped.
      ASSERT_EQ(r->block(b).channel(1)[k], static_cast<float>(-(*reread)[1].ordinate[n].real()));
    }
  }
  // And the printed values are the signal (E20.12 keeps 12 digits).
  EXPECT_NEAR(r->block(1).channel(0)[5], std::sin(0.1 * 133) + 0.133, 1e-6);
}

TEST_F(RecordReplay, ReplayKeepsOnlyTheBlocksBetweenStartAndEnd) {
  Recording r;
  const std::vector<AccelBlock> blocks = MakeBlocks(5);
  r.layout = LayoutOf(blocks[0].view());
  for (std::size_t i = 0; i < 5; ++i) {
    const AccelBlock& b = blocks[2 * i];
    r.blocks.push_back({b.sequence, b.t0_ns, b.speed_hz, b.speed_source});
    r.samples.insert(r.samples.end(), b.samples.begin(), b.samples.end());
  }
  ASSERT_TRUE(WriteRecording(r, dir_ / "rec").ok());
  // Blocks start every 0.16 s: [0.3, 0.5) holds the blocks at 0.32 and 0.48 s.
  std::string err;
  ASSERT_EQ(RunTool({"replay", (dir_ / "rec").string(), "--start", "0.3", "--end", "0.5",
                     "--write-recording", (dir_ / "cut").string()},
                    dir_, "replay", nullptr, &err),
            0)
      << err;
  Result<Recording> cut = ReadRecording(dir_ / "cut");
  ASSERT_TRUE(cut.ok()) << cut.error();
  ASSERT_EQ(cut->block_count(), 2u);
  ExpectSameBlock(cut->block(0), blocks[4].view());
  ExpectSameBlock(cut->block(1), blocks[6].view());
}

TEST_F(RecordReplay, ReplayLoopContinuesSequenceAndTimeAcrossPasses) {
  // 8 samples at 100 Hz in blocks of 4: two blocks per pass, three passes.
  std::string text = "Sample rate: 100 Hz\nA1-X\n";
  for (int k = 0; k < 8; ++k) text += std::to_string(k) + "\n";
  std::ofstream(dir_ / "export.txt") << text;
  ToolProcess rec({"record", "--domain", Domain(), "--out", (dir_ / "rec").string(), "--count",
                   "6"},
                  dir_, "rec");
  ASSERT_TRUE(rec.WaitForStderr("subscribed", std::chrono::seconds(10))) << rec.Err();
  std::string out, err;
  ASSERT_EQ(RunTool({"replay", (dir_ / "export.txt").string(), "--block-length", "4", "--fast",
                     "--loop", "--loops", "3", "--machine", "gb", "--domain", Domain()},
                    dir_, "replay", &out, &err),
            0)
      << err;
  ASSERT_EQ(rec.Wait(std::chrono::seconds(15)), 0) << rec.Err();
  Result<Recording> r = ReadRecording(dir_ / "rec" / "gb");
  ASSERT_TRUE(r.ok()) << r.error();
  ASSERT_EQ(r->block_count(), 6u);
  for (std::size_t i = 0; i < 6; ++i) {
    EXPECT_EQ(r->blocks[i].sequence, i);
    EXPECT_EQ(r->blocks[i].t0_ns - r->blocks[0].t0_ns, static_cast<std::int64_t>(i) * 40000000);
    EXPECT_EQ(r->block(i).channel(0)[1], static_cast<float>((i % 2) * 4 + 1));
  }
}

TEST_F(RecordReplay, ReplayFailsWithExitCode1WhenNobodySubscribes) {
  std::ofstream(dir_ / "export.txt") << "Sample rate: 100 Hz\nA1-X\n1\n2\n";
  std::string err;
  EXPECT_EQ(RunTool({"replay", (dir_ / "export.txt").string(), "--fast", "--wait", "0.3",
                     "--domain", Domain()},
                    dir_, "replay", nullptr, &err),
            1);
  EXPECT_NE(err.find("no daemon subscribed to the block topic"), std::string::npos) << err;
}

TEST_F(RecordReplay, EverySubcommandHasHelp) {
  for (const char* cmd : {"record", "replay", "bridge"}) {
    std::string out;
    EXPECT_EQ(RunTool({cmd, "--help"}, dir_, std::string("help_") + cmd, &out), 0) << cmd;
    EXPECT_NE(out.find("--domain"), std::string::npos) << out;
  }
}

}  // namespace
}  // namespace gearpath::tools
