// `gearpath report` end to end: a recording of the simulated Table-1 gearbox (healthy blocks,
// then a tooth fracture on G1) is reported by the built tool; the page must parse as XML, draw
// one bar per path and one marker per shaft harmonic, and carry exactly the numbers of a
// BlockProcessor run here on the same blocks. Bad inputs exit with code 2 and say why.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <optional>
#include <string>
#include <vector>

#include "core/diagnosis/train_layout.h"
#include "core/io/frf_set_io.h"
#include "core/io/recording.h"
#include "core/model/gear_train.h"
#include "core/model/lumped_gearbox_model.h"
#include "core/pipeline/block_processor.h"
#include "core/simulation/gearbox_simulator.h"
#include "core/simulation/model_frf_set.h"

namespace gearpath {
namespace {

namespace fs = std::filesystem;

constexpr std::uint32_t kBlock = 8192;
constexpr double kFs = 8000.0;
constexpr int kHealthyBlocks = 6;
constexpr int kFaultyBlocks = 3;
constexpr int kReportedBlock = kHealthyBlocks + 1;  // the second faulty block

std::string ReadText(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

struct ToolRun {
  int code = -1;
  std::string out;
  std::string err;
};

// Runs `gearpath <args>` (arguments are test-made paths and numbers, no shell metacharacters).
ToolRun RunTool(const std::string& args, const fs::path& dir) {
  const fs::path out = dir / "tool.out";
  const fs::path err = dir / "tool.err";
  const std::string cmd =
      std::string(GEARPATH_TOOL_PATH) + " " + args + " >" + out.string() + " 2>" + err.string();
  const int status = std::system(cmd.c_str());
  ToolRun r;
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = ReadText(out);
  r.err = ReadText(err);
  return r;
}

bool HavePython() { return std::system("python3 -c 'import xml.dom.minidom' 2>/dev/null") == 0; }

// 0 when python3's XML parser accepts the file.
int ParseXml(const fs::path& file) {
  const std::string cmd =
      "python3 -c 'import sys, xml.dom.minidom; xml.dom.minidom.parse(sys.argv[1])' " +
      file.string();
  return std::system(cmd.c_str());
}

std::size_t Count(const std::string& text, const std::string& needle) {
  std::size_t n = 0;
  for (auto p = text.find(needle); p != std::string::npos; p = text.find(needle, p + 1)) ++n;
  return n;
}

// The data-value attributes of the table row opened by `row_marker`, in order.
std::vector<double> RowValues(const std::string& html, const std::string& row_marker) {
  std::vector<double> v;
  const auto start = html.find(row_marker);
  if (start == std::string::npos) return v;
  const auto end = html.find("</tr>", start);
  const std::string key = "data-value=\"";
  for (auto p = html.find(key, start); p != std::string::npos && p < end;
       p = html.find(key, p + 1)) {
    v.push_back(std::strtod(html.c_str() + p + key.size(), nullptr));
  }
  return v;
}

fs::path FixtureDir() {
  return fs::temp_directory_path() / ("gearpath_report_test_" + std::to_string(getpid()));
}

// Removes the recording and the pages once every test has run.
class RemoveFixtureDir : public ::testing::Environment {
 public:
  void TearDown() override { fs::remove_all(FixtureDir()); }
};
[[maybe_unused]] ::testing::Environment* const kCleanup =
    ::testing::AddGlobalTestEnvironment(new RemoveFixtureDir);

struct Fixture {
  fs::path dir;
  fs::path recording;
  MachineSetup setup;
  // The processor outlives the results: their path and shaft names are views into it.
  std::optional<BlockProcessor> processor;
  std::vector<BlockResult> results;  // per block, from `processor`
  // Copies of each block's condition-indicator values and z-scores (results[i].condition's
  // spans view the processor's buffers, which the next block overwrites).
  std::vector<std::vector<std::vector<double>>> condition_values;
  std::vector<std::vector<std::vector<double>>> condition_z;
};

// Table-1 model, the `builtin:table1` FRF grid (bins 1..4096 of 8192 samples at 8 kHz).
const Fixture& Shared() {
  static const Fixture f = [] {
    Fixture x;
    x.dir = FixtureDir();
    fs::remove_all(x.dir);
    fs::create_directories(x.dir);
    x.recording = x.dir / "rec";
    auto model = LumpedGearboxModel::Create(Table1Parameters());
    EXPECT_TRUE(model.ok());
    const GearTrain train = GearTrain::Table1();
    Eigen::VectorXd grid(kBlock / 2);
    for (Eigen::Index k = 0; k < grid.size(); ++k) {
      grid[k] = static_cast<double>(k + 1) * kFs / kBlock;
    }
    auto set = MakeModelFrfSet(model.value(), train, grid);
    EXPECT_TRUE(set.ok());

    Recording rec;
    std::uint64_t sequence = 0;
    for (const bool faulty : {false, true}) {
      SimulatorConfig c;
      c.machine_id = "sim";
      c.fault.type = faulty ? FaultType::kToothFracture : FaultType::kNone;
      c.fault.gear = faulty ? "G1" : "";
      c.sample_rate_hz = kFs;
      c.block_length = kBlock;
      c.noise_relative = 0.05;
      c.seed = faulty ? 11 : 7;
      c.include_housing_channel = false;
      // The faulty stream continues the healthy one in time.
      c.start_time_ns = faulty ? static_cast<std::int64_t>(kHealthyBlocks) * kBlock *
                                     1'000'000'000 / static_cast<std::int64_t>(kFs)
                               : 0;
      c.first_sequence = faulty ? kHealthyBlocks : 0;
      auto sim = GearboxSimulator::Create(model.value(), train, c);
      EXPECT_TRUE(sim.ok()) << sim.error();
      AccelBlock block;
      for (int i = 0; i < (faulty ? kFaultyBlocks : kHealthyBlocks); ++i) {
        sim->NextBlock(block);
        block.sequence = sequence++;
        const AccelBlockView v = block.view();
        if (rec.blocks.empty()) rec.layout = LayoutOf(v);
        rec.blocks.push_back({v.sequence, v.t0_ns, v.speed_hz, v.speed_source});
        rec.samples.insert(rec.samples.end(), v.samples.begin(), v.samples.end());
      }
    }
    EXPECT_TRUE(WriteRecording(rec, x.recording).ok());

    // The truth the page must show: the pipeline on the same blocks, automatic settings.
    x.setup.machine_id = "sim";
    x.setup.frf_set = set.value();
    x.setup.train = TrainLayoutFromGearTrain(train).value();
    x.setup.options.sample_rate_hz = kFs;
    x.setup.options.nominal_speed_hz = rec.blocks[0].speed_hz;
    x.setup.options.baseline_blocks = kHealthyBlocks;
    auto p = BlockProcessor::Create(x.setup);
    EXPECT_TRUE(p.ok()) << p.error();
    x.processor.emplace(std::move(p).value());
    BlockResult r;
    for (std::size_t i = 0; i < rec.block_count(); ++i) {
      EXPECT_TRUE(x.processor->Process(rec.block(i), r).accepted());
      x.results.push_back(r);
      auto& values = x.condition_values.emplace_back();
      auto& z = x.condition_z.emplace_back();
      for (const BlockConditionIndicators& c : r.condition) {
        values.emplace_back(c.value.begin(), c.value.end());
        z.emplace_back(c.z.begin(), c.z.end());
      }
    }
    return x;
  }();
  return f;
}

std::string ReportArgs(const Fixture& f, const std::string& range, const fs::path& out) {
  return "report --builtin table1 --recording " + f.recording.string() + " " + range +
         " --baseline-blocks " + std::to_string(kHealthyBlocks) + " -o " + out.string();
}

TEST(ReportCommandTest, WritesAWellFormedPageForAFaultyBlock) {
  const Fixture& f = Shared();
  const fs::path out = f.dir / "block.html";
  const ToolRun r = RunTool(ReportArgs(f, "--block " + std::to_string(kReportedBlock), out), f.dir);
  ASSERT_EQ(r.code, 0) << r.err;
  ASSERT_TRUE(fs::exists(out));
  if (!HavePython()) GTEST_SKIP() << "python3 with xml.dom.minidom not available";
  EXPECT_EQ(ParseXml(out), 0) << "the page is not well-formed XML";
}

TEST(ReportCommandTest, DrawsOneBarPerPathAndOneMarkerPerShaftHarmonic) {
  const Fixture& f = Shared();
  const fs::path out = f.dir / "markers.html";
  ASSERT_EQ(RunTool(ReportArgs(f, "--block " + std::to_string(kReportedBlock), out), f.dir).code,
            0);
  const std::string html = ReadText(out);
  const BlockResult& truth = f.results[kReportedBlock];
  EXPECT_EQ(Count(html, "<rect class=\"path-bar"), truth.paths.size());
  for (const BlockPathShare& p : truth.paths) {
    EXPECT_EQ(Count(html, "data-path=\"" + std::string(p.name) + "\" data-share=\"" +
                              fmt::format("{}", p.share) + "\""),
              1u)
        << p.name;
  }
  // Raw and reconstructed SES: every shaft's harmonics 1..5 marked once each.
  EXPECT_EQ(Count(html, "<line class=\"harmonic-marker\""), 2 * 5 * truth.shafts.size());
  for (const BlockShaftIndicator& sh : truth.shafts) {
    for (int h = 1; h <= 5; ++h) {
      EXPECT_EQ(Count(html, fmt::format("data-shaft=\"{}\" data-harmonic=\"{}\" data-hz=\"{}\"",
                                        sh.shaft, h, h * sh.characteristic_hz)),
                2u)
          << sh.shaft << " harmonic " << h;
    }
  }
  EXPECT_EQ(Count(html, "<rect class=\"chosen-band\""), 2u);
}

TEST(ReportCommandTest, TableAndVerdictAreTheBlockResults) {
  const Fixture& f = Shared();
  const fs::path out = f.dir / "table.html";
  ASSERT_EQ(RunTool(ReportArgs(f, "--block " + std::to_string(kReportedBlock), out), f.dir).code,
            0);
  const std::string html = ReadText(out);
  const BlockResult& truth = f.results[kReportedBlock];
  ASSERT_EQ(truth.shafts.size(), 3u);
  for (const BlockShaftIndicator& sh : truth.shafts) {
    const std::vector<double> v =
        RowValues(html, "<tr data-shaft=\"" + std::string(sh.shaft) + "\">");
    ASSERT_EQ(v.size(), 6u) << sh.shaft;
    EXPECT_EQ(v[0], sh.characteristic_hz);
    EXPECT_EQ(v[1], sh.raw);
    EXPECT_EQ(v[2], sh.raw_threshold);
    EXPECT_EQ(v[3], sh.reconstructed);
    EXPECT_EQ(v[4], sh.reconstructed_threshold);
    EXPECT_EQ(v[5], sh.enhancement_percent);
    EXPECT_GT(sh.raw_threshold, 0.0) << "the baseline was learned from the healthy blocks";
  }
  // A fault was simulated: the verdict is not "no fault", and the page says the pipeline's.
  ASSERT_TRUE(truth.verdict.state == FaultState::kSuspected ||
              truth.verdict.state == FaultState::kAlarm);
  const std::string state = truth.verdict.state == FaultState::kAlarm ? "alarm" : "suspected";
  EXPECT_EQ(Count(html, fmt::format("<p class=\"verdict-text\" data-state=\"{}\" data-gear=\"{}\">",
                                    state, truth.verdict.gear_name)),
            1u);
  EXPECT_EQ(truth.verdict.gear_name, "G1");
  EXPECT_NE(html.find(state == "alarm" ? ">ALARM: gear G1" : ">SUSPECTED: gear G1"),
            std::string::npos);
}

TEST(ReportCommandTest, ConditionTablesAreTheBlockResultsIndicatorsWithTheLimitInForce) {
  const Fixture& f = Shared();
  const fs::path out = f.dir / "condition.html";
  ASSERT_EQ(RunTool(ReportArgs(f, "--block " + std::to_string(kReportedBlock), out), f.dir).code,
            0);
  const std::string html = ReadText(out);
  const BlockResult& truth = f.results[kReportedBlock];
  ASSERT_GT(truth.score.limit_z, 0.0) << "the baseline was learned from the healthy blocks";
  EXPECT_NE(html.find(fmt::format("|z| {:.4g} (from the false-alarm rate)", truth.score.limit_z)),
            std::string::npos);
  ASSERT_FALSE(truth.condition.empty());
  EXPECT_EQ(Count(html, "<tr data-signal="), truth.condition.size());
  for (std::size_t i = 0; i < truth.condition.size(); ++i) {
    const BlockConditionIndicators& c = truth.condition[i];
    const std::vector<double>& value = f.condition_values[kReportedBlock][i];
    const std::vector<double>& z = f.condition_z[kReportedBlock][i];
    const std::vector<double> v = RowValues(
        html, fmt::format("<tr data-signal=\"{}\" data-source=\"{}\" data-shaft=\"{}\">",
                          c.signal, ToString(c.source), c.shaft));
    ASSERT_EQ(v.size(), 1 + 2 * value.size()) << c.signal << " at " << c.shaft;
    EXPECT_EQ(v[0], c.score);
    for (std::size_t k = 0; k < value.size(); ++k) {
      EXPECT_EQ(v[1 + 2 * k], value[k]) << c.signal << " at " << c.shaft << ", value " << k;
      EXPECT_EQ(v[2 + 2 * k], z[k]) << c.signal << " at " << c.shaft << ", z " << k;
    }
  }
}

// RMS, peak, crest factor and kurtosis of a recorded channel, written out here (independent
// of tools/report/signal_statistics.cc): about the mean, kurtosis not in excess.
std::vector<double> ChannelStatistics(const Recording& rec, std::size_t block, std::size_t c) {
  const auto x = rec.block(block).channel(c);
  double mean = 0.0;
  for (const float v : x) mean += v;
  mean /= static_cast<double>(x.size());
  double m2 = 0.0;
  double m4 = 0.0;
  double peak = 0.0;
  for (const float v : x) {
    const double d = v - mean;
    m2 += d * d;
    m4 += d * d * d * d;
    peak = std::max(peak, std::abs(d));
  }
  m2 /= static_cast<double>(x.size());
  m4 /= static_cast<double>(x.size());
  return {std::sqrt(m2), peak, peak / std::sqrt(m2), m4 / (m2 * m2)};
}

TEST(ReportCommandTest, StatisticsOfEveryChannelAndTheBlockTimeInUtc) {
  const Fixture& f = Shared();
  const fs::path out = f.dir / "statistics.html";
  ASSERT_EQ(RunTool(ReportArgs(f, "--block " + std::to_string(kReportedBlock), out), f.dir).code,
            0);
  const std::string html = ReadText(out);
  auto rec = ReadRecording(f.recording);
  ASSERT_TRUE(rec.ok()) << rec.error();
  for (std::size_t c = 0; c < rec->layout.channels.size(); ++c) {
    const ChannelInfo& ch = rec->layout.channels[c];
    const std::vector<double> v = RowValues(
        html, fmt::format("<tr data-statistics=\"{} {}\">", ch.sensor, AxisName(ch.axis)));
    const std::vector<double> truth = ChannelStatistics(rec.value(), kReportedBlock, c);
    ASSERT_EQ(v.size(), 4u) << ch.sensor;
    for (std::size_t k = 0; k < 4; ++k) EXPECT_NEAR(v[k], truth[k], 1e-9 * truth[k]) << k;
  }
  // The faulty blocks continue the healthy ones in time from t0 = 0: block 7 starts at
  // 7 x 8192 / 8000 s = 7.168 s.
  EXPECT_NE(html.find(">1970-01-01T00:00:07.168Z<"), std::string::npos);
}

TEST(ReportCommandTest, MeshZoomsContributionSpectraAndSynchronousAverages) {
  const Fixture& f = Shared();
  const fs::path out = f.dir / "signals.html";
  ASSERT_EQ(RunTool(ReportArgs(f, "--block " + std::to_string(kReportedBlock), out), f.dir).code,
            0);
  const std::string html = ReadText(out);
  const BlockResult& truth = f.results[kReportedBlock];
  // Table 1: G1 (28 teeth, input) - G2, G3 (34 teeth, intermediate) - G4.
  ASSERT_EQ(truth.shafts.size(), 3u);
  const double input = truth.shafts[0].characteristic_hz;
  const double inter = truth.shafts[1].characteristic_hz;
  EXPECT_EQ(Count(html, "<svg xmlns=\"http://www.w3.org/2000/svg\" class=\"mesh-zoom\""), 2u);
  EXPECT_EQ(Count(html, fmt::format("class=\"mesh-cursor\" data-hz=\"{}\"", 28 * input)), 1u);
  EXPECT_EQ(Count(html, fmt::format("class=\"mesh-cursor\" data-hz=\"{}\"", 34 * inter)), 1u);
  EXPECT_EQ(Count(html, fmt::format("data-shaft=\"input\" data-order=\"-2\" data-hz=\"{}\"",
                                    28 * input - 2 * input)),
            1u);
  // The simulated mesh tone is the largest line near the mesh frequency.
  const std::string peak_key = "class=\"spectrum-peak\" data-hz=\"";
  const auto peak = html.find(peak_key);
  ASSERT_NE(peak, std::string::npos);
  const double peak_hz = std::strtod(html.c_str() + peak + peak_key.size(), nullptr);
  EXPECT_NEAR(peak_hz, 28 * input, 1.5 * kFs / kBlock);
  // One contribution line per path, plus the measured spectrum and the sum.
  EXPECT_EQ(Count(html, "<path class=\"spectrum-line\""), 2 + truth.paths.size() + 2);
  // One identified force spectrum per path, each with its largest line in the analysis band.
  EXPECT_EQ(Count(html, "class=\"spectrum-line force-line\""), truth.paths.size());
  for (const BlockPathShare& p : truth.paths) {
    const std::string key = fmt::format("class=\"force-peak\" data-path=\"{}\" data-hz=\"", p.name);
    const auto at = html.find(key);
    ASSERT_NE(at, std::string::npos) << p.name;
    const double hz = std::strtod(html.c_str() + at + key.size(), nullptr);
    EXPECT_GE(hz, truth.analysis_band_lo_hz) << p.name;
    EXPECT_LE(hz, truth.analysis_band_hi_hz) << p.name;
  }
  // One average per distinct shaft rate (intermediate and output turn at 7 Hz).
  EXPECT_EQ(Count(html, "class=\"synchronous-average\""), 2u);
  EXPECT_EQ(Count(html, "<path class=\"waveform\" data-samples=\"8192\""), 2u);
}

TEST(ReportCommandTest, SpanReportAddsOneTrendRowPerBlock) {
  const Fixture& f = Shared();
  const fs::path out = f.dir / "span.html";
  const ToolRun r = RunTool(ReportArgs(f, "--span 4:8", out), f.dir);
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string html = ReadText(out);
  EXPECT_EQ(Count(html, "<tr data-block=\""), 5u);
  for (int b = 4; b <= 8; ++b) {
    const std::vector<double> v = RowValues(html, fmt::format("<tr data-block=\"{}\">", b));
    ASSERT_EQ(v.size(), 6u);
    EXPECT_EQ(v[1], f.results[static_cast<std::size_t>(b)].shafts[0].reconstructed);
  }
  EXPECT_EQ(Count(html, "<polyline class=\"trend-reconstructed\""), 3u);
  // Blocks 4 and 5 are still learning (baseline of 6): the bands start at block 6.
  EXPECT_EQ(Count(html, "<rect class=\"score-band-alarm\" data-from=\"6\" data-to=\"8\""), 1u);
  EXPECT_EQ(Count(html, "<rect class=\"score-band-alarm\""), 1u);
  EXPECT_NE(html.find("first block at 1970-01-01T00:00:04.096Z"), std::string::npos);
  if (HavePython()) {
    EXPECT_EQ(ParseXml(out), 0);
  }
}

TEST(ReportCommandTest, FrfSetDirectoryGivesTheSameNumbersAsTheBuiltinSet) {
  const Fixture& f = Shared();
  const fs::path set_dir = f.dir / "frf";
  if (!fs::exists(set_dir)) {
    ASSERT_TRUE(WriteFrfSet(f.setup.frf_set, set_dir).ok());
  }
  const fs::path out = f.dir / "frf.html";
  const ToolRun r =
      RunTool("report --frf-set " + set_dir.string() + " --train table1 " + "--recording " +
                  f.recording.string() + " --block " + std::to_string(kReportedBlock) +
                  " --baseline-blocks " + std::to_string(kHealthyBlocks) + " -o " + out.string(),
              f.dir);
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string html = ReadText(out);
  const BlockResult& truth = f.results[kReportedBlock];
  for (const BlockShaftIndicator& sh : truth.shafts) {
    const std::vector<double> v =
        RowValues(html, "<tr data-shaft=\"" + std::string(sh.shaft) + "\">");
    ASSERT_EQ(v.size(), 6u);
    EXPECT_EQ(v[3], sh.reconstructed);
  }
  const ToolRun missing =
      RunTool("report --frf-set " + (f.dir / "no_set").string() + " --recording " +
                  f.recording.string() + " --block 0 -o " + (f.dir / "x.html").string(),
              f.dir);
  EXPECT_EQ(missing.code, 2);
  EXPECT_NE(missing.err.find((f.dir / "no_set").string()), std::string::npos) << missing.err;
}

TEST(ReportCommandTest, RejectsMissingRecording) {
  const Fixture& f = Shared();
  const ToolRun r = RunTool("report --builtin table1 --recording " + (f.dir / "nope").string() +
                                " --block 0 -o " + (f.dir / "x.html").string(),
                            f.dir);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("recording '" + (f.dir / "nope").string() +
                       "' does not exist or is not a directory"),
            std::string::npos)
      << r.err;
}

TEST(ReportCommandTest, RejectsBlockOutOfRange) {
  const Fixture& f = Shared();
  const ToolRun r = RunTool(ReportArgs(f, "--block 9", f.dir / "x.html"), f.dir);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--block 9 is out of range: the recording holds 9 blocks (0..8)"),
            std::string::npos)
      << r.err;
  const ToolRun s = RunTool(ReportArgs(f, "--span 3:12", f.dir / "x.html"), f.dir);
  EXPECT_EQ(s.code, 2);
  EXPECT_NE(s.err.find("--span 3:12: block 12 is out of range"), std::string::npos) << s.err;
  const ToolRun t = RunTool(ReportArgs(f, "--span 5-6", f.dir / "x.html"), f.dir);
  EXPECT_EQ(t.code, 2);
  EXPECT_NE(t.err.find("--span '5-6' is not START:END"), std::string::npos) << t.err;
}

TEST(ReportCommandTest, RejectsUnknownMachine) {
  const Fixture& f = Shared();
  const ToolRun r = RunTool("report --builtin table9 --recording " + f.recording.string() +
                                " --block 0 -o " + (f.dir / "x.html").string(),
                            f.dir);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("unknown built-in machine 'table9' (known: table1)"), std::string::npos)
      << r.err;
  EXPECT_FALSE(fs::exists(f.dir / "x.html"));
}

TEST(ReportCommandTest, RejectsThresholdListsOfTheWrongLength) {
  const Fixture& f = Shared();
  const ToolRun r = RunTool(ReportArgs(f,
                                       "--block 0 --raw-thresholds 1,2 "
                                       "--reconstructed-thresholds 1,2",
                                       f.dir / "x.html"),
                            f.dir);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("thresholds"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace gearpath
