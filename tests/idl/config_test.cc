// The embedded loopback configuration is the config file, byte for byte, and the environment
// is applied after it only when asked.
#include <gtest/gtest.h>
#include <stdlib.h>

#include <cstdio>
#include <fstream>
#include <sstream>
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

TEST_F(EnvironmentTest, CycloneddsUriIsAppendedAfterTheBaseConfigWhenApplied) {
  setenv("CYCLONEDDS_URI", "file:///etc/site.xml", 1);
  EXPECT_EQ(ComposeDomainConfig("<A/>", EnvironmentConfig::kApply), "<A/>,file:///etc/site.xml");
  EXPECT_EQ(ComposeDomainConfig("<A/>", EnvironmentConfig::kIgnore), "<A/>");
}

TEST_F(EnvironmentTest, NothingIsAppendedWhenCycloneddsUriIsUnsetOrEmpty) {
  unsetenv("CYCLONEDDS_URI");
  EXPECT_EQ(ComposeDomainConfig("<A/>", EnvironmentConfig::kApply), "<A/>");
  setenv("CYCLONEDDS_URI", "", 1);
  EXPECT_EQ(ComposeDomainConfig("<A/>", EnvironmentConfig::kApply), "<A/>");
}

// Cyclone itself applies CYCLONEDDS_URI on top of the loopback configuration: the fragment
// below turns Cyclone's config tracing on, and the trace shows the loopback settings intact
// and only `lo` selected.
TEST_F(EnvironmentTest, CycloneAppliesCycloneddsUriOnTopOfTheLoopbackConfig) {
  const std::string log =
      ::testing::TempDir() + "gearpath_idl_env_" + std::to_string(getpid()) + ".log";
  std::remove(log.c_str());
  setenv("CYCLONEDDS_URI",
         ("<CycloneDDS><Domain><Tracing><Verbosity>config</Verbosity><OutputFile>" + log +
          "</OutputFile></Tracing></Domain></CycloneDDS>")
             .c_str(),
         1);
  {
    Domain domain(testing::TestDomainBase(), kLoopbackConfigXml, EnvironmentConfig::kApply);
    Participant participant(domain);
  }
  std::ifstream file(log);
  ASSERT_TRUE(file) << "no Cyclone trace at " << log << ": CYCLONEDDS_URI was not applied";
  std::ostringstream content;
  content << file.rdbuf();
  const std::string trace = content.str();
  std::remove(log.c_str());
  EXPECT_NE(trace.find("NetworkInterface[@address]: 127.0.0.1"), std::string::npos);
  EXPECT_NE(trace.find("AllowMulticast/#text: false"), std::string::npos);
  EXPECT_NE(trace.find("MaxAutoParticipantIndex/#text: 60"), std::string::npos);
  EXPECT_NE(trace.find("selected interfaces: lo "), std::string::npos);
}

}  // namespace
}  // namespace gearpath::dds
