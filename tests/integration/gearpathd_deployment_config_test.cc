// Leaving loopback the documented way (issue 11), tried on loopback: gearpathd given a
// deployment Cyclone configuration file (here one that selects 127.0.0.1 with multicast off, as
// a plant's would select its NIC) starts, logs the interfaces Cyclone selected, and processes a
// block. Through `dds.config`, and through CYCLONEDDS_URI naming the file, which used to be
// merged with the embedded loopback configuration and made Cyclone refuse `lo` twice.
#include <fstream>
#include <string>

#include "tests/integration/gearpathd_fixture.h"

namespace gearpath::testing {
namespace {

// A copy of the embedded loopback configuration as a deployment file.
std::string WriteDeploymentFile(const std::filesystem::path& dir) {
  const std::string path = (dir / "cyclonedds-deployment.xml").string();
  std::ofstream(path) << dds::kLoopbackConfigXml;
  return path;
}

class DeploymentConfigFile : public GearpathdOverDds {
 protected:
  void Configure(json& config) override {
    deployment_file_ = WriteDeploymentFile(dir_);
    config["dds"]["config"] = deployment_file_;
  }
  std::string deployment_file_;
};

TEST_F(DeploymentConfigFile, GearpathdStartsOnTheFileAndProcessesABlock) {
  Publish(NoiseBlock(0));
  ASSERT_TRUE(WaitStatus([](const auto& m) { return m.blocks_processed == 1; }, 30s))
      << daemon_->Log();
  EXPECT_EQ(last_status_.blocks_rejected, 0u);
  EXPECT_NE(daemon_->Log().find("configuration from file " + deployment_file_ +
                                "; selected interfaces: lo "),
            std::string::npos)
      << daemon_->Log();
}

class DeploymentConfigFromEnvironment : public GearpathdOverDds {
 protected:
  void Configure(json& config) override {
    (void)config;
    daemon_environment_ = {"CYCLONEDDS_URI=file://" + WriteDeploymentFile(dir_)};
  }
};

TEST_F(DeploymentConfigFromEnvironment, CycloneddsUriNamingAFileThatSelectsLoopbackWorks) {
  Publish(NoiseBlock(0));
  ASSERT_TRUE(WaitStatus([](const auto& m) { return m.blocks_processed == 1; }, 30s))
      << daemon_->Log();
  EXPECT_EQ(daemon_->Log().find("may not be selected twice"), std::string::npos);
  EXPECT_NE(daemon_->Log().find("configuration from CYCLONEDDS_URI; selected interfaces: lo "),
            std::string::npos)
      << daemon_->Log();
}

}  // namespace
}  // namespace gearpath::testing
