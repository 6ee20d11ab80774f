// MachineSetup from configuration: FRF source, channel and path mapping, options; errors name
// the configuration key.
#include "daemon/machine_setup_builder.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>

#include "core/io/frf_set_io.h"

namespace gearpath::daemon {
namespace {

using nlohmann::json;

// A small valid decoupled set: 2 housing channels (A1x, A2x) x 3 paths (B1x, B2x, B3x).
FrfSet SmallSet() {
  FrfSet set;
  set.description = "test";
  set.decoupling = "model";
  set.paths = {{"B1x", "B1", "x", {"G1"}}, {"B2x", "B2", "x", {"G2", "G3"}},
               {"B3x", "B3", "x", {"G4"}}};
  set.channels = {{"A1", "x"}, {"A2", "x"}};
  const int bins = 8;
  set.decoupled.frequency_hz = Eigen::VectorXd::LinSpaced(bins, 10.0, 80.0);
  for (int k = 0; k < bins; ++k) {
    set.decoupled.at.push_back(Eigen::MatrixXcd::Constant(2, 3, Complex(1.0 + k, 0.5)));
  }
  return set;
}

class MachineSetupBuilder : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("gearpathd_setup_" + std::to_string(getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    ASSERT_TRUE(WriteFrfSet(SmallSet(), dir_).ok());
    config_ = json::parse(DefaultConfigText());
    config_["machines"][0]["frf_set"] = dir_.string();
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  Result<MachineSetup> Build() {
    auto parsed = ParseDaemonConfig(config_.dump(), "test.json");
    if (!parsed) return Error{"config: " + parsed.error()};
    return BuildMachineSetup(parsed->machines[0]);
  }

  std::filesystem::path dir_;
  json config_;
};

TEST_F(MachineSetupBuilder, TranslatesTheConfiguredOptionsAndTrain) {
  json& a = config_["machines"][0]["analysis"];
  a["inverse"]["method"] = "tikhonov";
  a["inverse"]["alpha_rule"] = "fixed";
  a["inverse"]["alpha"] = 0.25;
  a["inverse"]["iterations"] = 7;
  a["dominant_path"]["criterion"] = "indicator";
  a["baseline"]["raw_thresholds"] = json::array({1.0, 2.0, 3.0});
  a["baseline"]["operating_bands"] = 4;
  auto setup = Build();
  ASSERT_TRUE(setup.ok()) << setup.error();
  const AnalysisOptions& o = setup->options;
  EXPECT_EQ(o.identification.method, InverseMethod::kTikhonov);
  EXPECT_EQ(o.identification.regularisation.rule, RegularisationRule::kFixed);
  EXPECT_EQ(o.identification.regularisation.parameter, 0.25);
  EXPECT_EQ(o.identification.iterations, 7);
  EXPECT_EQ(o.criterion, AnalysisOptions::DominantCriterion::kIndicator);
  EXPECT_EQ(o.raw_thresholds, (std::vector<double>{1.0, 2.0, 3.0}));
  EXPECT_EQ(o.operating_bands, 4);
  EXPECT_EQ(o.sample_rate_hz, 8000.0);
  EXPECT_EQ(o.nominal_speed_hz, 10.0);
  EXPECT_EQ(setup->machine_id, "table1");
  // Table-1 train: G1 (input) -> G2 (intermediate); G3 (intermediate) -> G4 (output).
  ASSERT_EQ(setup->train.gears.size(), 4u);
  EXPECT_EQ(setup->train.gears[2].name, "G3");
  EXPECT_EQ(setup->train.gears[2].shaft, 1);
  ASSERT_EQ(setup->train.meshes.size(), 2u);
  EXPECT_EQ(setup->train.meshes[1].gear_a, 2);
  EXPECT_EQ(setup->train.meshes[1].gear_b, 3);
  auto ratios = ShaftRateRatios(setup->train);
  ASSERT_TRUE(ratios.ok()) << ratios.error();
  EXPECT_DOUBLE_EQ((*ratios)[1], 28.0 / 40.0);  // rate ratio = z_driver / z_driven
  EXPECT_DOUBLE_EQ((*ratios)[2], 28.0 / 40.0 * 34.0 / 34.0);
}

TEST_F(MachineSetupBuilder, AnExplicitFrfRowRelabelsThatRowWithTheBlockChannel) {
  config_["machines"][0]["channels"] = json::array(
      {{{"sensor", "S9"}, {"axis", "y"}, {"frf_row", 1}}, {{"sensor", "A1"}, {"axis", "x"}}});
  auto setup = Build();
  ASSERT_TRUE(setup.ok()) << setup.error();
  EXPECT_EQ(setup->frf_set.channels[1].sensor, "S9");
  EXPECT_EQ(setup->frf_set.channels[1].axis, "y");
  ASSERT_EQ(setup->block_channels.size(), 2u);
  EXPECT_EQ(setup->block_channels[0].sensor, "S9");
  EXPECT_EQ(setup->block_channels[0].axis, Axis::kY);
}

TEST_F(MachineSetupBuilder, PathOverridesReplaceTheGearsTheFrfSetNames) {
  config_["machines"][0]["paths"] = json::array({{{"name", "B2x"}, {"gears", {"G2"}}}});
  auto setup = Build();
  ASSERT_TRUE(setup.ok()) << setup.error();
  EXPECT_EQ(setup->frf_set.paths[1].gears, (std::vector<std::string>{"G2"}));
  EXPECT_EQ(setup->frf_set.paths[0].gears, (std::vector<std::string>{"G1"}));
}

TEST_F(MachineSetupBuilder, RejectsAPathTheFrfSetDoesNotHaveNamingTheKey) {
  config_["machines"][0]["paths"] = json::array({{{"name", "B9x"}, {"gears", {"G2"}}}});
  auto setup = Build();
  ASSERT_FALSE(setup.ok());
  EXPECT_EQ(setup.error(), "machines[0].paths[0].name: the FRF set has no path \"B9x\" (its "
                           "paths: B1x, B2x, B3x)");
}

TEST_F(MachineSetupBuilder, RejectsAnFrfRowBeyondTheSetNamingTheKey) {
  config_["machines"][0]["channels"] =
      json::array({{{"sensor", "A1"}, {"axis", "x"}, {"frf_row", 2}}});
  auto setup = Build();
  ASSERT_FALSE(setup.ok());
  EXPECT_EQ(setup.error(), "machines[0].channels[0].frf_row: row 2 is out of range (the FRF set "
                           "has 2 response channels)");
}

TEST_F(MachineSetupBuilder, RejectsAMissingFrfDirectoryNamingTheKey) {
  config_["machines"][0]["frf_set"] = (dir_ / "absent").string();
  auto setup = Build();
  ASSERT_FALSE(setup.ok());
  EXPECT_EQ(setup.error().rfind("machines[0].frf_set: ", 0), 0u) << setup.error();
  EXPECT_NE(setup.error().find("absent"), std::string::npos) << setup.error();
}

TEST_F(MachineSetupBuilder, AnIdentityFrfSetMakesEveryChannelAPathWithItsGearsOnTheBlockGrid) {
  json& m = config_["machines"][0];
  m["frf_set"] = "identity";
  m["acquisition"]["min_samples_per_channel"] = 1024;
  m["acquisition"]["max_samples_per_channel"] = 8192;
  m["channels"] = json::array({{{"sensor", "A1"}, {"axis", "x"}, {"gears", {"G1", "G2"}}},
                               {{"sensor", "A2"}, {"axis", "z"}, {"gears", {"G3", "G4"}}}});
  auto setup = Build();
  ASSERT_TRUE(setup.ok()) << setup.error();
  const FrfSet& set = setup->frf_set;
  EXPECT_EQ(set.decoupling, "identity");
  ASSERT_EQ(set.paths.size(), 2u);
  EXPECT_EQ(set.paths[0].name, "A1/x");
  EXPECT_EQ(set.paths[1].name, "A2/z");
  EXPECT_EQ(set.paths[1].gears, (std::vector<std::string>{"G3", "G4"}));
  ASSERT_EQ(setup->block_channels.size(), 2u);
  EXPECT_EQ(setup->block_channels[1].sensor, "A2");
  // Grid: the first bin of the longest block, then the shortest block's bins up to fs / 2.
  const Eigen::VectorXd& f = set.decoupled.frequency_hz;
  ASSERT_EQ(f.size(), 1 + 512);
  EXPECT_DOUBLE_EQ(f[0], 8000.0 / 8192);
  EXPECT_DOUBLE_EQ(f[1], 8000.0 / 1024);
  EXPECT_DOUBLE_EQ(f[f.size() - 1], 4000.0);
  EXPECT_TRUE(set.decoupled.at[7].isIdentity());
}

TEST_F(MachineSetupBuilder, AnIdentityFrfSetIsNotLookedForOnDisk) {
  // "identity" is a keyword, not a directory: no file is read, so none has to exist.
  config_["machines"][0]["frf_set"] = "identity";
  config_["machines"][0]["channels"] =
      json::array({{{"sensor", "A1"}, {"axis", "x"}, {"gears", {"G1"}}}});
  auto setup = Build();
  ASSERT_TRUE(setup.ok()) << setup.error();
  EXPECT_EQ(setup->frf_set.paths.size(), 1u);
}

}  // namespace
}  // namespace gearpath::daemon
