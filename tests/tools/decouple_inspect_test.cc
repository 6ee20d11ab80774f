// `gearpath decouple` and `gearpath inspect` on a lumped mass-spring gearbox whose housing FRFs
// are known exactly: a two-mass rotor (a1, a2) on two bearings (springs + dampers a1-p1, a2-p2)
// in a four-mass housing (p1, p2 at the bearings, m1, m2 elsewhere). Virtual decoupling of the
// assembled FRFs must give the FRFs of the housing alone (seed Eqs. 22 and 24 are exact on such
// a model), computed here independently by inverting the housing's own dynamic stiffness.
#include <gtest/gtest.h>
#include <unistd.h>

#include <Eigen/Dense>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "core/frf/frf_set.h"
#include "core/io/frf_set_io.h"
#include "core/io/recording.h"
#include "core/io/uff58.h"
#include "tests/tools/tool_process.h"

namespace gearpath::tools {
namespace {

namespace fs = std::filesystem;
using testing::RunTool;

constexpr int kA1 = 0, kA2 = 1, kP1 = 2, kP2 = 3, kM1 = 4, kM2 = 5;
constexpr double kPi = 3.14159265358979323846;

struct Model {
  Eigen::VectorXd f;
  std::vector<Eigen::MatrixXcd> assembled;  // 6 x 6 receptance, DOF order a1 a2 p1 p2 m1 m2
  std::vector<Eigen::MatrixXcd> housing;    // 4 x 4 receptance of the housing alone: p1 p2 m1 m2
};

void AddSpring(Eigen::MatrixXcd& z, int i, int j, std::complex<double> k) {
  z(i, i) += k;
  if (j >= 0) {
    z(j, j) += k;
    z(i, j) -= k;
    z(j, i) -= k;
  }
}

Model MakeModel() {
  Model m;
  m.f = Eigen::VectorXd::LinSpaced(50, 10.0, 500.0);
  const double mass[6] = {2.0, 1.5, 5.0, 4.0, 3.0, 3.5};
  for (Eigen::Index k = 0; k < m.f.size(); ++k) {
    const double w = 2 * kPi * m.f[k];
    const std::complex<double> jw(0.0, w);
    auto housing_springs = [&](Eigen::MatrixXcd& z, int off) {  // off: index shift of p1
      auto s = [&](double stiffness) { return stiffness * (1.0 + 1e-4 * jw); };
      AddSpring(z, kP1 - off, kM1 - off, s(3e5));
      AddSpring(z, kM1 - off, kM2 - off, s(2.5e5));
      AddSpring(z, kM2 - off, kP2 - off, s(3.5e5));
      AddSpring(z, kP1 - off, -1, s(1e6));
      AddSpring(z, kP2 - off, -1, s(8e5));
    };
    Eigen::MatrixXcd z = Eigen::MatrixXcd::Zero(6, 6);
    for (int i = 0; i < 6; ++i) z(i, i) -= w * w * mass[i];
    AddSpring(z, kA1, kA2, 2e5);
    AddSpring(z, kA1, kP1, 5e5 + 50.0 * jw);
    AddSpring(z, kA2, kP2, 4e5 + 40.0 * jw);
    housing_springs(z, 0);
    m.assembled.push_back(z.inverse());
    Eigen::MatrixXcd zh = Eigen::MatrixXcd::Zero(4, 4);
    for (int i = 0; i < 4; ++i) zh(i, i) -= w * w * mass[i + 2];
    housing_springs(zh, 2);
    m.housing.push_back(zh.inverse());
  }
  return m;
}

std::vector<Eigen::MatrixXcd> Block(const std::vector<Eigen::MatrixXcd>& h, std::vector<int> rows,
                                    std::vector<int> cols) {
  std::vector<Eigen::MatrixXcd> out;
  for (const auto& mk : h) {
    Eigen::MatrixXcd b(rows.size(), cols.size());
    for (std::size_t r = 0; r < rows.size(); ++r) {
      for (std::size_t c = 0; c < cols.size(); ++c) b(r, c) = mk(rows[r], cols[c]);
    }
    out.push_back(b);
  }
  return out;
}

FrfSet CoupledModelSet(const Model& m, bool with_m) {
  FrfSet set;
  set.description = "lumped test gearbox";
  set.quantity = FrfQuantity::kReceptance;
  set.unit = "m/N";
  CoupledSet c;
  c.active = {{"a1", "a1", "x"}, {"a2", "a2", "x"}};
  c.passive = {{"p1", "p1", "x"}, {"p2", "p2", "x"}};
  c.blocks.frequency_hz = m.f;
  c.blocks.aa = Block(m.assembled, {kA1, kA2}, {kA1, kA2});
  c.blocks.pa = Block(m.assembled, {kP1, kP2}, {kA1, kA2});
  c.blocks.pp = Block(m.assembled, {kP1, kP2}, {kP1, kP2});
  c.blocks.ap = Block(m.assembled, {kA1, kA2}, {kP1, kP2});
  if (with_m) {
    c.measurement = {{"m1", "m1", "x"}, {"m2", "m2", "x"}};
    c.blocks.ma = Block(m.assembled, {kM1, kM2}, {kA1, kA2});
    c.blocks.mp = Block(m.assembled, {kM1, kM2}, {kP1, kP2});
  }
  set.coupled = c;
  return set;
}

double MaxRelativeError(const FrfMatrix& got, const std::vector<Eigen::MatrixXcd>& want) {
  double worst = 0;
  for (std::size_t k = 0; k < want.size(); ++k) {
    worst = std::max(worst, (got.at[k] - want[k]).norm() / want[k].norm());
  }
  return worst;
}

// Eq. 25 over whole rows, written out here independently of core/frf/frac.
double RowFrac(const std::vector<Eigen::MatrixXcd>& h, int ra, int rb) {
  std::complex<double> cross = 0;
  double ea = 0, eb = 0;
  for (const auto& mk : h) {
    cross += (mk.row(ra).conjugate().array() * mk.row(rb).array()).sum();
    ea += mk.row(ra).squaredNorm();
    eb += mk.row(rb).squaredNorm();
  }
  return std::norm(cross) / (ea * eb);
}

class DecoupleInspect : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("gearpath_tools_test_" + std::to_string(getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    model_ = MakeModel();
  }
  void TearDown() override {
    if (!HasFailure()) fs::remove_all(dir_);
  }
  fs::path dir_;
  Model model_;
};

// The numbers printed on the line that starts with `label`.
std::vector<double> NumbersOnLine(const std::string& text, const std::string& label) {
  std::istringstream in(text);
  std::string line;
  std::vector<double> out;
  while (std::getline(in, line)) {
    if (line.rfind(label, 0) != 0) continue;
    std::istringstream fields(line.substr(label.size()));
    double v;
    while (fields >> v) out.push_back(v);
  }
  return out;
}

TEST_F(DecoupleInspect, Eq24GivesTheHousingAloneAndPrintsTheFracTable) {
  ASSERT_TRUE(WriteFrfSet(CoupledModelSet(model_, true), dir_ / "coupled").ok());
  FrfSet ref;
  ref.quantity = FrfQuantity::kReceptance;
  ref.unit = "m/N";
  ref.decoupling = "physical";
  ref.paths = {{"p1", "b1", "x", {}}, {"p2", "b2", "x", {}}};
  ref.channels = {{"m1", "x"}, {"m2", "x"}};
  ref.decoupled.frequency_hz = model_.f;
  ref.decoupled.at = Block(model_.housing, {2, 3}, {0, 1});
  ASSERT_TRUE(WriteFrfSet(ref, dir_ / "ref").ok());

  std::string out, err;
  ASSERT_EQ(
      RunTool({"decouple", (dir_ / "coupled").string(), "--at", "m", "--out",
               (dir_ / "dec").string(), "--reference", (dir_ / "ref").string(), "--pair", "m1=m2"},
              dir_, "decouple", &out, &err),
      0)
      << err;
  EXPECT_NE(out.find("condition number of (H_pa - H_aa): worst"), std::string::npos) << out;
  EXPECT_NE(out.find("m1/real value"), std::string::npos) << out;
  EXPECT_NE(out.find("m1/m2"), std::string::npos) << out;
  const std::vector<double> frac = NumbersOnLine(out, "FRAC(H_d,mp)");
  ASSERT_EQ(frac.size(), 3u) << out;
  EXPECT_NEAR(frac[0], 1.0, 1e-5);
  EXPECT_NEAR(frac[1], 1.0, 1e-5);
  EXPECT_NEAR(frac[2], RowFrac(Block(model_.housing, {2, 3}, {0, 1}), 0, 1), 1e-5);
  EXPECT_LT(frac[2], 0.999);  // the two points really differ, so the check can fail

  Result<FrfSet> dec = ReadFrfSet(dir_ / "dec");
  ASSERT_TRUE(dec.ok()) << dec.error();
  EXPECT_EQ(dec->decoupling, "eq24");
  ASSERT_EQ(dec->decoupled.outputs(), 2);
  EXPECT_LT(MaxRelativeError(dec->decoupled, Block(model_.housing, {2, 3}, {0, 1})), 1e-8);
}

TEST_F(DecoupleInspect, Eq22FromUffFrfsWithADofMapGivesTheHousingAlone) {
  // Only the blocks Eq. 22 needs; H_ap by reciprocity.
  const int node[6] = {11, 12, 21, 22, 31, 32};
  std::vector<Uff58Record> records;
  for (int r : {kA1, kA2, kP1, kP2}) {
    for (int c : {kA1, kA2, kP1, kP2}) {
      if (r < kP1 && c >= kP1) continue;  // no H_ap
      Uff58Record rec;
      rec.function_type = kUffFrequencyResponse;
      rec.response_node = node[r];
      rec.response_direction = 1;
      rec.reference_node = node[c];
      rec.reference_direction = 1;
      rec.abscissa_start = 10.0;
      rec.abscissa_increment = 10.0;
      for (const auto& mk : model_.assembled) rec.ordinate.push_back(mk(r, c));
      records.push_back(rec);
    }
  }
  ASSERT_TRUE(WriteUff58(dir_ / "frf.unv", records, UffEncoding::kBinary).ok());
  std::string out, err;
  ASSERT_EQ(RunTool({"decouple", (dir_ / "frf.unv").string(), "--at", "p", "--dof", "a1=11:x:a",
                     "--dof", "a2=12:x:a", "--dof", "p1=21:x:p", "--dof", "p2=22:x:p", "--out",
                     (dir_ / "dec").string()},
                    dir_, "decouple", &out, &err),
            0)
      << err;
  Result<FrfSet> dec = ReadFrfSet(dir_ / "dec");
  ASSERT_TRUE(dec.ok()) << dec.error();
  EXPECT_EQ(dec->decoupling, "eq22");
  EXPECT_EQ(dec->paths[1].name, "p2");
  EXPECT_LT(MaxRelativeError(dec->decoupled, Block(model_.housing, {0, 1}, {0, 1})), 1e-8);
}

TEST_F(DecoupleInspect, DecoupleRejectsBadInputWithExitCode2) {
  std::string err;
  EXPECT_EQ(RunTool({"decouple", (dir_ / "none").string(), "--at", "p"}, dir_, "d1", nullptr, &err),
            2);
  EXPECT_NE(err.find("no such file or directory"), std::string::npos) << err;

  ASSERT_TRUE(WriteFrfSet(CoupledModelSet(model_, false), dir_ / "no_m").ok());
  EXPECT_EQ(RunTool({"decouple", (dir_ / "no_m").string(), "--at", "m"}, dir_, "d2", nullptr, &err),
            2);
  EXPECT_NE(err.find("--at m (Eq. 24) needs measurement DOFs"), std::string::npos) << err;

  EXPECT_EQ(RunTool({"decouple", (dir_ / "no_m").string(), "--at", "p", "--pair", "p9=p1"}, dir_,
                    "d3", nullptr, &err),
            2);
  EXPECT_NE(err.find("no row \"p9\" in the result (rows: p1, p2)"), std::string::npos) << err;

  std::ofstream(dir_ / "frf.unv") << "    -1\n    58\n";
  EXPECT_EQ(
      RunTool({"decouple", (dir_ / "frf.unv").string(), "--at", "p"}, dir_, "d4", nullptr, &err),
      2);
  EXPECT_NE(err.find("a UFF input needs the DOF roles"), std::string::npos) << err;

  FrfSet only_decoupled;
  only_decoupled.quantity = FrfQuantity::kReceptance;
  only_decoupled.unit = "m/N";
  only_decoupled.decoupling = "model";
  only_decoupled.paths = {{"p1", "b1", "x", {}}};
  only_decoupled.channels = {{"m1", "x"}};
  only_decoupled.decoupled.frequency_hz = model_.f;
  only_decoupled.decoupled.at = Block(model_.housing, {2}, {0});
  ASSERT_TRUE(WriteFrfSet(only_decoupled, dir_ / "dec_only").ok());
  EXPECT_EQ(
      RunTool({"decouple", (dir_ / "dec_only").string(), "--at", "p"}, dir_, "d5", nullptr, &err),
      2);
  EXPECT_NE(err.find("has no \"coupled\" part"), std::string::npos) << err;
}

TEST_F(DecoupleInspect, DecoupleFailsWithExitCode1WhenABinIsTooIllConditioned) {
  ASSERT_TRUE(WriteFrfSet(CoupledModelSet(model_, false), dir_ / "coupled").ok());
  std::string err;
  // Every condition number is >= 1, so a limit of 1 rejects the first bin.
  EXPECT_EQ(RunTool({"decouple", (dir_ / "coupled").string(), "--at", "p", "--max-condition",
                     "1"},
                    dir_, "decouple", nullptr, &err),
            1);
  EXPECT_NE(err.find("Hz"), std::string::npos) << err;
  EXPECT_FALSE(fs::exists(dir_ / "dec"));
}

TEST_F(DecoupleInspect, InspectDescribesACoupledSetWithItsChecks) {
  ASSERT_TRUE(WriteFrfSet(CoupledModelSet(model_, true), dir_ / "coupled").ok());
  std::string out, err;
  ASSERT_EQ(
      RunTool({"inspect", (dir_ / "coupled").string(), "--json"}, dir_, "inspect", &out, &err), 0)
      << err;
  const auto j = nlohmann::json::parse(out);
  EXPECT_EQ(j["kind"], "frf-set");
  const auto& c = j["coupled"];
  EXPECT_EQ(c["dofs"]["a"], nlohmann::json({"a1", "a2"}));
  EXPECT_EQ(c["dofs"]["m"], nlohmann::json({"m1", "m2"}));
  EXPECT_EQ(c["frequency"]["bins"], 50);
  EXPECT_DOUBLE_EQ(c["frequency"]["min_hz"].get<double>(), 10.0);
  EXPECT_DOUBLE_EQ(c["frequency"]["max_hz"].get<double>(), 500.0);
  EXPECT_NEAR(c["frequency"]["resolution_hz"].get<double>(), 10.0, 1e-9);
  EXPECT_TRUE(c["checks"]["finite"].get<bool>());
  // A passive structure is reciprocal: H_ap = H_pa^T to rounding.
  EXPECT_LT(c["checks"]["reciprocity_ap_pa"]["max_relative_difference"].get<double>(), 1e-10);
  EXPECT_GE(c["condition_number_pa_minus_aa"]["worst"].get<double>(),
            c["condition_number_pa_minus_aa"]["median"].get<double>());
  EXPECT_GE(c["condition_number_pa_minus_aa"]["min"].get<double>(), 1.0);

  ASSERT_EQ(RunTool({"inspect", (dir_ / "coupled").string()}, dir_, "inspect_text", &out, &err), 0);
  EXPECT_NE(out.find("reciprocity_ap_pa"), std::string::npos) << out;
}

TEST_F(DecoupleInspect, InspectDescribesARecordingWithItsSequenceGaps) {
  Recording r;
  r.layout = {"gb", 1000.0, {{"A1", Axis::kX, "m/s^2", 0.0}}, 100};
  for (std::uint64_t seq : {5u, 6u, 9u}) {
    r.blocks.push_back(
        {seq, static_cast<std::int64_t>(seq) * 100000000, 20.0, SpeedSource::kUnknown});
  }
  r.samples.assign(300, 0.5f);
  r.samples[7] = std::nanf("");
  ASSERT_TRUE(WriteRecording(r, dir_ / "rec").ok());
  std::string out, err;
  ASSERT_EQ(RunTool({"inspect", (dir_ / "rec").string(), "--json"}, dir_, "inspect", &out, &err), 0)
      << err;
  const auto j = nlohmann::json::parse(out);
  EXPECT_EQ(j["kind"], "recording");
  EXPECT_EQ(j["blocks"], 3);
  EXPECT_DOUBLE_EQ(j["duration_s"].get<double>(), 0.3);
  EXPECT_EQ(j["sequence_gaps"], 1);
  EXPECT_EQ(j["missing_blocks"], 2);
  EXPECT_EQ(j["checks"]["non_finite_samples"], 1);
  EXPECT_FALSE(j.contains("load"));  // plain AccelBlocks: no load to show
}

TEST_F(DecoupleInspect, InspectShowsTheLoadRangeOfARecordingThatCarriesIt) {
  Recording r;
  r.layout = {"gb", 1000.0, {{"A1", Axis::kX, "m/s^2", 0.0}}, 10, "kW"};
  for (const double load : {55.0, 72.5, 61.0}) {
    r.blocks.push_back({r.blocks.size(), static_cast<std::int64_t>(r.blocks.size()) * 10000000,
                        20.0, SpeedSource::kAcquisition, load});
  }
  r.samples.assign(30, 0.25f);
  ASSERT_TRUE(WriteRecording(r, dir_ / "rec").ok());
  std::string out, err;
  ASSERT_EQ(RunTool({"inspect", (dir_ / "rec").string(), "--json"}, dir_, "inspect", &out, &err), 0)
      << err;
  const auto j = nlohmann::json::parse(out);
  EXPECT_EQ(j["load"], nlohmann::json::parse(R"({"min": 55.0, "max": 72.5, "unit": "kW"})")) << j;
}

// A machine state file as gearpathd wrote it (the fuzz seed, made by the daemon's own writer),
// given the epoch, alarm, ranges and counts of a machine after maintenance: inspect shows what
// the daemon would resume, and refuses a file the daemon would refuse, by key.
TEST_F(DecoupleInspect, InspectShowsWhatAMachineStateFileWouldResume) {
  std::ifstream seed(std::string(GEARPATH_SOURCE_DIR) +
                     "/tests/fuzz/corpus/fuzz_machine_state/learned.state.json");
  ASSERT_TRUE(seed.good());
  nlohmann::json state = nlohmann::json::parse(seed);
  state["machine_id"] = "gearbox-1";
  state["saved_at_ns"] = 1795000000000000000;
  state["counters"]["received"] = 1200;
  state["counters"]["not_judged"] = {{"load_outside", 5}};
  nlohmann::json& learned = state["learned"];
  learned["baseline_epoch"] = "2026-11-29 G1 replaced";
  learned["alarm"]["state"] = "alarm";
  learned["baseline_speed_hz"] = {7.5, 7.6};
  learned["baseline_load"] = {96.0, 104.0};
  learned["baseline_load_partial"] = false;
  // A second operating band, learned at 140-160 (the band in use's baseline, copied).
  nlohmann::json parked = {{"operating_band_id", 1},
                           {"indicator_baseline", learned["indicator_baseline"]},
                           {"residual_variance_healthy", learned["residual_variance_healthy"]},
                           {"criterion_healthy", learned["criterion_healthy"]},
                           {"baseline_speed_hz", {7.5, 7.6}},
                           {"baseline_load", {140.0, 160.0}},
                           {"baseline_load_partial", false}};
  learned["operating_bands"] = nlohmann::json::array({parked});
  std::ofstream(dir_ / "gearbox-1.state.json") << state.dump();
  std::string out, err;
  ASSERT_EQ(RunTool({"inspect", (dir_ / "gearbox-1.state.json").string(), "--json"}, dir_,
                    "inspect", &out, &err),
            0)
      << err;
  const auto j = nlohmann::json::parse(out);
  EXPECT_EQ(j["kind"], "machine-state");
  EXPECT_EQ(j["machine_id"], "gearbox-1");
  EXPECT_EQ(j["saved_at"], "2026-11-18T11:06:40.000Z");
  EXPECT_EQ(j["baseline_epoch"], "2026-11-29 G1 replaced");
  EXPECT_EQ(j["verdict_state"], "alarm");
  EXPECT_FALSE(j["baseline"]["learning"].get<bool>());
  EXPECT_EQ(j["baseline"]["blocks_learned"], j["baseline"]["blocks_needed"]);
  EXPECT_EQ(j["speed_range_hz"], nlohmann::json::parse("[7.5, 7.6]"));
  EXPECT_EQ(j["load_range"], nlohmann::json::parse("[96.0, 104.0]"));
  ASSERT_EQ(j["operating_bands"].size(), 2u) << j;
  EXPECT_TRUE(j["operating_bands"][0]["in_use"].get<bool>());
  EXPECT_EQ(j["operating_bands"][0]["load_range"], nlohmann::json::parse("[96.0, 104.0]"));
  EXPECT_EQ(j["operating_bands"][1]["id"], 1);
  EXPECT_FALSE(j["operating_bands"][1]["in_use"].get<bool>());
  EXPECT_FALSE(j["operating_bands"][1]["learning"].get<bool>());
  EXPECT_EQ(j["operating_bands"][1]["load_range"], nlohmann::json::parse("[140.0, 160.0]"));
  EXPECT_EQ(j["blocks"]["received"], 1200);
  EXPECT_EQ(j["blocks"]["not_judged"], nlohmann::json::parse(R"({"load_outside": 5})"));

  // Saved before the epoch was recorded: said so, not shown as an empty epoch.
  learned.erase("baseline_epoch");
  std::ofstream(dir_ / "old.state.json") << state.dump();
  ASSERT_EQ(
      RunTool({"inspect", (dir_ / "old.state.json").string(), "--json"}, dir_, "old", &out, &err),
      0)
      << err;
  EXPECT_EQ(nlohmann::json::parse(out)["baseline_epoch"], "(not recorded)");

  // What the daemon would refuse is refused, with the key.
  learned["baseline_epoch"] = "two\nlines";
  std::ofstream(dir_ / "bad.state.json") << state.dump();
  EXPECT_EQ(RunTool({"inspect", (dir_ / "bad.state.json").string()}, dir_, "bad", nullptr, &err),
            2);
  EXPECT_NE(err.find("baseline_epoch holds control character 0x0a"), std::string::npos) << err;
}

TEST_F(DecoupleInspect, InspectRejectsMissingAndUnknownInputs) {
  std::string err;
  EXPECT_EQ(RunTool({"inspect", (dir_ / "none").string()}, dir_, "i1", nullptr, &err), 2);
  EXPECT_NE(err.find("no such file or directory"), std::string::npos) << err;
  fs::create_directories(dir_ / "odd");
  std::ofstream(dir_ / "odd" / "manifest.json") << R"({"format": "something-else"})";
  EXPECT_EQ(RunTool({"inspect", (dir_ / "odd").string()}, dir_, "i2", nullptr, &err), 2);
  EXPECT_NE(err.find("unknown format \"something-else\""), std::string::npos) << err;
  std::ofstream(dir_ / "words.txt") << "no numbers here\n";
  EXPECT_EQ(RunTool({"inspect", (dir_ / "words.txt").string()}, dir_, "i3", nullptr, &err), 2);
  EXPECT_NE(err.find("no data rows were found"), std::string::npos) << err;
}

TEST_F(DecoupleInspect, InspectReportsATextExportsLayout) {
  std::ofstream(dir_ / "export.txt")
      << "Time;A1-X;A1-Y\ns;m/s^2;m/s^2\n0,0;1,5;2\n0,5;1;2\n1,0;1;2\n";
  std::string out, err;
  ASSERT_EQ(
      RunTool({"inspect", (dir_ / "export.txt").string(), "--json"}, dir_, "inspect", &out, &err),
      0)
      << err;
  const auto j = nlohmann::json::parse(out);
  EXPECT_EQ(j["layout"]["separator"], ";");
  EXPECT_TRUE(j["layout"]["decimal_comma"].get<bool>());
  EXPECT_TRUE(j["layout"]["time_column"].get<bool>());
  EXPECT_DOUBLE_EQ(j["sample_rate_hz"].get<double>(), 2.0);
  EXPECT_EQ(j["channels"].size(), 2u);
}

TEST_F(DecoupleInspect, DecoupleAndInspectHaveHelp) {
  for (const auto& [cmd, option] :
       {std::pair{"decouple", "--at"}, std::pair{"inspect", "--json"}}) {
    std::string out;
    EXPECT_EQ(RunTool({cmd, "--help"}, dir_, std::string("help_") + cmd, &out), 0) << cmd;
    EXPECT_NE(out.find(option), std::string::npos) << out;
  }
}

}  // namespace
}  // namespace gearpath::tools
