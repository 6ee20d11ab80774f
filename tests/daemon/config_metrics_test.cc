// The `metrics` section: defaults (off, loopback, 9469), and clear errors for a bad port, an
// address that is not numeric, and a non-loopback address without allow_remote.
#include <gtest/gtest.h>

#include "daemon/daemon_config.h"
#include "daemon/ip_address.h"

namespace gearpath::daemon {
namespace {

using nlohmann::json;

json WithMetrics(const json& metrics) {
  json c = json::parse(DefaultConfigText());
  c["metrics"] = metrics;
  return c;
}

std::string ErrorsOf(const json& config) {
  auto parsed = ParseDaemonConfig(config.dump(), "test.json");
  return parsed.ok() ? std::string() : parsed.error();
}

TEST(MetricsConfig, OffOnLoopbackPort9469ByDefault) {
  json c = json::parse(DefaultConfigText());
  c.erase("metrics");
  auto parsed = ParseDaemonConfig(c.dump(), "test.json");
  ASSERT_TRUE(parsed.ok()) << parsed.error();
  EXPECT_FALSE(parsed->metrics.enabled);
  EXPECT_EQ(parsed->metrics.address, "127.0.0.1");
  EXPECT_EQ(parsed->metrics.port, 9469);
  EXPECT_FALSE(parsed->metrics.allow_remote);
  // The shipped file spells out the same.
  auto shipped = ParseDaemonConfig(DefaultConfigText(), kEmbeddedOrigin);
  ASSERT_TRUE(shipped.ok()) << shipped.error();
  EXPECT_EQ(shipped->metrics, parsed->metrics);
}

TEST(MetricsConfig, AcceptsPortZeroAndIpv6Loopback) {
  auto parsed = ParseDaemonConfig(
      WithMetrics({{"enabled", true}, {"address", "::1"}, {"port", 0}}).dump(), "test.json");
  ASSERT_TRUE(parsed.ok()) << parsed.error();
  EXPECT_TRUE(parsed->metrics.enabled);
  EXPECT_EQ(parsed->metrics.address, "::1");
  EXPECT_EQ(parsed->metrics.port, 0);
}

TEST(MetricsConfig, RejectsAPortOutOfRangeNamingTheKey) {
  EXPECT_EQ(ErrorsOf(WithMetrics({{"port", 70000}})),
            "metrics.port: expected a value in [0, 65535], got 70000");
  EXPECT_EQ(ErrorsOf(WithMetrics({{"port", -1}})),
            "metrics.port: expected a value in [0, 65535], got -1");
  EXPECT_EQ(ErrorsOf(WithMetrics({{"port", "9469"}})),
            "metrics.port: expected an integer, got string \"9469\"");
}

TEST(MetricsConfig, RejectsAHostNameOrGarbageAsAddress) {
  EXPECT_EQ(ErrorsOf(WithMetrics({{"address", "localhost"}})),
            "metrics.address: expected a numeric IPv4 or IPv6 address (e.g. 127.0.0.1 or ::1), "
            "got \"localhost\"");
  EXPECT_EQ(ErrorsOf(WithMetrics({{"address", "127.0.0.1:9469"}})).rfind("metrics.address: ", 0),
            0u);
  EXPECT_EQ(ErrorsOf(WithMetrics({{"address", ""}})),
            "metrics.address: expected at least 1 characters, got 0");
}

TEST(MetricsConfig, RefusesANonLoopbackAddressUnlessAllowRemote) {
  EXPECT_EQ(ErrorsOf(WithMetrics({{"enabled", true}, {"address", "0.0.0.0"}})),
            "metrics.address: \"0.0.0.0\" is not a loopback address; the endpoint has no TLS "
            "and no authentication, so set metrics.allow_remote to true to serve it beyond "
            "this host");
  auto parsed = ParseDaemonConfig(
      WithMetrics({{"address", "0.0.0.0"}, {"allow_remote", true}}).dump(), "test.json");
  ASSERT_TRUE(parsed.ok()) << parsed.error();
  EXPECT_TRUE(parsed->metrics.allow_remote);
}

TEST(MetricsConfig, RejectsAnUnknownKeyListingTheAllowedOnes) {
  EXPECT_EQ(ErrorsOf(WithMetrics({{"bind", "127.0.0.1"}})),
            "metrics.bind: unknown key (allowed here: enabled, address, port, allow_remote)");
}

TEST(IpAddress, ClassifiesLoopbackAndNumericAddresses) {
  EXPECT_TRUE(IsLoopbackAddress("127.0.0.1"));
  EXPECT_TRUE(IsLoopbackAddress("127.1.2.3"));
  EXPECT_TRUE(IsLoopbackAddress("::1"));
  EXPECT_FALSE(IsLoopbackAddress("0.0.0.0"));
  EXPECT_FALSE(IsLoopbackAddress("::"));
  EXPECT_FALSE(IsLoopbackAddress("128.0.0.1"));
  EXPECT_FALSE(IsLoopbackAddress("localhost"));
  EXPECT_TRUE(IsNumericAddress("::ffff:127.0.0.1"));
  EXPECT_FALSE(IsNumericAddress("1.2.3"));
  EXPECT_FALSE(IsNumericAddress("host.example"));
}

}  // namespace
}  // namespace gearpath::daemon
