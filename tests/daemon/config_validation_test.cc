// gearpathd configuration: the embedded default validates, and every error names its key path.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "daemon/config_schema.h"
#include "daemon/daemon_config.h"

namespace gearpath::daemon {
namespace {

using nlohmann::json;

std::string ReadFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

json DefaultJson() { return json::parse(DefaultConfigText()); }

// The error text for `config`, or "" when it validates.
std::string ErrorsOf(const json& config) {
  auto parsed = ParseDaemonConfig(config.dump(), "test.json");
  return parsed.ok() ? std::string() : parsed.error();
}

TEST(DaemonConfig, EmbeddedDefaultValidates) {
  auto parsed = ParseDaemonConfig(DefaultConfigText(), kEmbeddedOrigin);
  ASSERT_TRUE(parsed.ok()) << parsed.error();
  ASSERT_EQ(parsed->machines.size(), 1u);
  EXPECT_EQ(parsed->machines[0].id, "table1");
  EXPECT_EQ(parsed->machines[0].frf_set, "builtin:table1");
  EXPECT_EQ(parsed->machines[0].key_path, "machines[0]");
}

TEST(DaemonConfig, EmbeddedDefaultIsTheShippedConfigFileVerbatim) {
  EXPECT_EQ(DefaultConfigText(), ReadFile(GEARPATH_SOURCE_DIR "/config/gearpathd.json"));
}

TEST(DaemonConfig, RejectsAnUnknownInverseMethodNamingTheKeyAndTheChoices) {
  json c = DefaultJson();
  c["machines"][0]["analysis"]["inverse"]["method"] = "mwii";
  EXPECT_EQ(ErrorsOf(c),
            "machines[0].analysis.inverse.method: expected one of mwi, tikhonov, least_squares, "
            "got \"mwii\"");
}

TEST(DaemonConfig, RejectsAnUnknownKeyNamingItsPath) {
  json c = DefaultJson();
  c["machines"][0]["analysis"]["inverse"]["alpah"] = 1.0;
  const std::string errors = ErrorsOf(c);
  EXPECT_EQ(errors.rfind("machines[0].analysis.inverse.alpah: unknown key", 0), 0u) << errors;
  c = DefaultJson();
  c["logging"] = json::object();
  EXPECT_EQ(ErrorsOf(c).rfind("logging: unknown key (allowed here: daemon, state, standby, dds, metrics, machines)", 0),
            0u);
}

TEST(DaemonConfig, RejectsAMissingRequiredKeyNamingIt) {
  json c = DefaultJson();
  c["machines"][0].erase("frf_set");
  EXPECT_EQ(ErrorsOf(c), "machines[0].frf_set: required key is missing");
  c = DefaultJson();
  c["machines"][0]["acquisition"].erase("sample_rate_hz");
  EXPECT_EQ(ErrorsOf(c), "machines[0].acquisition.sample_rate_hz: required key is missing");
}

TEST(DaemonConfig, RejectsAnOutOfRangeValueWithItsRange) {
  json c = DefaultJson();
  c["dds"]["domain_id"] = 300;
  EXPECT_EQ(ErrorsOf(c), "dds.domain_id: expected a value in [0, 232], got 300");
  c = DefaultJson();
  c["machines"][0]["acquisition"]["sample_rate_hz"] = 0.0;
  EXPECT_EQ(ErrorsOf(c), "machines[0].acquisition.sample_rate_hz: expected a value in (0, "
                         "10000000], got 0");
  c = DefaultJson();
  c["machines"][0]["analysis"]["baseline"]["operating_bands"] = 17;
  EXPECT_EQ(ErrorsOf(c),
            "machines[0].analysis.baseline.operating_bands: expected a value in [1, 16], got 17");
}

TEST(DaemonConfig, RejectsAValueOfTheWrongType) {
  json c = DefaultJson();
  c["daemon"]["status_period_s"] = "1";
  EXPECT_EQ(ErrorsOf(c), "daemon.status_period_s: expected a number, got string \"1\"");
  c = DefaultJson();
  c["machines"][0]["gear_train"]["gears"][1]["teeth"] = 40.5;
  EXPECT_EQ(ErrorsOf(c), "machines[0].gear_train.gears[1].teeth: expected an integer, got number "
                         "40.5");
  c = DefaultJson();
  c["machines"] = json::object();
  EXPECT_EQ(ErrorsOf(c), "machines: expected an array, got object {}");
}

TEST(DaemonConfig, RejectsAnEmptyMachineList) {
  json c = DefaultJson();
  c["machines"] = json::array();
  EXPECT_EQ(ErrorsOf(c), "machines: expected at least 1 items, got 0");
}

TEST(DaemonConfig, ReportsEveryErrorNotOnlyTheFirst) {
  json c = DefaultJson();
  c["dds"]["domain_id"] = -1;
  c["machines"][0]["analysis"]["envelope"]["kurtogram_max_level"] = 0;
  const std::string errors = ErrorsOf(c);
  EXPECT_NE(errors.find("dds.domain_id:"), std::string::npos) << errors;
  EXPECT_NE(errors.find("\nmachines[0].analysis.envelope.kurtogram_max_level:"), std::string::npos)
      << errors;
}

TEST(DaemonConfig, RejectsDuplicateMachineIdsNamingBoth) {
  json c = DefaultJson();
  c["machines"].push_back(c["machines"][0]);
  EXPECT_EQ(ErrorsOf(c), "machines[1].id: duplicate machine id \"table1\" (also machines[0].id)");
}

TEST(DaemonConfig, RejectsAStageThatNamesAnUnknownGear) {
  json c = DefaultJson();
  c["machines"][0]["gear_train"]["stages"][1]["driven"] = "G9";
  EXPECT_EQ(ErrorsOf(c), "machines[0].gear_train.stages[1].driven: unknown gear \"G9\"");
}

TEST(DaemonConfig, RejectsAPathNamingAnUnknownGearAndAGearOnNoShaft) {
  json c = DefaultJson();
  c["machines"][0]["paths"] = json::array({{{"name", "B1x"}, {"gears", {"G1", "G7"}}}});
  c["machines"][0]["gear_train"]["shafts"][2]["gears"] = json::array({"G1"});
  EXPECT_EQ(ErrorsOf(c),
            "machines[0].gear_train.shafts[2].gears[0]: gear \"G1\" is already on shaft "
            "\"input\"\n"
            "machines[0].gear_train.gears[3]: gear \"G4\" is on no shaft (list it in "
            "gear_train.shafts[].gears)\n"
            "machines[0].paths[0].gears[1]: unknown gear \"G7\"");
}

TEST(DaemonConfig, RejectsTwoChannelsMappedToOneFrfRow) {
  json c = DefaultJson();
  c["machines"][0]["channels"] = json::array({{{"sensor", "A4"}, {"axis", "x"}, {"frf_row", 0}},
                                              {{"sensor", "A5"}, {"axis", "x"}, {"frf_row", 0}}});
  EXPECT_EQ(ErrorsOf(c),
            "machines[0].channels[1].frf_row: row 0 is already mapped by channels[0]");
}

TEST(DaemonConfig, RejectsBlockLimitsThatExcludeEveryBlock) {
  json c = DefaultJson();
  c["machines"][0]["acquisition"]["min_samples_per_channel"] = 4096;
  c["machines"][0]["acquisition"]["max_samples_per_channel"] = 2048;
  EXPECT_EQ(ErrorsOf(c), "machines[0].acquisition.min_samples_per_channel: 4096 exceeds "
                         "max_samples_per_channel 2048");
}

TEST(DaemonConfig, RejectsAnUnknownBuiltinFrfSet) {
  json c = DefaultJson();
  c["machines"][0]["frf_set"] = "builtin:table2";
  EXPECT_EQ(ErrorsOf(c), "machines[0].frf_set: unknown built-in FRF set \"builtin:table2\" "
                         "(known: builtin:table1)");
}

// `"frf_set": "identity"` with each channel's nearby gears (monitoring before the hammer test).
json IdentityJson() {
  json c = DefaultJson();
  c["machines"][0]["frf_set"] = "identity";
  c["machines"][0]["channels"] =
      json::array({{{"sensor", "A1"}, {"axis", "x"}, {"gears", {"G1", "G2"}}},
                   {{"sensor", "A2"}, {"axis", "y"}, {"gears", {"G3", "G4"}}}});
  return c;
}

TEST(DaemonConfig, AcceptsAnIdentityFrfSetWithEveryChannelsGears) {
  EXPECT_EQ(ErrorsOf(IdentityJson()), "");
}

TEST(DaemonConfig, AnIdentityFrfSetNeedsTheChannelsListed) {
  json c = IdentityJson();
  c["machines"][0]["channels"] = json::array();
  EXPECT_EQ(ErrorsOf(c), "machines[0].channels: frf_set \"identity\" needs the block's channels "
                         "listed, each with the gears its sensor sits near (channels[].gears)");
}

TEST(DaemonConfig, AnIdentityFrfSetNeedsEveryChannelsGearsAndNamesTheChannel) {
  json c = IdentityJson();
  c["machines"][0]["channels"][1].erase("gears");
  EXPECT_EQ(ErrorsOf(c), "machines[0].channels[1].gears: required with frf_set \"identity\" "
                         "(the gears this sensor sits nearest to)");
  c = IdentityJson();
  c["machines"][0]["channels"][1]["gears"] = json::array();
  EXPECT_EQ(ErrorsOf(c), "machines[0].channels[1].gears: expected at least 1 items, got 0");
}

TEST(DaemonConfig, AnIdentityChannelsGearsMustExistOnceAndItsRowStaysImplicit) {
  json c = IdentityJson();
  c["machines"][0]["channels"][0]["gears"] = {"G1", "G9", "G1"};
  c["machines"][0]["channels"][1]["frf_row"] = 1;
  EXPECT_EQ(ErrorsOf(c),
            "machines[0].channels[0].gears[1]: unknown gear \"G9\"\n"
            "machines[0].channels[0].gears[2]: gear \"G1\" is named twice\n"
            "machines[0].channels[1].frf_row: must be -1 with frf_set \"identity\" (channel i "
            "is row i of the identity set)");
}

TEST(DaemonConfig, ChannelGearsWithAMeasuredFrfSetAreRefusedNotIgnored) {
  json c = DefaultJson();
  c["machines"][0]["channels"] =
      json::array({{{"sensor", "p1"}, {"axis", "x"}, {"gears", {"G1"}}}});
  EXPECT_EQ(ErrorsOf(c), "machines[0].channels[0].gears: only used with frf_set \"identity\" "
                         "(an FRF set names its paths' gears; override them in paths[])");
}

TEST(DaemonConfig, TheConditionIndicatorsTopicNameIsConfigurableLikeTheOthers) {
  auto parsed = ParseDaemonConfig(DefaultConfigText(), kEmbeddedOrigin);
  ASSERT_TRUE(parsed.ok()) << parsed.error();
  EXPECT_EQ(parsed->topics.condition_indicators, "gearpath/ConditionIndicators");
  json c = DefaultJson();
  c["dds"]["topics"]["condition_indicators"] = "plant7/ConditionIndicators";
  auto renamed = ParseDaemonConfig(c.dump(), "test.json");
  ASSERT_TRUE(renamed.ok()) << renamed.error();
  EXPECT_EQ(renamed->topics.condition_indicators, "plant7/ConditionIndicators");
  c["dds"]["topics"]["condition_indicators"] = "";
  EXPECT_EQ(ErrorsOf(c), "dds.topics.condition_indicators: expected at least 1 characters, got 0");
}

TEST(DaemonConfig, TheMachineHealthTopicNameIsConfigurableLikeTheOthers) {
  auto parsed = ParseDaemonConfig(DefaultConfigText(), kEmbeddedOrigin);
  ASSERT_TRUE(parsed.ok()) << parsed.error();
  EXPECT_EQ(parsed->topics.machine_health, "gearpath/MachineHealth");
  json c = DefaultJson();
  c["dds"]["topics"]["machine_health"] = "plant7/MachineHealth";
  auto renamed = ParseDaemonConfig(c.dump(), "test.json");
  ASSERT_TRUE(renamed.ok()) << renamed.error();
  EXPECT_EQ(renamed->topics.machine_health, "plant7/MachineHealth");
  c["dds"]["topics"]["machine_health"] = "";
  EXPECT_EQ(ErrorsOf(c), "dds.topics.machine_health: expected at least 1 characters, got 0");
}

// Issue 9, no arbitrary machine cap: 100 machines (more than Status' 64) are a configuration
// like any other; only an absurd count is refused, naming the key and the sanity bound.
TEST(DaemonConfig, AHundredMachinesAreAcceptedAndAnAbsurdCountIsRefused) {
  json c = DefaultJson();
  const json one = c["machines"][0];
  const auto with_machines = [&](int n) {
    c["machines"] = json::array();
    for (int i = 0; i < n; ++i) {
      json m = one;
      m["id"] = "gb" + std::to_string(i);
      c["machines"].push_back(std::move(m));
    }
  };
  with_machines(100);
  auto parsed = ParseDaemonConfig(c.dump(), "test.json");
  ASSERT_TRUE(parsed.ok()) << parsed.error();
  ASSERT_EQ(parsed->machines.size(), 100u);
  EXPECT_EQ(parsed->machines[99].id, "gb99");
  EXPECT_EQ(parsed->machines[99].key_path, "machines[99]");

  with_machines(4097);
  EXPECT_EQ(ErrorsOf(c), "machines: expected at most 4096 items, got 4097");
}

TEST(DaemonConfig, RejectsMalformedJsonNamingTheFile) {
  auto parsed = ParseDaemonConfig("{\"daemon\": {", "broken.json");
  ASSERT_FALSE(parsed.ok());
  EXPECT_EQ(parsed.error().rfind("broken.json: not valid JSON:", 0), 0u) << parsed.error();
}

TEST(DaemonConfig, RejectsAMissingFileNamingIt) {
  auto parsed = LoadDaemonConfigFile("/nonexistent/gearpathd.json");
  ASSERT_FALSE(parsed.ok());
  EXPECT_EQ(parsed.error(), "/nonexistent/gearpathd.json: cannot open the configuration file");
}

TEST(DaemonConfig, FillsEveryOmittedKeyWithItsDeclaredDefault) {
  json c = DefaultJson();
  c.erase("daemon");
  c.erase("dds");
  c["machines"][0].erase("analysis");
  auto parsed = ParseDaemonConfig(c.dump(), "minimal.json");
  ASSERT_TRUE(parsed.ok()) << parsed.error();
  // The defaults are declared in the schema; the shipped config spells the same values out.
  const json full = ParseDaemonConfig(DefaultConfigText(), kEmbeddedOrigin)->normalized;
  EXPECT_EQ(parsed->normalized["daemon"], full["daemon"]);
  EXPECT_EQ(parsed->normalized["dds"], full["dds"]);
  EXPECT_EQ(parsed->normalized["machines"][0]["analysis"], full["machines"][0]["analysis"]);
  EXPECT_EQ(parsed->daemon_id, "gearpathd");
  EXPECT_EQ(parsed->log_level, "info");
}

TEST(DaemonConfig, DocumentationHoldsTheReferenceGeneratedFromTheSchema) {
  const std::string doc = ReadFile(GEARPATH_SOURCE_DIR "/docs/configuration.md");
  const std::string table = RenderSchemaReference(DaemonConfigSchema());
  std::ofstream("configuration_reference.md") << table;  // for splicing into the doc by hand
  EXPECT_NE(doc.find(table), std::string::npos)
      << "docs/configuration.md is out of date; regenerate its table with "
         "`gearpathd --print-config-reference`:\n"
      << table;
}

TEST(ConfigSchema, ReferenceHasOneRowPerLeafKeyWithRangeAndDefault) {
  const std::string table = RenderSchemaReference(DaemonConfigSchema());
  EXPECT_NE(table.find("| `machines[].analysis.inverse.method` | string | mwi, tikhonov, "
                       "least_squares | `\"mwi\"` |"),
            std::string::npos)
      << table;
  EXPECT_NE(table.find("| `dds.domain_id` | integer | [0, 232] | `0` |"), std::string::npos);
}

}  // namespace
}  // namespace gearpath::daemon
