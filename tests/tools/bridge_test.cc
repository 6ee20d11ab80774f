// `gearpath bridge`: its units (directory scan, state file, stream framing) with an in-memory
// block sink, restarts included, and the command end to end over loopback DDS.
//
// Every test compares what was published against what the test itself wrote: no block lost or
// duplicated, sequence numbers consecutive across a restart, t0 as documented, samples bit for
// bit. Clocks are injected (settle rule) and processes waited on with deadlines: no sleeps.
#include <arpa/inet.h>
#include <fcntl.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <unistd.h>

#include <bit>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>
#include <thread>

#include "core/io/recording.h"
#include "tests/tools/tool_process.h"
#include "tools/bridge/bridge_state.h"
#include "tools/bridge/directory_bridge.h"
#include "tools/bridge/stream_bridge.h"
#include "tools/bridge/stream_cutter.h"
#include "tools/bridge/stream_header.h"

namespace gearpath::tools {
namespace {

namespace fs = std::filesystem;
using testing::ReadText;
using testing::TestDomainId;
using testing::ToolProcess;

// Keeps copies of what was "published"; fails from block `fail_at` on, like a bridge whose
// daemon vanished or that was killed: the block is not taken.
class MemorySink : public BlockSink {
 public:
  explicit MemorySink(std::size_t fail_at = SIZE_MAX) : fail_at_(fail_at) {}
  Status Publish(const AccelBlockView& v) override {
    if (blocks.size() >= fail_at_) return Error{"sink gone"};
    AccelBlock b;
    b.machine_id = std::string(v.machine_id);
    b.sequence = v.sequence;
    b.t0_ns = v.t0_ns;
    b.sample_rate_hz = v.sample_rate_hz;
    b.speed_hz = v.speed_hz;
    b.speed_source = v.speed_source;
    b.channels.assign(v.channels.begin(), v.channels.end());
    b.samples_per_channel = v.samples_per_channel;
    b.samples.assign(v.samples.begin(), v.samples.end());
    blocks.push_back(std::move(b));
    return Status::Ok();
  }
  Status Flush(std::chrono::milliseconds) override { return Status::Ok(); }
  std::vector<AccelBlock> blocks;

 private:
  std::size_t fail_at_;
};

std::vector<std::uint32_t> Bits(std::span<const float> s) {
  std::vector<std::uint32_t> out;
  for (float f : s) out.push_back(std::bit_cast<std::uint32_t>(f));
  return out;
}

class Bridge : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("gearpath_bridge_test_" + std::to_string(getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_ / "export");
    state_ = dir_ / "bridge.state.json";
  }
  void TearDown() override {
    if (!HasFailure()) fs::remove_all(dir_);
  }

  // A text export of 2 channels at 1000 Hz whose samples (exact in decimal and in binary)
  // depend on `seed`; planar samples returned.
  static std::vector<float> ExportSamples(int seed, std::size_t n) {
    std::vector<float> planar(2 * n);
    for (std::size_t k = 0; k < n; ++k) {
      planar[k] = static_cast<float>((static_cast<int>(k * 7 + seed * 131) % 1000) - 500) * 0.125f;
      planar[n + k] =
          static_cast<float>((static_cast<int>(k * 13 + seed * 17) % 777) - 300) / 64.0f;
    }
    return planar;
  }
  static std::string ExportText(int seed, std::size_t n) {
    const std::vector<float> s = ExportSamples(seed, n);
    std::string text =
        "DH8303 export, test " + std::to_string(seed) + "\nSample rate: 1000 Hz\nA1-X;A1-Y\n";
    char row[64];
    for (std::size_t k = 0; k < n; ++k) {
      std::snprintf(row, sizeof row, "%.9g;%.9g\n", s[k], s[n + k]);
      text += row;
    }
    return text;
  }
  void WriteFile(const fs::path& p, const std::string& text) {
    std::ofstream(p, std::ios::binary) << text;
  }
  static std::int64_t MtimeNs(const fs::path& p) {
    struct stat st {};
    EXPECT_EQ(::stat(p.c_str(), &st), 0);
    return static_cast<std::int64_t>(st.st_mtim.tv_sec) * 1000000000 + st.st_mtim.tv_nsec;
  }

  // The blocks a file must give (block length 100 at 1000 Hz: 0.1 s each): t0 = mtime minus
  // the file's duration, plus 0.1 s per block; `sequence` numbers from `first_sequence`.
  static void ExpectFileBlocks(const std::vector<AccelBlock>& got, std::size_t at, int seed,
                               std::size_t n, std::int64_t mtime_ns, std::uint64_t first_sequence) {
    const std::vector<float> s = ExportSamples(seed, n);
    const std::int64_t t0 = mtime_ns - static_cast<std::int64_t>(n) * 1000000;
    for (std::size_t b = 0; b < n / 100; ++b) {
      SCOPED_TRACE("file seed " + std::to_string(seed) + ", block " + std::to_string(b));
      ASSERT_LT(at + b, got.size());
      const AccelBlock& g = got[at + b];
      EXPECT_EQ(g.machine_id, "gearbox-7");
      EXPECT_EQ(g.sequence, first_sequence + b);
      EXPECT_EQ(g.t0_ns, t0 + static_cast<std::int64_t>(b) * 100000000);
      EXPECT_EQ(g.sample_rate_hz, 1000.0);
      ASSERT_EQ(g.samples_per_channel, 100u);
      ASSERT_EQ(g.channels.size(), 2u);
      EXPECT_EQ(g.channels[1].sensor, "A1");
      EXPECT_EQ(g.channels[1].axis, Axis::kY);
      for (std::size_t c = 0; c < 2; ++c) {
        const std::span<const float> want(s.data() + c * n + b * 100, 100);
        EXPECT_EQ(Bits(g.view().channel(c)), Bits(want)) << "channel " << c;
      }
    }
  }

