// gearpathd against hostile input (issue 10's bar): reloaded with each input that once killed
// it (a number that overflows a double, nesting 50 000 deep in the configuration or 100 000
// deep in an FRF set manifest, bytes that are not UTF-8), it keeps running its old
// configuration and still processes blocks; blocks with an implausible speed, all zeros or
// sequence number 2^64-1 are judged without corrupting its counters.
#include <algorithm>
#include <limits>
#include <string>

#include "core/io/frf_set_io.h"
#include "core/pipeline/block_validation.h"
#include "tests/integration/gearpathd_fixture.h"

namespace gearpath::testing {
namespace {

// `text` with the first value of `"key": ` replaced by `value` (raw JSON).
std::string WithValue(std::string text, const std::string& key, const std::string& value) {
  const std::string k = "\"" + key + "\": ";
  const auto at = text.find(k);
  EXPECT_NE(at, std::string::npos) << key;
  const auto end = text.find_first_of(",\n}", at + k.size());
  return text.replace(at + k.size(), end - at - k.size(), value);
}

std::size_t Count(const std::string& text, const std::string& part) {
  std::size_t n = 0;
  for (auto at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) ++n;
  return n;
}

struct CrashInput {
  const char* what;
  std::string config_text;  // the configuration file written before SIGHUP
  std::string error;        // what the reload error must say
};

TEST_F(GearpathdOverDds, ReloadWithEachCrashInputKeepsRunningTheOldConfiguration) {
  std::uint64_t seq = 1;
  Publish(NoiseBlock(seq++));
  ASSERT_TRUE(WaitStatus([](const auto& m) { return m.blocks_processed == 1; }, 30s));

  // An FRF set on disk (the built-in one), whose manifest the last two inputs corrupt.
  const auto set_dir = dir_ / "frf_set";
  auto set = daemon::BuiltinFrfSet("table1");
  ASSERT_TRUE(set.ok()) << set.error();
  ASSERT_TRUE(WriteFrfSet(*set, set_dir).ok());
  const std::string manifest = (set_dir / kFrfSetManifestName).string();
  std::string manifest_text;
  {
    std::ifstream in(manifest);
    manifest_text.assign(std::istreambuf_iterator<char>(in), {});
  }
  json on_disk = config_;
  on_disk["machines"][0]["frf_set"] = set_dir.string();
  const std::string good = config_.dump(2);
  const std::string deep = std::string(50'000, '[') + std::string(50'000, ']');
  std::string not_utf8 = good;
  not_utf8.replace(not_utf8.find(daemon_id_), daemon_id_.size(), "gearpathd_\xE9\xFF");

  const std::vector<CrashInput> inputs = {
      {"1e999 in the configuration", WithValue(good, "status_period_s", "1e999"),
       config_path_ + ": not valid JSON: line "},
      {"-1e999 in the configuration", WithValue(good, "status_period_s", "-1e999"),
       "number overflow parsing '-1e999' (too large for a double)"},
      {"50 000 nested arrays in the configuration", WithValue(good, "status_period_s", deep),
       "nested deeper than 64 levels"},
      {"a daemon id that is not UTF-8", not_utf8, "UTF-8"},
      {"1e999 in the FRF set manifest", on_disk.dump(2),
       manifest + ": not valid JSON: line 3, column"},
      {"100 000 nested arrays in the FRF set manifest", on_disk.dump(2),
       manifest + ": not valid JSON: line 3, column 84: nested deeper than 64 levels"},
  };
  std::size_t failures = 0;
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    const CrashInput& input = inputs[i];
    SCOPED_TRACE(input.what);
    if (i == 4) {
      std::ofstream(manifest) << WithValue(manifest_text, "format_version", "1e999");
    } else if (i == 5) {
      std::ofstream(manifest) << WithValue(manifest_text, "format_version",
                                           std::string(100'000, '[') + std::string(100'000, ']'));
    }
    const std::size_t said_before = Count(daemon_->Log(), input.error);
    std::ofstream(config_path_, std::ios::trunc) << input.config_text;
    daemon_->Signal(SIGHUP);
    ++failures;
    const std::string refused = "reload failed, still running the previous configuration";
    const auto deadline = std::chrono::steady_clock::now() + 30s;
    while (Count(daemon_->Log(), refused) < failures && daemon_->running() &&
           std::chrono::steady_clock::now() < deadline) {
      std::this_thread::sleep_for(20ms);
    }
    ASSERT_TRUE(daemon_->running()) << "gearpathd died on reload";
    ASSERT_EQ(Count(daemon_->Log(), refused), failures);
    EXPECT_GT(Count(daemon_->Log(), input.error), said_before) << input.error;
    // Still running the old configuration: the next block is processed.
    Publish(NoiseBlock(seq++));
    const std::uint64_t processed = seq - 1;
    ASSERT_TRUE(WaitStatus([&](const auto& m) { return m.blocks_processed == processed; }, 30s))
        << "processed " << last_status_.blocks_processed;
  }
  EXPECT_EQ(last_status_.blocks_rejected, 0u);
  EXPECT_TRUE(daemon_->running());
}

TEST_F(GearpathdOverDds, RejectsImplausibleSpeedAndAllZeroBlocksAndSurvivesSequence2To64Minus1) {
  std::uint64_t processed = 0;
  std::uint64_t rejected = 0;
  Publish(NoiseBlock(1));
  ++processed;
  ASSERT_TRUE(WaitStatus([&](const auto& m) { return m.blocks_processed == processed; }, 30s));
  struct Bad {
    const char* what;
    RejectReason reason;
    void (*spoil)(AccelBlock&);
  };
  const Bad bad[] = {
      {"speed 1e300 Hz", RejectReason::kImplausibleSpeed,
       [](AccelBlock& b) { b.speed_hz = 1e300; }},
      {"NaN speed", RejectReason::kImplausibleSpeed,
       [](AccelBlock& b) { b.speed_hz = std::numeric_limits<double>::quiet_NaN(); }},
      {"all-zero block", RejectReason::kFlatChannel,
       [](AccelBlock& b) { std::fill(b.samples.begin(), b.samples.end(), 0.0f); }},
  };
  std::uint64_t seq = 2;
  for (const Bad& b : bad) {
    SCOPED_TRACE(b.what);
    AccelBlock block = NoiseBlock(seq++);
    b.spoil(block);
    Publish(block);
    ++rejected;
    const std::string reason(ToString(b.reason));
    ASSERT_TRUE(WaitStatus(
        [&](const auto& m) {
          return m.blocks_rejected == rejected &&
                 std::string_view(m.last_rejection_reason).starts_with(reason);
        },
        20s))
        << last_status_.last_rejection_reason;
  }
  EXPECT_TRUE(
      daemon_->WaitForLog("rejected (implausible_speed): speed 1e+300 Hz of block 2 is "
                          "outside the plausible range",
                          5s));
  // 2^64-1 then normal blocks: all processed, none lost (the rejected blocks explain the gap).
  for (std::uint64_t s : {std::numeric_limits<std::uint64_t>::max(), seq, seq + 1}) {
    Publish(NoiseBlock(s));
    ++processed;
    ASSERT_TRUE(WaitStatus([&](const auto& m) { return m.blocks_processed == processed; }, 30s))
        << "block " << s << ": " << last_status_.last_rejection_reason;
  }
  EXPECT_EQ(last_status_.blocks_rejected, rejected);
  EXPECT_EQ(last_status_.blocks_received, processed + rejected);
  EXPECT_EQ(daemon_->Log().find("block(s) missing"), std::string::npos) << daemon_->Log();
  // The dominant path of the last block has a name.
  auto dominant = WaitResult<gearpath_DominantPath>(
      *dominant_reader_, [&](const auto& r) { return r.block_sequence == seq + 1; }, 10s);
  ASSERT_TRUE(dominant.has_value());
  EXPECT_NE(dds::GetString((*dominant)->path_name), "");
}

}  // namespace
}  // namespace gearpath::testing
