// gearpathd's command line: --check-config exit codes and messages, --version, bad options.
// Runs the real binary as a child process (no DDS: --check-config never creates a domain).
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "daemon/daemon_config.h"
#include "tests/daemon/child_process.h"

namespace gearpath::daemon {
namespace {

using nlohmann::json;
using std::chrono::seconds;
using testing::RunToCompletion;

class GearpathdCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("gearpathd_cli_" + std::to_string(getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  std::string WriteConfig(const json& config) {
    const std::string path = (dir_ / "gearpathd.json").string();
    std::ofstream(path) << config.dump(2);
    return path;
  }

  // Runs gearpathd with `args`; returns its exit code (-100 on timeout) and fills `output`.
  int Run(const std::vector<std::string>& args, std::string* output) {
    auto code = RunToCompletion(GEARPATHD_PATH, args, (dir_ / "out.log").string(), output,
                                seconds(60));
    return code.value_or(-100);
  }

  std::filesystem::path dir_;
};

TEST_F(GearpathdCli, CheckConfigAcceptsTheEmbeddedDefaultAndBuildsItsMachine) {
  std::string out;
  EXPECT_EQ(Run({"--check-config"}, &out), 0) << out;
  EXPECT_NE(out.find("<embedded default>: configuration valid, 1 machine(s) built"),
            std::string::npos)
      << out;
  EXPECT_NE(out.find("machine table1: FRF"), std::string::npos) << out;
}

TEST_F(GearpathdCli, CheckConfigAcceptsTheShippedConfigFile) {
  std::string out;
  EXPECT_EQ(Run({"--check-config", "--config", GEARPATH_SOURCE_DIR "/config/gearpathd.json"},
                &out),
            0)
      << out;
}

TEST_F(GearpathdCli, CheckConfigRejectsAnInvalidValueWithExitCode2NamingTheKey) {
  json c = json::parse(DefaultConfigText());
  c["machines"][0]["analysis"]["inverse"]["method"] = "mwii";
  std::string out;
  EXPECT_EQ(Run({"--check-config", "--config", WriteConfig(c)}, &out), 2) << out;
  EXPECT_NE(out.find("machines[0].analysis.inverse.method: expected one of mwi, tikhonov, "
                     "least_squares, got \"mwii\""),
            std::string::npos)
      << out;
}

TEST_F(GearpathdCli, CheckConfigRejectsAMissingFrfSetDirectoryNamingTheKey) {
  json c = json::parse(DefaultConfigText());
  c["machines"][0]["frf_set"] = (dir_ / "no_such_set").string();
  std::string out;
  EXPECT_EQ(Run({"--check-config", "--config", WriteConfig(c)}, &out), 2) << out;
  EXPECT_NE(out.find("machines[0].frf_set: "), std::string::npos) << out;
}

TEST_F(GearpathdCli, CheckConfigRejectsMalformedJsonWithExitCode2NamingTheFile) {
  const std::string path = (dir_ / "broken.json").string();
  std::ofstream(path) << "{\"daemon\": ";
  std::string out;
  EXPECT_EQ(Run({"--check-config", "--config", path}, &out), 2) << out;
  EXPECT_NE(out.find(path + ": not valid JSON"), std::string::npos) << out;
}

TEST_F(GearpathdCli, RejectsAMissingConfigFileAndAnUnknownOptionWithExitCode2) {
  std::string out;
  EXPECT_EQ(Run({"--config", (dir_ / "absent.json").string()}, &out), 2) << out;
  EXPECT_EQ(Run({"--frobnicate"}, &out), 2) << out;
  EXPECT_EQ(Run({"--log-level", "loud"}, &out), 2) << out;
}

TEST_F(GearpathdCli, VersionPrintsTheProjectVersionAndExitsZero) {
  std::string out;
  EXPECT_EQ(Run({"--version"}, &out), 0);
  EXPECT_EQ(out.rfind("gearpathd ", 0), 0u) << out;
}

TEST_F(GearpathdCli, PrintDefaultConfigPrintsTheShippedFile) {
  std::string out;
  EXPECT_EQ(Run({"--print-default-config"}, &out), 0);
  std::ifstream in(GEARPATH_SOURCE_DIR "/config/gearpathd.json");
  std::ostringstream file;
  file << in.rdbuf();
  EXPECT_EQ(out, file.str());
}

}  // namespace
}  // namespace gearpath::daemon