  DirectoryBridgeOptions DirOptions(std::chrono::nanoseconds settle = {}) {
    DirectoryBridgeOptions o;
    o.directory = dir_ / "export";
    o.state_file = state_;
    o.input.machine = "gearbox-7";
    o.input.block_length = 100;
    o.settle = settle;
    o.clock = [this] { return now_; };
    return o;
  }

  BridgeState LoadState() {
    Result<BridgeState> s = LoadBridgeState(state_);
    EXPECT_TRUE(s.ok()) << s.error();
    return s.ok() ? *s : BridgeState{};
  }

  fs::path dir_, state_;
  std::chrono::nanoseconds now_{0};
};

TEST_F(Bridge, DirectoryPublishesEachFileOnceInOrderAndResumesMidFileAfterARestart) {
  // Names decide the order, not creation: b is written first.
  WriteFile(dir_ / "export" / "run_b.txt", ExportText(2, 230));  // 2 blocks + 30 samples
  WriteFile(dir_ / "export" / "run_a.txt", ExportText(1, 300));  // 3 blocks
  WriteFile(dir_ / "export" / "run_c.csv", ExportText(3, 400));  // 4 blocks
  std::vector<AccelBlock> published;
  {
    // First run: the sink takes 4 blocks, then fails (daemon gone, bridge killed) in run_b.
    BridgeState state = LoadState();
    MemorySink sink(4);
    DirectoryBridge bridge(DirOptions(), &state, &sink);
    Result<std::size_t> n = bridge.Poll();
    ASSERT_FALSE(n.ok());
    EXPECT_NE(n.error().find("run_b.txt: block 1 (sequence 4): sink gone"), std::string::npos)
        << n.error();
    published = sink.blocks;
  }
  {
    const BridgeState on_disk = LoadState();
    EXPECT_EQ(on_disk.next_sequence, 4u);
    ASSERT_EQ(on_disk.files.size(), 2u);
    EXPECT_EQ(on_disk.files[0].status, FileStatus::kPublished);
    EXPECT_EQ(on_disk.files[1].status, FileStatus::kPublishing);
    EXPECT_EQ(on_disk.files[1].blocks_published, 1u);
  }
  {
    // Restart: a new bridge from the state file continues with run_b's second block.
    BridgeState state = LoadState();
    MemorySink sink;
    DirectoryBridge bridge(DirOptions(), &state, &sink);
    Result<std::size_t> n = bridge.Poll();
    ASSERT_TRUE(n.ok()) << n.error();
    EXPECT_EQ(*n, 5u);
    Result<std::size_t> again = bridge.Poll();  // nothing new: nothing published
    ASSERT_TRUE(again.ok());
    EXPECT_EQ(*again, 0u);
    published.insert(published.end(), sink.blocks.begin(), sink.blocks.end());
    EXPECT_EQ(state.counters.files_published, 3u);
    EXPECT_EQ(state.counters.blocks_published, 9u);
    EXPECT_EQ(state.counters.dropped_samples, 30u);
  }
  {
    BridgeState state = LoadState();  // a third start publishes nothing either
    MemorySink sink;
    DirectoryBridge bridge(DirOptions(), &state, &sink);
    ASSERT_TRUE(bridge.Poll().ok());
    EXPECT_TRUE(sink.blocks.empty());
  }
  ASSERT_EQ(published.size(), 9u);
  for (std::size_t i = 0; i < published.size(); ++i) EXPECT_EQ(published[i].sequence, i);
  ExpectFileBlocks(published, 0, 1, 300, MtimeNs(dir_ / "export" / "run_a.txt"), 0);
  ExpectFileBlocks(published, 3, 2, 230, MtimeNs(dir_ / "export" / "run_b.txt"), 3);
  ExpectFileBlocks(published, 5, 3, 400, MtimeNs(dir_ / "export" / "run_c.csv"), 5);
}

TEST_F(Bridge, DirectoryTakesAFileOnlyOnceItHasSettledAndIgnoresPartFiles) {
  const fs::path file = dir_ / "export" / "run_a.txt";
  const std::string full = ExportText(1, 300);
  const std::size_t cut = full.find('\n', full.size() / 2) + 1;
  WriteFile(file, full.substr(0, cut));  // half written
  WriteFile(dir_ / "export" / "run_b.txt.part", ExportText(2, 200));
  BridgeState state = LoadState();
  MemorySink sink;
  DirectoryBridge bridge(DirOptions(std::chrono::seconds(5)), &state, &sink);
  ASSERT_TRUE(bridge.Poll().ok());
  EXPECT_TRUE(sink.blocks.empty()) << "a file seen for the first time has not settled";

  now_ += std::chrono::seconds(10);
  std::ofstream(file, std::ios::binary | std::ios::app) << full.substr(cut);  // writer goes on
  ASSERT_TRUE(bridge.Poll().ok());
  EXPECT_TRUE(sink.blocks.empty()) << "the file grew: its settle period starts again";

  now_ += std::chrono::seconds(4);
  ASSERT_TRUE(bridge.Poll().ok());
  EXPECT_TRUE(sink.blocks.empty()) << "4 s unchanged < 5 s settle";

  now_ += std::chrono::seconds(1);
  ASSERT_TRUE(bridge.Poll().ok());
  ASSERT_EQ(sink.blocks.size(), 3u) << "the whole file, once";
  ExpectFileBlocks(sink.blocks, 0, 1, 300, MtimeNs(file), 0);

  // The .part file never went out; renamed to its final name it is taken (after settling).
  fs::rename(dir_ / "export" / "run_b.txt.part", dir_ / "export" / "run_b.txt");
  ASSERT_TRUE(bridge.Poll().ok());
  EXPECT_EQ(sink.blocks.size(), 3u);
  now_ += std::chrono::seconds(5);
  ASSERT_TRUE(bridge.Poll().ok());
  ASSERT_EQ(sink.blocks.size(), 5u);
  ExpectFileBlocks(sink.blocks, 3, 2, 200, MtimeNs(dir_ / "export" / "run_b.txt"), 3);
}

TEST_F(Bridge, DirectoryCountsACorruptFileSkipsItAndNeverRetriesIt) {
  WriteFile(dir_ / "export" / "run_a.txt", ExportText(1, 200));
  WriteFile(dir_ / "export" / "run_b.txt", "A1-X;A1-Y\n1.0;2.0\nthree;4.0\n");
  WriteFile(dir_ / "export" / "run_c.txt", ExportText(3, 100));
  std::vector<std::string> log;
  {
    BridgeState state = LoadState();
    MemorySink sink;
    DirectoryBridge bridge(DirOptions(), &state, &sink,
                           [&](const std::string& line) { log.push_back(line); });
    ASSERT_TRUE(bridge.Poll().ok());
    ASSERT_EQ(sink.blocks.size(), 3u);  // a and c; sequence continues over the bad file
    ExpectFileBlocks(sink.blocks, 0, 1, 200, MtimeNs(dir_ / "export" / "run_a.txt"), 0);
    ExpectFileBlocks(sink.blocks, 2, 3, 100, MtimeNs(dir_ / "export" / "run_c.txt"), 2);
    EXPECT_EQ(state.counters.files_failed, 1u);
    ASSERT_TRUE(bridge.Poll().ok());  // not retried
    EXPECT_EQ(state.counters.files_failed, 1u);
    EXPECT_EQ(sink.blocks.size(), 3u);
  }
  bool logged = false;
  for (const std::string& l : log) {
    logged = logged || (l.find("run_b.txt") != std::string::npos &&
                        l.find("not retried") != std::string::npos);
  }
  EXPECT_TRUE(logged);
  const BridgeState state = LoadState();
  ASSERT_EQ(state.files.size(), 3u);
  EXPECT_EQ(state.files[1].name, "run_b.txt");
  EXPECT_EQ(state.files[1].status, FileStatus::kFailed);
  EXPECT_NE(state.files[1].error.find("run_b.txt"), std::string::npos) << state.files[1].error;
  {
    // After a restart it is still not retried; with --failed-dir a new bad file is moved away.
    BridgeState again = LoadState();
    WriteFile(dir_ / "export" / "run_d.unv", "    -1\n    58\ngarbage\n");
    DirectoryBridgeOptions o = DirOptions();
    o.failed_directory = dir_ / "failed";
    MemorySink sink;
    DirectoryBridge bridge(o, &again, &sink);
    ASSERT_TRUE(bridge.Poll().ok());
    EXPECT_TRUE(sink.blocks.empty());
    EXPECT_EQ(again.counters.files_failed, 2u);
    EXPECT_TRUE(fs::exists(dir_ / "failed" / "run_d.unv"));
    EXPECT_FALSE(fs::exists(dir_ / "export" / "run_d.unv"));
    EXPECT_TRUE(fs::exists(dir_ / "export" / "run_b.txt"));
  }
}

TEST_F(Bridge, DirectoryOrderByMtimeTakesTheOlderFileFirst) {
  WriteFile(dir_ / "export" / "z_first.txt", ExportText(1, 100));
  WriteFile(dir_ / "export" / "a_second.txt", ExportText(2, 100));
  const auto now = fs::file_time_type::clock::now();
  fs::last_write_time(dir_ / "export" / "z_first.txt", now - std::chrono::hours(2));
  fs::last_write_time(dir_ / "export" / "a_second.txt", now - std::chrono::hours(1));
  BridgeState state = LoadState();
  MemorySink sink;
  DirectoryBridgeOptions o = DirOptions();
  o.order = FileOrder::kMtime;
  DirectoryBridge bridge(o, &state, &sink);
  ASSERT_TRUE(bridge.Poll().ok());
  ASSERT_EQ(sink.blocks.size(), 2u);
  ExpectFileBlocks(sink.blocks, 0, 1, 100, MtimeNs(dir_ / "export" / "z_first.txt"), 0);
  ExpectFileBlocks(sink.blocks, 1, 2, 100, MtimeNs(dir_ / "export" / "a_second.txt"), 1);
}

TEST_F(Bridge, DirectoryForgetsFilesNoLongerThereAndTakesALaterFileOfTheSameNameAsNewData) {
  std::vector<std::string> log;
  BridgeState state = LoadState();
  MemorySink sink;
  DirectoryBridge bridge(DirOptions(), &state, &sink,
                         [&](const std::string& line) { log.push_back(line); });
  // An acquisition side that exports and cleans up: 40 files come and go, one at a time. The
  // state file holds the files that are in the directory, never the history.
  for (int i = 0; i < 40; ++i) {
    const fs::path file = dir_ / "export" / ("run_" + std::to_string(100 + i) + ".txt");
    WriteFile(file, ExportText(i, 100));
    ASSERT_TRUE(bridge.Poll().ok());
    ASSERT_EQ(sink.blocks.size(), static_cast<std::size_t>(i + 1));
    ExpectFileBlocks(sink.blocks, static_cast<std::size_t>(i), i, 100, MtimeNs(file),
                     static_cast<std::uint64_t>(i));
    fs::remove(file);
  }
  ASSERT_TRUE(bridge.Poll().ok());
  EXPECT_TRUE(state.files.empty());
  EXPECT_TRUE(LoadState().files.empty()) << "the state file on disk is pruned too";
  EXPECT_EQ(state.counters.files_published, 40u);
  EXPECT_EQ(state.counters.files_failed, 0u);
  bool said = false;
  for (const std::string& l : log) {
    said = said || l.find("1 file(s) no longer in") != std::string::npos;
  }
  EXPECT_TRUE(said);

  // A file that stays is published once however often the directory is scanned; a new file
  // under a forgotten name is new data, published with the next sequence numbers.
  WriteFile(dir_ / "export" / "keep.txt", ExportText(50, 200));
  ASSERT_TRUE(bridge.Poll().ok());
  ASSERT_TRUE(bridge.Poll().ok());
  ASSERT_EQ(sink.blocks.size(), 42u);
  const fs::path reused = dir_ / "export" / "run_100.txt";
  WriteFile(reused, ExportText(60, 300));
  ASSERT_TRUE(bridge.Poll().ok());
  ASSERT_EQ(sink.blocks.size(), 45u);
  ExpectFileBlocks(sink.blocks, 42, 60, 300, MtimeNs(reused), 42);
  ASSERT_EQ(LoadState().files.size(), 2u);
}

TEST_F(Bridge, DirectoryCountsAFileRemovedHalfPublishedAsFailed) {
  WriteFile(dir_ / "export" / "run_a.txt", ExportText(1, 500));  // 5 blocks
  {
    BridgeState state = LoadState();
    MemorySink sink(2);  // the bridge dies after two blocks
    DirectoryBridge bridge(DirOptions(), &state, &sink);
    ASSERT_FALSE(bridge.Poll().ok());
  }
  ASSERT_EQ(LoadState().files.size(), 1u);
  EXPECT_EQ(LoadState().files[0].status, FileStatus::kPublishing);
  fs::remove(dir_ / "export" / "run_a.txt");  // cleaned up while the bridge was down
  std::vector<std::string> log;
  BridgeState state = LoadState();
  MemorySink sink;
  DirectoryBridge bridge(DirOptions(), &state, &sink,
                         [&](const std::string& line) { log.push_back(line); });
  ASSERT_TRUE(bridge.Poll().ok());
  EXPECT_TRUE(sink.blocks.empty());
  const BridgeState after = LoadState();
  EXPECT_TRUE(after.files.empty());
  EXPECT_EQ(after.counters.files_failed, 1u);
  EXPECT_EQ(after.next_sequence, 2u);
  EXPECT_NE(after.last_error.find("run_a.txt: removed after 2 of its 5 blocks were published"),
            std::string::npos)
      << after.last_error;
  ASSERT_FALSE(log.empty());
  EXPECT_NE(log[0].find("removed after 2 of its 5"), std::string::npos) << log[0];
}

TEST_F(Bridge, StateFileIsReplacedAtomicallyAndAnUnreadableOneIsRefused) {
  BridgeState s;
  s.machine_id = "gearbox-7";
  s.next_sequence = 18446744073709551000ull;
  s.files.push_back(
      {.name = "a.txt", .size = 12, .mtime_ns = 5, .status = FileStatus::kFailed, .error = "bad"});
  ASSERT_TRUE(SaveBridgeState(s, state_).ok());
  for (const auto& e : fs::directory_iterator(dir_)) {
    EXPECT_EQ(e.path().filename().string().find(".tmp"), std::string::npos) << e.path();
  }
  const BridgeState back = LoadState();
  EXPECT_EQ(back.next_sequence, s.next_sequence);
  ASSERT_EQ(back.files.size(), 1u);
  EXPECT_EQ(back.files[0].error, "bad");

  WriteFile(state_, "{\"format\": \"gearpath-bridge-state\", \"version\": 1");
  Result<BridgeState> bad = LoadBridgeState(state_);
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.error().find(state_.string()), std::string::npos) << bad.error();
}

