// The deployment keys of the dds section: dds.config (a Cyclone XML file that replaces the
// embedded loopback configuration) and dds.security (all six DDS Security files, or none).
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>

#include "daemon/daemon_config.h"

namespace gearpath::daemon {
namespace {

using nlohmann::json;

json Default() { return json::parse(DefaultConfigText()); }

TEST(DdsDeploymentKeys, DefaultIsTheEmbeddedLoopbackConfigurationWithoutSecurity) {
  auto config = ParseDaemonConfig(Default().dump(), "test");
  ASSERT_TRUE(config.ok()) << config.error();
  EXPECT_EQ(config->dds_config_file, "");
  EXPECT_EQ(config->dds_security, DdsSecurityFiles{});
}

TEST(DdsDeploymentKeys, ConfigFileAndSecurityFilesAreRead) {
  json j = Default();
  j["dds"]["config"] = "/etc/gearpath/cyclonedds.xml";
  j["dds"]["security"] = {{"identity_ca", "ca.pem"},         {"identity_certificate", "d.pem"},
                          {"identity_private_key", "d.key"}, {"permissions_ca", "pca.pem"},
                          {"governance", "governance.p7s"},  {"permissions", "perm.p7s"}};
  auto config = ParseDaemonConfig(j.dump(), "test");
  ASSERT_TRUE(config.ok()) << config.error();
  EXPECT_EQ(config->dds_config_file, "/etc/gearpath/cyclonedds.xml");
  EXPECT_EQ(config->dds_security, (DdsSecurityFiles{"ca.pem", "d.pem", "d.key", "pca.pem",
                                                    "governance.p7s", "perm.p7s"}));
}

TEST(DdsDeploymentKeys, SecurityWithSomeFilesMissingIsRefusedNamingEachMissingKey) {
  json j = Default();
  j["dds"]["security"]["identity_ca"] = "ca.pem";
  j["dds"]["security"]["permissions"] = "perm.p7s";
  auto config = ParseDaemonConfig(j.dump(), "test");
  ASSERT_FALSE(config.ok());
  for (const char* key :
       {"identity_certificate", "identity_private_key", "permissions_ca", "governance"}) {
    EXPECT_NE(config.error().find(std::string("dds.security.") + key + ": required"),
              std::string::npos)
        << config.error();
  }
  EXPECT_EQ(config.error().find("dds.security.identity_ca"), std::string::npos);
}

TEST(DdsDeploymentKeys, UnknownSecurityKeyIsRefused) {
  json j = Default();
  j["dds"]["security"]["password"] = "x";
  auto config = ParseDaemonConfig(j.dump(), "test");
  ASSERT_FALSE(config.ok());
  EXPECT_NE(config.error().find("dds.security.password: unknown key"), std::string::npos)
      << config.error();
}

}  // namespace
}  // namespace gearpath::daemon
