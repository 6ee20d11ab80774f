// More than ten Cyclone instances share one loopback domain: each takes its own participant
// index (unicast port) up to MaxAutoParticipantIndex = 60, where Cyclone's default of 9 stops
// the eleventh, and unicast discovery through the 127.0.0.1 peer reaches all of them.
#include <gtest/gtest.h>

#include <chrono>
#include <memory>
#include <vector>

#include "idl/dds/gearpath_topics.h"
#include "tests/idl/loopback_test_domains.h"

namespace gearpath::dds {
namespace {

// Each Domain here is a separate Cyclone instance, exactly what a separate process would be:
// its own sockets, own participant index, discovery over UDP.
struct Node {
  explicit Node(dds_domainid_t local_id)
      : domain(local_id, testing::TestConfig(testing::TestDomainBase()),
               EnvironmentConfig::kIgnore),
        participant(domain),
        topic(participant) {}
  Domain domain;
  Participant participant;
  Topic<gearpath_Status> topic;
};

TEST(ParticipantIndex, TwelveInstancesJoinOneLoopbackDomainAndDiscoverEachOther) {
  constexpr int kInstances = 12;
  std::vector<std::unique_ptr<Node>> nodes;
  for (int i = 0; i < kInstances; ++i) {
    // Local ids are private to this process; ExternalDomainId puts them all on one wire domain.
    nodes.push_back(std::make_unique<Node>(static_cast<dds_domainid_t>(300 + i)));
  }
  Writer<gearpath_Status> writer(nodes[0]->topic);
  std::vector<Reader<gearpath_Status>> readers;
  for (int i = 1; i < kInstances; ++i)
    readers.emplace_back(nodes[static_cast<std::size_t>(i)]->topic);
  const Status matched = writer.WaitForReaders(kInstances - 1, std::chrono::seconds(20));
  EXPECT_TRUE(matched) << matched.error();
}

}  // namespace
}  // namespace gearpath::dds