// --- stream mode ----------------------------------------------------------------------------

constexpr std::int64_t kStreamT0 = 1700000000000000000ll;

// A float32 stream of 3 channels at 2560 Hz (64 samples = 25 ms exactly) holding frames
// [first_frame, first_frame + frames) of a fixed signal, with awkward values.
float StreamValue(std::size_t frame, std::size_t c) {
  if (frame == 5 && c == 1) return -0.0f;
  if (frame == 6 && c == 2) return std::numeric_limits<float>::denorm_min();
  return std::sin(0.01f * static_cast<float>(frame * (c + 1))) * 3.7f + static_cast<float>(c);
}

std::vector<std::byte> FloatStream(std::size_t first_frame, std::size_t frames,
                                   std::size_t extra_bytes = 0) {
  StreamHeader h;
  h.format = StreamSampleFormat::kFloat32;
  h.sample_rate_hz = 2560.0;
  h.shaft_speed_hz = 24.5;
  h.t0_ns = kStreamT0 + static_cast<std::int64_t>(first_frame) * 390625;  // 1/2560 s
  h.scales = {1.0, 1.0, 1.0};
  Result<std::vector<std::byte>> bytes = EncodeStreamHeader(h, {"A1-X", "A1-Y", "B2-Z"});
  EXPECT_TRUE(bytes.ok());
  std::vector<std::byte> out = *bytes;
  for (std::size_t f = first_frame; f < first_frame + frames; ++f) {
    for (std::size_t c = 0; c < 3; ++c) {
      const float v = StreamValue(f, c);
      const auto* p = reinterpret_cast<const std::byte*>(&v);
      out.insert(out.end(), p, p + 4);
    }
  }
  out.insert(out.end(), extra_bytes, std::byte{0x7f});
  return out;
}

