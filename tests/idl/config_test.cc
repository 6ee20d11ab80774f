// The embedded loopback configuration is the config file, byte for byte; a deployment file or
// CYCLONEDDS_URI (when asked) replaces it rather than merging with it; the interfaces Cyclone
// selects are reported.
#include <gtest/gtest.h>
#include <stdlib.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

#include "idl/dds/domain.h"
#include "tests/idl/loopback_test_domains.h"

namespace gearpath::dds {
namespace {

TEST(LoopbackConfig, EmbeddedStringEqualsTheConfigFile) {
  std::ifstream file(GEARPATH_LOOPBACK_CONFIG_FILE, std::ios::binary);
  ASSERT_TRUE(file) << GEARPATH_LOOPBACK_CONFIG_FILE;
  std::ostringstream content;
  content << file.rdbuf();
  EXPECT_EQ(content.str(), kLoopbackConfigXml);
}

TEST(LoopbackConfig, BindsToLoopbackWithMulticastOffAndRoomForMoreThanTenProcesses) {
  const std::string xml(kLoopbackConfigXml);
  EXPECT_NE(xml.find("<NetworkInterface address=\"127.0.0.1\" multicast=\"false\"/>"),
            std::string::npos);
  EXPECT_NE(xml.find("<AllowMulticast>false</AllowMulticast>"), std::string::npos);
  EXPECT_NE(xml.find("<Peer Address=\"127.0.0.1\"/>"), std::string::npos);
  EXPECT_NE(xml.find("<ParticipantIndex>auto</ParticipantIndex>"), std::string::npos);
  EXPECT_NE(xml.find("<MaxAutoParticipantIndex>60</MaxAutoParticipantIndex>"), std::string::npos);
}

class EnvironmentTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const char* old = getenv("CYCLONEDDS_URI");
    had_ = old != nullptr;
    if (had_) old_ = old;
  }
  void TearDown() override {
    if (had_) {
      setenv("CYCLONEDDS_URI", old_.c_str(), 1);
    } else {
      unsetenv("CYCLONEDDS_URI");
    }
  }

 private:
  bool had_ = false;
  std::string old_;
};

TEST_F(EnvironmentTest, CycloneddsUriReplacesTheGivenConfigWhenApplied) {
  setenv("CYCLONEDDS_URI", "file:///etc/site.xml", 1);
  const DomainConfig applied =
      ResolveDomainConfig(DomainConfig{"<A/>", "code"}, EnvironmentConfig::kApply);
  EXPECT_EQ(applied.text, "file:///etc/site.xml");
  EXPECT_EQ(applied.origin, "CYCLONEDDS_URI");
  EXPECT_EQ(ResolveDomainConfig(DomainConfig{"<A/>", "code"}, EnvironmentConfig::kIgnore).text,
            "<A/>");
}

TEST_F(EnvironmentTest, TheLoopbackConfigIsUsedWhenCycloneddsUriIsUnsetOrEmpty) {
  unsetenv("CYCLONEDDS_URI");
  EXPECT_EQ(ResolveDomainConfig("", EnvironmentConfig::kApply).text, kLoopbackConfigXml);
  setenv("CYCLONEDDS_URI", "", 1);
  EXPECT_EQ(ResolveDomainConfig("", EnvironmentConfig::kApply).text, kLoopbackConfigXml);
}

// A deployment configuration file: written by the test, loopback only (127.0.0.1, no
// multicast), as a plant would write its own with its NIC and peers.
class DeploymentFileTest : public EnvironmentTest {
 protected:
  void SetUp() override {
    EnvironmentTest::SetUp();
    path_ = ::testing::TempDir() + "gearpath_idl_deploy_" + std::to_string(getpid()) + ".xml";
    std::ofstream(path_) << kLoopbackConfigXml;
  }
  void TearDown() override {
    std::remove(path_.c_str());
    EnvironmentTest::TearDown();
  }
  std::string path_;
};

TEST_F(DeploymentFileTest, ADeploymentFileIsTheWholeConfigurationWhateverTheEnvironment) {
  setenv("CYCLONEDDS_URI", "<CycloneDDS/>", 1);
  const DomainConfig config = ResolveDomainConfig(path_, EnvironmentConfig::kApply);
  EXPECT_EQ(config.text, kLoopbackConfigXml);
  EXPECT_EQ(config.origin, "file " + path_);
}

TEST_F(DeploymentFileTest, AnUnreadableOrNonXmlDeploymentFileIsRefusedNamingTheFile) {
  try {
    (void)ResolveDomainConfig(path_ + ".missing", EnvironmentConfig::kIgnore);
    ADD_FAILURE() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path_ + ".missing: cannot read"), std::string::npos)
        << e.what();
  }
  std::ofstream(path_) << "eth0";
  EXPECT_THROW((void)ResolveDomainConfig(path_, EnvironmentConfig::kIgnore), std::runtime_error);
}

// The case of issue 11: CYCLONEDDS_URI naming a file that selects 127.0.0.1 was merged with the
// loopback configuration and Cyclone refused `lo` twice. Now it replaces it.
TEST_F(DeploymentFileTest, CycloneddsUriNamingAFileThatSelectsLoopbackCreatesTheDomain) {
  setenv("CYCLONEDDS_URI", ("file://" + path_).c_str(), 1);
  const dds_domainid_t id = testing::TestDomainBase();
  const DomainConfig config = ResolveDomainConfig("", EnvironmentConfig::kApply);
  EXPECT_EQ(config.origin, "CYCLONEDDS_URI");
  EXPECT_EQ(SelectedInterfaces(id, config.text).rfind("lo ", 0), 0u);
  Domain domain(id, kLoopbackConfigXml, EnvironmentConfig::kApply);
  Participant participant(domain);
  EXPECT_GT(participant.handle(), 0);
}

TEST(SelectedInterfaces, TheLoopbackConfigSelectsOnlyLo) {
  const std::string selected =
      SelectedInterfaces(testing::TestDomainBase(), std::string(kLoopbackConfigXml));
  EXPECT_EQ(selected.rfind("lo ", 0), 0u) << selected;
  EXPECT_EQ(selected.find(") "), std::string::npos) << "more than one interface: " << selected;
  // The probe domain is gone: the real one can be created on the same id.
  Domain domain(testing::TestDomainBase(), kLoopbackConfigXml, EnvironmentConfig::kIgnore);
}

TEST(SelectedInterfaces, AnInterfaceThatDoesNotExistIsRefusedWithCyclonesReason) {
  std::string config(kLoopbackConfigXml);
  const std::string lo = "<NetworkInterface address=\"127.0.0.1\"";
  config.replace(config.find(lo), lo.size(), "<NetworkInterface name=\"gp-no-such-if\"");
  try {
    (void)SelectedInterfaces(testing::TestDomainBase(), config);
    ADD_FAILURE() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("gp-no-such-if"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace gearpath::dds
