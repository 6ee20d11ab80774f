// gearpathd --check-config (and so the systemd unit's ExecStartPre) checks the files the dds
// section names: a missing dds.config file or DDS Security file is an invalid configuration
// (exit 2) naming the key and the file. No DDS: --check-config never creates a domain.
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

class GearpathdDdsFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("gearpathd_dds_files_" + std::to_string(getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::create_directories(dir_);
    config_ = json::parse(DefaultConfigText());
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  std::string File(const std::string& name, const std::string& content) {
    const std::string path = (dir_ / name).string();
    std::ofstream(path) << content;
    return path;
  }

  int CheckConfig(std::string* output) {
    const std::string path = File("gearpathd.json", config_.dump(2));
    return RunToCompletion(GEARPATHD_PATH, {"--check-config", "--config", path},
                           (dir_ / "out.log").string(), output, seconds(60))
        .value_or(-100);
  }

  std::filesystem::path dir_;
  json config_;
};

TEST_F(GearpathdDdsFiles, ReadableDeploymentAndSecurityFilesPassTheCheck) {
  config_["dds"]["config"] = File("cyclonedds.xml", "<CycloneDDS/>");
  for (const char* key : {"identity_ca", "identity_certificate", "identity_private_key",
                          "permissions_ca", "governance", "permissions"}) {
    config_["dds"]["security"][key] = File(std::string(key) + ".pem", "x");
  }
  std::string out;
  EXPECT_EQ(CheckConfig(&out), 0) << out;
}

TEST_F(GearpathdDdsFiles, AMissingDeploymentFileOrSecurityFileIsAnInvalidConfiguration) {
  config_["dds"]["config"] = (dir_ / "no-such.xml").string();
  for (const char* key : {"identity_ca", "identity_certificate", "identity_private_key",
                          "permissions_ca", "governance", "permissions"}) {
    config_["dds"]["security"][key] = File(std::string(key) + ".pem", "x");
  }
  config_["dds"]["security"]["identity_private_key"] = (dir_ / "no-such.key").string();
  std::string out;
  EXPECT_EQ(CheckConfig(&out), 2) << out;
  EXPECT_NE(out.find("dds.config: " + (dir_ / "no-such.xml").string() + ": cannot read"),
            std::string::npos)
      << out;
  EXPECT_NE(out.find("dds.security.identity_private_key: cannot read " +
                     (dir_ / "no-such.key").string()),
            std::string::npos)
      << out;
}

}  // namespace
}  // namespace gearpath::daemon