void ExpectStreamBlocks(const std::vector<AccelBlock>& got, std::size_t blocks) {
  ASSERT_EQ(got.size(), blocks);
  for (std::size_t b = 0; b < blocks; ++b) {
    SCOPED_TRACE("block " + std::to_string(b));
    const AccelBlock& g = got[b];
    EXPECT_EQ(g.sequence, b);
    EXPECT_EQ(g.t0_ns, kStreamT0 + static_cast<std::int64_t>(b) * 25000000);
    EXPECT_EQ(g.speed_hz, 24.5);
    EXPECT_EQ(g.speed_source, SpeedSource::kAcquisition);
    ASSERT_EQ(g.channels.size(), 3u);
    EXPECT_EQ(g.channels[2].sensor, "B2");
    EXPECT_EQ(g.channels[2].axis, Axis::kZ);
    ASSERT_EQ(g.samples_per_channel, 64u);
    for (std::size_t c = 0; c < 3; ++c) {
      std::vector<float> want;
      for (std::size_t k = 0; k < 64; ++k) want.push_back(StreamValue(b * 64 + k, c));
      EXPECT_EQ(Bits(g.view().channel(c)), Bits(want)) << "channel " << c;
    }
  }
}

class StreamBridgeTest : public Bridge {
 protected:
  // Runs a StreamBridge over `bytes` (from a file descriptor, as the command does).
  Result<StreamOutcome> RunStream(const std::vector<std::byte>& bytes, BlockSink& sink,
                                  BridgeState& state) {
    const fs::path file = dir_ / "stream.bin";
    std::ofstream(file, std::ios::binary)
        .write(reinterpret_cast<const char*>(bytes.data()), static_cast<long>(bytes.size()));
    const int fd = ::open(file.c_str(), O_RDONLY);
    EXPECT_GE(fd, 0);
    StreamBridge bridge({.machine_id = "gearbox-7", .block_length = 64, .state_file = state_},
                        &state, &sink);
    Result<StreamOutcome> out = bridge.Run(fd);
    ::close(fd);
    return out;
  }
};

