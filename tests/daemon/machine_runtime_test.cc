// BuildMachines prepares the listed block lengths before the daemon reports READY, and a length
// the machine would reject fails the whole configuration with the key named.
#include "daemon/machine_runtime.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

namespace gearpath::daemon {
namespace {

using nlohmann::json;

Result<MachineSet> Build(const json& lengths, int machines) {
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
  return BuildMachines(*config);
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

}  // namespace
}  // namespace gearpath::daemon
