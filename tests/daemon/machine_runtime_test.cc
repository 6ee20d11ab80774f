// BuildMachines prepares the listed block lengths before the daemon reports READY, and a length
// the machine would reject fails the whole configuration with the key named.
#include "daemon/machine_runtime.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

namespace gearpath::daemon {
namespace {

using nlohmann::json;

DaemonConfig Config(const json& lengths, int machines) {
  json c = json::parse(DefaultConfigText());
  const json one = c["machines"][0];
  c["machines"] = json::array();
  for (int i = 0; i < machines; ++i) {
    json m = one;
    m["id"] = "gb" + std::to_string(i);
    m["acquisition"]["prepare_samples_per_channel"] = lengths;
    c["machines"].push_back(m);
  }
  auto config = ParseDaemonConfig(c.dump(), "test");
  EXPECT_TRUE(config.ok()) << config.error();
  return config.value();
}

Result<MachineSet> Build(const json& lengths, int machines) {
  return BuildMachines(Config(lengths, machines));
}

TEST(BuildMachinesTest, ListedBlockLengthsArePreparedOnEveryMachine) {
  auto set = Build(json::array({4096, 8192}), 3);
  ASSERT_TRUE(set.ok()) << set.error();
  ASSERT_EQ(set->machines.size(), 3u);
  for (const auto& [id, m] : set->machines) {
    EXPECT_TRUE(m->processor.configured_for(4096)) << id;
    EXPECT_TRUE(m->processor.configured_for(8192)) << id;
    EXPECT_FALSE(m->processor.configured_for(16384)) << id;  // left to its first block
  }
}

TEST(BuildMachinesTest, ALengthOutsideTheAcceptedRangeIsRefusedWithItsKey) {
  auto set = Build(json::array({8192, 512}), 2);  // min_samples_per_channel is 1024
  ASSERT_FALSE(set.ok());
  EXPECT_NE(set.error().find("machines[0].acquisition.prepare_samples_per_channel (512)"),
            std::string::npos)
      << set.error();
}

TEST(BuildMachinesTest, MachinesOnOneFrfSetShareOneLoadAndOneOperatorAlsoAcrossAReload) {
  const DaemonConfig config = Config(json::array({4096}), 3);  // all on builtin:table1
  auto set = BuildMachines(config);
  ASSERT_TRUE(set.ok()) << set.error();
  const FrfRegistry& registry = *set->frf_registry;
  EXPECT_EQ(registry.loads(), 1u);
  EXPECT_EQ(registry.sets_created(), 1u);
  const SharedFrfOperators* shared = set->machines.at("gb0")->processor.setup().shared_frf.get();
  ASSERT_NE(shared, nullptr);
  for (const auto& [id, m] : set->machines) {
    EXPECT_EQ(m->processor.setup().shared_frf.get(), shared) << id;
  }
  EXPECT_EQ(shared->operators_built(), 1u);
  // A reload of the unchanged configuration reads the source again and finds the same matrix:
  // the new machines take the running ones' operators, nothing is recomputed.
  auto reloaded = BuildMachines(config, set->frf_registry);
  ASSERT_TRUE(reloaded.ok()) << reloaded.error();
  EXPECT_EQ(registry.loads(), 2u);
  EXPECT_EQ(registry.sets_created(), 1u);
  for (const auto& [id, m] : reloaded->machines) {
    EXPECT_EQ(m->processor.setup().shared_frf.get(), shared) << id;
  }
  EXPECT_EQ(shared->operators_built(), 1u);
}

TEST(BuildMachinesTest, MachinesOnDifferentFrfSetsDoNotShare) {
  json c = json::parse(DefaultConfigText());
  json other = c["machines"][0];
  other["id"] = "identity-gb";
  other["frf_set"] = "identity";
  other["acquisition"]["min_samples_per_channel"] = 1024;
  other["acquisition"]["max_samples_per_channel"] = 8192;
  other["acquisition"]["prepare_samples_per_channel"] = json::array();
  other["channels"] = json::array({{{"sensor", "A1"}, {"axis", "x"}, {"gears", {"G1", "G2"}}},
                                   {{"sensor", "A2"}, {"axis", "z"}, {"gears", {"G3", "G4"}}}});
  c["machines"].push_back(other);
  auto config = ParseDaemonConfig(c.dump(), "test");
  ASSERT_TRUE(config.ok()) << config.error();
  auto set = BuildMachines(*config);
  ASSERT_TRUE(set.ok()) << set.error();
  EXPECT_EQ(set->frf_registry->sets_created(), 2u);
  const auto& machines = set->machines;
  EXPECT_NE(machines.begin()->second->processor.setup().shared_frf.get(),
            std::next(machines.begin())->second->processor.setup().shared_frf.get());
}

}  // namespace
}  // namespace gearpath::daemon