TEST_F(StreamBridgeTest, CutsBlocksWithT0AndSequenceAndResumesAfterARestartMidStream) {
  std::vector<AccelBlock> published;
  {
    // 10 blocks and a half on the wire; the bridge dies after publishing 4 of them.
    BridgeState state = LoadState();
    MemorySink sink(4);
    Result<StreamOutcome> out = RunStream(FloatStream(0, 10 * 64 + 32), sink, state);
    ASSERT_FALSE(out.ok());
    EXPECT_NE(out.error().find("sink gone"), std::string::npos);
    published = sink.blocks;
  }
  EXPECT_EQ(LoadState().next_sequence, 4u);
  {
    // Restarted, the producer reconnects and sends from the first sample not published, with
    // its time in the header: sequence numbers continue from the state file.
    BridgeState state = LoadState();
    MemorySink sink;
    Result<StreamOutcome> out = RunStream(FloatStream(4 * 64, 6 * 64 + 32), sink, state);
    ASSERT_TRUE(out.ok()) << out.error();
    EXPECT_EQ(out->stream_error, "");
    EXPECT_EQ(out->blocks, 6u);
    EXPECT_EQ(out->dropped_samples, 32u);
    published.insert(published.end(), sink.blocks.begin(), sink.blocks.end());
  }
  ExpectStreamBlocks(published, 10);
  const BridgeState state = LoadState();
  EXPECT_EQ(state.next_sequence, 10u);
  EXPECT_EQ(state.counters.blocks_published, 10u);
  EXPECT_EQ(state.counters.streams_ended, 1u);
  EXPECT_EQ(state.counters.dropped_samples, 32u);
}

TEST_F(StreamBridgeTest, ASilentStreamEndsAfterTheIdleTimeoutKeepingTheBlocksBefore) {
  // A producer that sends a block and a half, then nothing, and never closes (a hung DAQ, a
  // half-open connection): the stream ends once it has been idle for the timeout.
  int fds[2];
  ASSERT_EQ(::socketpair(AF_UNIX, SOCK_STREAM, 0, fds), 0);
  const std::vector<std::byte> bytes = FloatStream(0, 64 + 32);
  ASSERT_EQ(::write(fds[1], bytes.data(), bytes.size()), static_cast<ssize_t>(bytes.size()));
  BridgeState state = LoadState();
  MemorySink sink;
  StreamBridge bridge({.machine_id = "gearbox-7",
                       .block_length = 64,
                       .state_file = state_,
                       .idle_timeout = std::chrono::milliseconds(300)},
                      &state, &sink);
  const auto start = std::chrono::steady_clock::now();
  Result<StreamOutcome> out = bridge.Run(fds[0]);
  const auto took = std::chrono::steady_clock::now() - start;
  ::close(fds[0]);
  ::close(fds[1]);
  ASSERT_TRUE(out.ok()) << out.error();
  EXPECT_EQ(out->stream_error,
            "no data for 0.3 s (idle timeout): stream ended, 32 frames short of a block not sent");
  EXPECT_EQ(out->blocks, 1u);
  EXPECT_GE(took, std::chrono::milliseconds(300));
  EXPECT_LT(took, std::chrono::seconds(10));
  ExpectStreamBlocks(sink.blocks, 1);
  const BridgeState after = LoadState();
  EXPECT_EQ(after.counters.stream_errors, 1u);
  EXPECT_EQ(after.counters.streams_ended, 0u);
  EXPECT_EQ(after.next_sequence, 1u);

  // Data that keeps coming, if slower than the timeout in total, is never cut.
  ASSERT_EQ(::socketpair(AF_UNIX, SOCK_STREAM, 0, fds), 0);
  const std::vector<std::byte> slow = FloatStream(64, 2 * 64);
  std::thread producer([&] {
    for (std::size_t i = 0; i < slow.size(); i += slow.size() / 4) {
      const std::size_t n = std::min(slow.size() / 4, slow.size() - i);
      EXPECT_EQ(::write(fds[1], slow.data() + i, n), static_cast<ssize_t>(n));
      std::this_thread::sleep_for(std::chrono::milliseconds(150));  // the producer's pace
    }
    ::close(fds[1]);
  });
  BridgeState state2 = LoadState();
  MemorySink sink2;
  StreamBridge bridge2({.machine_id = "gearbox-7",
                        .block_length = 64,
                        .state_file = state_,
                        .idle_timeout = std::chrono::milliseconds(1000)},
                       &state2, &sink2);
  Result<StreamOutcome> out2 = bridge2.Run(fds[0]);
  producer.join();
  ::close(fds[0]);
  ASSERT_TRUE(out2.ok()) << out2.error();
  EXPECT_EQ(out2->stream_error, "");
  EXPECT_EQ(out2->blocks, 2u);
}

