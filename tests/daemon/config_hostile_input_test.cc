// gearpathd configuration against hostile files: each input that once aborted the daemon or
// overflowed its stack (issue 10) is a plain error naming the file and the place.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "daemon/daemon_config.h"

namespace gearpath::daemon {
namespace {

using nlohmann::json;

// The embedded default with `value` (raw JSON text) in place of status_period_s.
std::string DefaultWith(const std::string& value) {
  std::string text = json::parse(DefaultConfigText()).dump(2);
  const std::string key = "\"status_period_s\": ";
  const auto at = text.find(key);
  EXPECT_NE(at, std::string::npos);
  const auto end = text.find_first_of(",\n", at + key.size());
  text.replace(at + key.size(), end - at - key.size(), value);
  return text;
}

bool StartsWith(const std::string& s, const std::string& prefix) {
  return s.compare(0, prefix.size(), prefix) == 0;
}

TEST(DaemonConfigHostileInput, ANumberThatOverflowsADoubleIsAnErrorNotAnAbort) {
  auto parsed = ParseDaemonConfig(DefaultWith("1e999"), "gearpathd.json");
  ASSERT_FALSE(parsed.ok());
  EXPECT_TRUE(StartsWith(parsed.error(), "gearpathd.json: not valid JSON: line "))
      << parsed.error();
  EXPECT_NE(parsed.error().find("number overflow parsing '1e999' (too large for a double)"),
            std::string::npos)
      << parsed.error();
}

TEST(DaemonConfigHostileInput, FiftyThousandNestedArraysAreAnErrorNotAStackOverflow) {
  const std::string deep = std::string(50'000, '[') + std::string(50'000, ']');
  auto parsed = ParseDaemonConfig(DefaultWith(deep), "gearpathd.json");
  ASSERT_FALSE(parsed.ok());
  EXPECT_TRUE(StartsWith(parsed.error(), "gearpathd.json: not valid JSON: line "));
  EXPECT_NE(parsed.error().find("nested deeper than 64 levels"), std::string::npos)
      << parsed.error();
  // A whole document of nothing but brackets too.
  EXPECT_FALSE(ParseDaemonConfig(std::string(100'000, '['), "x.json").ok());
}

TEST(DaemonConfigHostileInput, NestingWithinTheLimitReachesTheSchemaWhichNamesTheKey) {
  const std::string nested = std::string(40, '[') + std::string(40, ']');
  auto parsed = ParseDaemonConfig(DefaultWith(nested), "gearpathd.json");
  ASSERT_FALSE(parsed.ok());
  EXPECT_TRUE(StartsWith(parsed.error(), "daemon.status_period_s: expected a number, got array"))
      << parsed.error();
}

TEST(DaemonConfigHostileInput, AnIntegralFloatBeyondInt64IsARangeErrorNotAConversion) {
  // Found by fuzz_daemon_config (UBSan: 6.55556e+56 outside the range of long).
  json c = json::parse(DefaultConfigText());
  c["dds"]["domain_id"] = 6.55556e56;
  auto parsed = ParseDaemonConfig(c.dump(), "gearpathd.json");
  ASSERT_FALSE(parsed.ok());
  EXPECT_EQ(parsed.error(), "dds.domain_id: expected a value in [0, 232], got 6.55556e+56");
}

TEST(DaemonConfigHostileInput, NonUtf8BytesAreAnErrorNamingThePosition) {
  std::string text = DefaultWith("1.0");
  text.replace(text.find("\"table1\""), 8, "\"t\xE9\xFF\"");
  auto parsed = ParseDaemonConfig(text, "gearpathd.json");
  ASSERT_FALSE(parsed.ok());
  EXPECT_TRUE(StartsWith(parsed.error(), "gearpathd.json: not valid JSON: line "))
      << parsed.error();
  EXPECT_NE(parsed.error().find("UTF-8"), std::string::npos) << parsed.error();
}

TEST(DaemonConfigHostileInput, LoadingAHostileFileNamesThePath) {
  const std::string path = (std::filesystem::temp_directory_path() /
                            ("gearpath_hostile_" + std::to_string(::getpid()) + ".json"))
                               .string();
  std::ofstream(path) << DefaultWith("-1e999");
  auto parsed = LoadDaemonConfigFile(path);
  ASSERT_FALSE(parsed.ok());
  EXPECT_TRUE(StartsWith(parsed.error(), path + ": not valid JSON: line ")) << parsed.error();
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace gearpath::daemon