TEST_F(StreamBridgeTest, CutterGivesTheSameBlocksHoweverTheBytesAreSplit) {
  const std::vector<std::byte> bytes = FloatStream(0, 3 * 64);
  std::vector<AccelBlock> got;
  MemorySink sink;
  StreamCutter cutter({.machine_id = "gearbox-7", .block_length = 64});
  for (std::size_t i = 0; i < bytes.size();) {
    const std::size_t n = std::min<std::size_t>(1 + (i % 7), bytes.size() - i);  // 1..7 bytes
    ASSERT_TRUE(cutter
                    .Feed(std::span(bytes).subspan(i, n),
                          [&](const AccelBlockView& v) { return sink.Publish(v); })
                    .ok());
    i += n;
  }
  ASSERT_TRUE(cutter.Finish().ok());
  ExpectStreamBlocks(sink.blocks, 3);
}

TEST_F(StreamBridgeTest, Int16SamplesAreScaledPerChannel) {
  StreamHeader h;
  h.format = StreamSampleFormat::kInt16;
  h.sample_rate_hz = 1000.0;
  h.t0_ns = 5;
  h.scales = {0.001, -2.5};
  std::vector<std::byte> bytes = *EncodeStreamHeader(h, {"7", "A3-Y"});
  const std::int16_t values[] = {32767, -32768, -1, 3, 0, 1000};
  for (std::int16_t v : values) {
    const auto* p = reinterpret_cast<const std::byte*>(&v);
    bytes.insert(bytes.end(), p, p + 2);
  }
  MemorySink sink;
  StreamCutter cutter({.machine_id = "m", .block_length = 3});
  ASSERT_TRUE(cutter.Feed(bytes, [&](const AccelBlockView& v) { return sink.Publish(v); }).ok());
  ASSERT_TRUE(cutter.Finish().ok());
  ASSERT_EQ(sink.blocks.size(), 1u);
  const AccelBlock& b = sink.blocks[0];
  EXPECT_EQ(b.t0_ns, 5);
  EXPECT_EQ(b.speed_source, SpeedSource::kUnknown);
  EXPECT_EQ(b.channels[0].sensor, "7");
  const std::vector<float> want = {
      static_cast<float>(32767 * 0.001), static_cast<float>(-1 * 0.001),
      static_cast<float>(0 * 0.001),     static_cast<float>(-32768 * -2.5),
      static_cast<float>(3 * -2.5),      static_cast<float>(1000 * -2.5)};
  EXPECT_EQ(Bits(b.samples), Bits(want));
}

TEST_F(StreamBridgeTest, MalformedOrTruncatedStreamsAreClearErrorsAndCounted) {
  struct Case {
    std::vector<std::byte> bytes;
    std::string expect;
  };
  std::vector<Case> cases;
  std::vector<std::byte> good = FloatStream(0, 64);
  {
    std::vector<std::byte> b = good;
    b[0] = std::byte{'X'};
    cases.push_back({b, "bad magic \"XPBS\""});
  }
  {
    std::vector<std::byte> b = good;
    b[4] = std::byte{9};
    cases.push_back({b, "version 9 is not supported"});
  }
  {
    std::vector<std::byte> b = good;
    b[8] = std::byte{3};
    cases.push_back({b, "sample format 3 unknown"});
  }
  {
    std::vector<std::byte> b = good;
    b[6] = std::byte{0};
    cases.push_back({b, "channel count 0"});
  }
  {
    std::vector<std::byte> b = good;
    const double nan = std::nan("");
    std::memcpy(b.data() + 16, &nan, 8);
    cases.push_back({b, "sample rate"});
  }
  cases.push_back({{std::byte{'h'}, std::byte{'i'}, std::byte{'\n'}}, "bad magic \"hi\\x0a"});
  cases.push_back({std::vector<std::byte>(good.begin(), good.begin() + 50),
                   "stream ended inside its header (50 bytes of 160)"});
  cases.push_back({FloatStream(0, 64, 5), "stream truncated: it ends 5 bytes into a frame of 12"});
  {
    std::vector<std::byte> b = FloatStream(0, 128);  // block 0 fine, block 1 beyond int64 time
    const std::int64_t last = std::numeric_limits<std::int64_t>::max();
    std::memcpy(b.data() + 32, &last, 8);
    cases.push_back({b, "overflows the int64 time"});
  }
  BridgeState state = LoadState();
  for (std::size_t i = 0; i < cases.size(); ++i) {
    SCOPED_TRACE(cases[i].expect);
    MemorySink sink;
    Result<StreamOutcome> out = RunStream(cases[i].bytes, sink, state);
    ASSERT_TRUE(out.ok()) << out.error();  // bad input, not a bridge failure
    EXPECT_NE(out->stream_error.find(cases[i].expect), std::string::npos) << out->stream_error;
    EXPECT_EQ(state.counters.stream_errors, i + 1);
  }
  EXPECT_EQ(state.counters.blocks_published, 2u);  // the blocks completed before the error
  EXPECT_EQ(LoadState().counters.stream_errors, cases.size());
}

TEST_F(StreamBridgeTest, RandomBytesNeverCrashTheCutter) {
  // Random garbage, and a valid header with random bytes of random length after it, split at
  // random: every outcome is blocks, a clean end, or an error message; never a crash.
  std::mt19937 rng(7);
  const std::vector<std::byte> header = FloatStream(0, 0);
  for (int round = 0; round < 300; ++round) {
    std::vector<std::byte> bytes = round % 2 ? header : std::vector<std::byte>{};
    if (round % 3 == 0 && !bytes.empty()) bytes[6 + rng() % 34] = std::byte(rng());  // bad field
    const std::size_t extra = rng() % 2000;
    for (std::size_t i = 0; i < extra; ++i) bytes.push_back(std::byte(rng()));
    StreamCutter cutter(
        {.machine_id = "m", .block_length = static_cast<std::uint32_t>(1 + rng() % 50)});
    std::size_t blocks = 0;
    Status st = Status::Ok();
    for (std::size_t i = 0; i < bytes.size() && st.ok();) {
      const std::size_t n = std::min<std::size_t>(1 + rng() % 300, bytes.size() - i);
      st = cutter.Feed(std::span(bytes).subspan(i, n), [&](const AccelBlockView& v) {
        EXPECT_EQ(v.samples.size(), v.channels.size() * v.samples_per_channel);
        ++blocks;
        return Status::Ok();
      });
      i += n;
    }
    if (st.ok()) st = cutter.Finish();
    EXPECT_TRUE(st.ok() || !st.error().empty());
    EXPECT_EQ(cutter.blocks(), blocks);
  }
}

// --- the command, end to end over loopback DDS ------------------------------------------------

class BridgeCommand : public Bridge {
 protected:
  std::string Domain() const { return std::to_string(TestDomainId()); }

  // What the recorder wrote for the machine, as owning blocks.
  std::vector<AccelBlock> Recorded(const std::string& name) {
    Result<Recording> r = ReadRecording(dir_ / name / "gearbox-7");
    EXPECT_TRUE(r.ok()) << r.error();
    std::vector<AccelBlock> got;
    if (!r.ok()) return got;
    for (std::size_t i = 0; i < r->block_count(); ++i) {
      MemorySink copy;
      EXPECT_TRUE(copy.Publish(r->block(i)).ok());
      got.push_back(copy.blocks[0]);
    }
    return got;
  }

  // Waits (deadline 30 s) until the state file says `next` blocks went out.
  bool WaitForNextSequence(std::uint64_t next) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
    while (std::chrono::steady_clock::now() < deadline) {
      Result<BridgeState> s = LoadBridgeState(state_);
      if (s.ok() && s->next_sequence == next) return true;
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    return false;
  }
};

TEST_F(BridgeCommand, DirectoryModeOverDdsKilledAndRestartedLosesAndRepeatsNothing) {
  WriteFile(dir_ / "export" / "run_a.txt", ExportText(1, 300));
  WriteFile(dir_ / "export" / "run_b.txt", ExportText(2, 200));
  // The recorder runs until told to stop: one that left right after the last block could
  // leave it unacknowledged, and the bridge would wait for it (as for a vanished daemon).
  ToolProcess rec({"record", "--domain", Domain(), "--out", (dir_ / "rec").string()}, dir_, "rec");
  ASSERT_TRUE(rec.WaitForStderr("subscribed", std::chrono::seconds(10))) << rec.Err();
  const std::vector<std::string> args = {"bridge",
                                         "--dir",
                                         (dir_ / "export").string(),
                                         "--machine",
                                         "gearbox-7",
                                         "--state",
                                         state_.string(),
                                         "--block-length",
                                         "100",
                                         "--settle",
                                         "0",
                                         "--poll",
                                         "0.05",
                                         "--domain",
                                         Domain()};
  {
    // A watching bridge, killed without warning once both files are out.
    ToolProcess bridge(args, dir_, "bridge1");
    ASSERT_TRUE(WaitForNextSequence(5)) << bridge.Err();
    bridge.Signal(SIGKILL);
    ASSERT_EQ(bridge.Wait(std::chrono::seconds(10)), -SIGKILL);
  }
  // A new export while it was down, half of it still being written under a .part name.
  WriteFile(dir_ / "export" / "run_c.txt", ExportText(3, 400));
  WriteFile(dir_ / "export" / "run_d.txt.part", ExportText(4, 100));
  std::vector<std::string> once = args;
  once.push_back("--once");
  ToolProcess bridge2(once, dir_, "bridge2");
  ASSERT_EQ(bridge2.Wait(std::chrono::seconds(30)), 0) << bridge2.Err();
  EXPECT_NE(bridge2.Out().find("published 4 blocks (next sequence 9)"), std::string::npos)
      << bridge2.Out();

  // Restarted with nothing new: nothing published, and it says so. (No subscriber needed.)
  std::vector<std::string> again = once;
  again.insert(again.end(), {"--subscribers", "0"});
  ToolProcess bridge3(again, dir_, "bridge3");
  ASSERT_EQ(bridge3.Wait(std::chrono::seconds(30)), 0) << bridge3.Err();
  EXPECT_NE(bridge3.Out().find("published 0 blocks (next sequence 9)"), std::string::npos)
      << bridge3.Out();

  rec.Signal(SIGINT);
  ASSERT_EQ(rec.Wait(std::chrono::seconds(15)), 0) << rec.Err();
  const std::vector<AccelBlock> got = Recorded("rec");
  ASSERT_EQ(got.size(), 9u);  // each block exactly once, in order
  ExpectFileBlocks(got, 0, 1, 300, MtimeNs(dir_ / "export" / "run_a.txt"), 0);
  ExpectFileBlocks(got, 3, 2, 200, MtimeNs(dir_ / "export" / "run_b.txt"), 3);
  ExpectFileBlocks(got, 5, 3, 400, MtimeNs(dir_ / "export" / "run_c.txt"), 5);

  // Another machine's state file is refused, prefixed.
  std::vector<std::string> other = once;
  other[4] = "gearbox-8";
  ToolProcess bridge4(other, dir_, "bridge4");
  ASSERT_EQ(bridge4.Wait(std::chrono::seconds(30)), 2);
  EXPECT_NE(bridge4.Err().find("gearpath bridge: "), std::string::npos);
  EXPECT_NE(bridge4.Err().find("belongs to machine \"gearbox-7\""), std::string::npos)
      << bridge4.Err();
}

TEST_F(BridgeCommand, StopsPromptlyOnSigtermWhileWaitingForADaemon) {
  WriteFile(dir_ / "export" / "run_a.txt", ExportText(1, 300));
  // Nobody subscribes: the bridge holds the first block for up to --wait 120 s; SIGTERM must
  // end that wait (a service stop), with nothing recorded as published.
  ToolProcess bridge({"bridge", "--dir", (dir_ / "export").string(), "--machine", "gearbox-7",
                      "--state", state_.string(), "--block-length", "100", "--settle", "0",
                      "--wait", "120", "--domain", Domain()},
                     dir_, "bridge");
  ASSERT_TRUE(bridge.WaitForStderr("run_a.txt: publishing 3 blocks", std::chrono::seconds(10)))
      << bridge.Err();
  bridge.Signal(SIGTERM);
  ASSERT_EQ(bridge.Wait(std::chrono::seconds(20)), 0) << bridge.Err();
  EXPECT_NE(bridge.Err().find("stopped while waiting for a daemon"), std::string::npos)
      << bridge.Err();
  EXPECT_NE(bridge.Out().find("published 0 blocks (next sequence 0)"), std::string::npos)
      << bridge.Out();
  EXPECT_EQ(LoadState().next_sequence, 0u);
}

// Sends `bytes` to 127.0.0.1:port as one connection.
void SendStream(int port, const std::vector<std::byte>& bytes) {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  ASSERT_GE(fd, 0);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_port = htons(static_cast<std::uint16_t>(port));
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  ASSERT_EQ(::connect(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr), 0);
  std::size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    ASSERT_GT(n, 0);
    done += static_cast<std::size_t>(n);
  }
  ::close(fd);
}

int ListeningPort(ToolProcess& bridge) {
  if (!bridge.WaitForStderr("listening on 127.0.0.1:", std::chrono::seconds(10))) return -1;
  const std::string err = bridge.Err();
  return std::stoi(err.substr(err.find("127.0.0.1:") + 10));
}

TEST_F(BridgeCommand, StreamModeOverTcpAndDdsContinuesAfterTheBridgeIsKilled) {
  ToolProcess rec({"record", "--domain", Domain(), "--out", (dir_ / "rec").string()}, dir_, "rec");
  ASSERT_TRUE(rec.WaitForStderr("subscribed", std::chrono::seconds(10))) << rec.Err();
  const std::vector<std::string> args = {"bridge",    "--listen", "127.0.0.1:0",   "--machine",
                                         "gearbox-7", "--state",  state_.string(), "--block-length",
                                         "64",        "--domain", Domain()};
  {
    ToolProcess bridge(args, dir_, "bridge1");
    const int port = ListeningPort(bridge);
    ASSERT_GT(port, 0) << bridge.Err();
    SendStream(port, FloatStream(0, 2 * 64));  // two connections, the signal continuing
    SendStream(port, FloatStream(2 * 64, 2 * 64 + 20));
    ASSERT_TRUE(WaitForNextSequence(4)) << bridge.Err();
    bridge.Signal(SIGKILL);
    ASSERT_EQ(bridge.Wait(std::chrono::seconds(10)), -SIGKILL);
  }
  // Restarted: the producer reconnects and sends from where the published blocks end.
  ToolProcess bridge(args, dir_, "bridge2");
  const int port = ListeningPort(bridge);
  ASSERT_GT(port, 0) << bridge.Err();
  EXPECT_NE(bridge.Err().find("(next sequence 4)"), std::string::npos) << bridge.Err();
  SendStream(port, FloatStream(4 * 64, 6 * 64 + 10));
  ASSERT_TRUE(bridge.WaitForStderr("6 blocks published", std::chrono::seconds(20))) << bridge.Err();
  bridge.Signal(SIGTERM);
  ASSERT_EQ(bridge.Wait(std::chrono::seconds(10)), 0) << bridge.Err();
  EXPECT_NE(bridge.Out().find("published 6 blocks (next sequence 10)"), std::string::npos)
      << bridge.Out();
  rec.Signal(SIGINT);  // every block acknowledged: the recorder has them all
  ASSERT_EQ(rec.Wait(std::chrono::seconds(15)), 0) << rec.Err();
  ExpectStreamBlocks(Recorded("rec"), 10);
}

TEST_F(BridgeCommand, ListenDropsASilentConnectionAfterTheIdleTimeoutAndServesTheNext) {
  ToolProcess bridge(
      {"bridge", "--listen", "127.0.0.1:0", "--machine", "gearbox-7", "--state", state_.string(),
       "--block-length", "64", "--idle-timeout", "0.5", "--domain", Domain()},
      dir_, "bridge");
  const int port = ListeningPort(bridge);
  ASSERT_GT(port, 0) << bridge.Err();
  // Two clients that connect and say nothing: each is disconnected by the bridge (read gives
  // end of file), the second one only because the first was let go.
  for (int client = 1; client <= 2; ++client) {
    const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
    ASSERT_GE(fd, 0);
    sockaddr_in addr{};
    addr.sin_family = AF_INET;
    addr.sin_port = htons(static_cast<std::uint16_t>(port));
    addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    // Timed from before connect(): the bridge's idle clock starts when it accepts, which can be
    // before this thread runs again after connect() returns (seen under load: 499.9 ms).
    const auto start = std::chrono::steady_clock::now();
    ASSERT_EQ(::connect(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr), 0);
    timeval limit{30, 0};  // the watchdog of this read
    ASSERT_EQ(::setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &limit, sizeof limit), 0);
    char byte = 0;
    EXPECT_EQ(::read(fd, &byte, 1), 0) << "client " << client << ": not closed by the bridge";
    EXPECT_GE(std::chrono::steady_clock::now() - start, std::chrono::milliseconds(500));
    ::close(fd);
  }
  ASSERT_TRUE(bridge.WaitForStderr("(stream errors so far: 2)", std::chrono::seconds(10)))
      << bridge.Err();
  EXPECT_NE(bridge.Err().find("no data for 0.5 s (idle timeout): stream ended before its header "
                              "was complete"),
            std::string::npos)
      << bridge.Err();
  bridge.Signal(SIGTERM);
  ASSERT_EQ(bridge.Wait(std::chrono::seconds(10)), 0) << bridge.Err();
  EXPECT_EQ(LoadState().counters.stream_errors, 2u);
}

}  // namespace
}  // namespace gearpath::tools
