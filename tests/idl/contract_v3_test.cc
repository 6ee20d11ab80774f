// Contract version 3 (idl/gearpath.idl; docs/topics.md, "Version 3: no machine cap"): the new
// MachineHealth topic is written in XCDR1 like every other, has the documented name, QoS class
// and key (daemon id and machine id: one instance per daemon and machine), and arrives field by
// field over loopback UDP; Status keeps its version-2 bound.
#include <dds/dds.h>
#include <gtest/gtest.h>

#include <array>
#include <chrono>
#include <map>
#include <string>
#include <vector>

#include "idl/dds/gearpath_topics.h"
#include "tests/idl/loopback_test_domains.h"

namespace gearpath::dds {
namespace {

using std::chrono::seconds;

TEST(ContractV3, TheVersionAndTheNewTopicAreThoseDocumented) {
  EXPECT_GE(gearpath_CONTRACT_VERSION, 3u);  // version 4 added AccelBlockV2 and kept this
  EXPECT_EQ(TopicTraits<gearpath_MachineHealth>::kName, "gearpath/MachineHealth");
  EXPECT_EQ(TopicTraits<gearpath_MachineHealth>::kClass, TopicClass::kStatus);
  // Status is unchanged: its machines stay bounded by 64 (the first 64 of a daemon).
  EXPECT_EQ(gearpath_MAX_MACHINES, 64u);
}

TEST(ContractV3, MachineHealthIsWrittenInXcdr1AndKeyedByDaemonAndMachine) {
  testing::LoopbackPair pair;
  testing::ExpectWrittenInXcdr1<gearpath_MachineHealth>(pair.publisher);

  const dds_topic_descriptor_t& d = gearpath_MachineHealth_desc;
  ASSERT_EQ(d.m_nkeys, 2u);
  EXPECT_STREQ(d.m_keys[0].m_name, "daemon_id");
  EXPECT_STREQ(d.m_keys[1].m_name, "machine_id");
}

// Takes every sample that arrives within `timeout` until `count` have, keyed by
// "daemon/machine".
bool TakeSamples(testing::LoopbackLink<gearpath_MachineHealth>& link, std::size_t count,
                 std::map<std::string, Owned<gearpath_MachineHealth>>& out) {
  std::vector<Owned<gearpath_MachineHealth>> samples(8);
  std::vector<SampleInfo> infos(8);
  const auto deadline = std::chrono::steady_clock::now() + seconds(10);
  while (out.size() < count && std::chrono::steady_clock::now() < deadline) {
    std::array<dds_attach_t, 1> triggered{};
    if (!link.waitset.Wait(triggered, seconds(1))) return false;
    auto n = link.reader.Take(samples, infos);
    if (!n) return false;
    for (std::size_t i = 0; i < *n; ++i) {
      if (!infos[i].valid_data) continue;
      const std::string key = std::string(GetString(samples[i]->daemon_id)) + "/" +
                              std::string(GetString(samples[i]->machine_id));
      out[key] = std::move(samples[i]);
    }
  }
  return out.size() >= count;
}

TEST(ContractV3, MachineHealthArrivesFieldByFieldOneInstancePerDaemonAndMachine) {
  testing::LoopbackPair pair;
  testing::LoopbackLink<gearpath_MachineHealth> link(pair);
  ASSERT_TRUE(link.writer.WaitForReaders(1, seconds(10)));

  Owned<gearpath_MachineHealth> sent;
  ASSERT_TRUE(SetString(sent->daemon_id, "gearpathd-a"));
  ASSERT_TRUE(SetString(sent->machine_id, "gearbox-99"));
  sent->daemon_state = gearpath_RUNNING;
  sent->timestamp_ns = 1'763'769'600'123'456'789LL;
  sent->machine_index = 99;
  sent->machine_count = 100;
  sent->fault_state = gearpath_SUSPECTED;
  sent->publishing_results = true;
  sent->last_block_sequence = 123456789012ULL;
  sent->last_block_t0_ns = 1'763'769'599'000'000'000LL;
  sent->blocks_received = 10;
  sent->blocks_processed = 7;
  sent->blocks_rejected = 3;
  sent->blocks_lost = 2;
  ASSERT_TRUE(SetString(sent->last_rejection_reason, "wrong_sample_rate: 4000 Hz, not 8000 Hz"));
  sent->last_alpha = 1e-3;
  sent->last_condition_number = 42.5;
  sent->last_relative_residual = 0.125;
  sent->latency_last_ms = 12.5;
  sent->latency_max_ms = 80.25;
  ASSERT_TRUE(link.writer.Write(*sent));
  // The same machine as seen by a standby: another instance, not a replacement.
  ASSERT_TRUE(SetString(sent->daemon_id, "gearpathd-b"));
  sent->publishing_results = false;
  ASSERT_TRUE(link.writer.Write(*sent));

  std::map<std::string, Owned<gearpath_MachineHealth>> got;
  ASSERT_TRUE(TakeSamples(link, 2, got)) << got.size() << " of 2 instances";
  ASSERT_EQ(got.count("gearpathd-a/gearbox-99"), 1u);
  ASSERT_EQ(got.count("gearpathd-b/gearbox-99"), 1u);
  const gearpath_MachineHealth& a = *got["gearpathd-a/gearbox-99"];
  EXPECT_EQ(a.daemon_state, gearpath_RUNNING);
  EXPECT_EQ(a.timestamp_ns, 1'763'769'600'123'456'789LL);
  EXPECT_EQ(a.machine_index, 99u);
  EXPECT_EQ(a.machine_count, 100u);
  EXPECT_EQ(a.fault_state, gearpath_SUSPECTED);
  EXPECT_TRUE(a.publishing_results);
  EXPECT_EQ(a.last_block_sequence, 123456789012ULL);
  EXPECT_EQ(a.last_block_t0_ns, 1'763'769'599'000'000'000LL);
  EXPECT_EQ(a.blocks_received, 10u);
  EXPECT_EQ(a.blocks_processed, 7u);
  EXPECT_EQ(a.blocks_rejected, 3u);
  EXPECT_EQ(a.blocks_lost, 2u);
  EXPECT_EQ(GetString(a.last_rejection_reason), "wrong_sample_rate: 4000 Hz, not 8000 Hz");
  EXPECT_EQ(a.last_alpha, 1e-3);
  EXPECT_EQ(a.last_condition_number, 42.5);
  EXPECT_EQ(a.last_relative_residual, 0.125);
  EXPECT_EQ(a.latency_last_ms, 12.5);
  EXPECT_EQ(a.latency_max_ms, 80.25);
  EXPECT_FALSE(got["gearpathd-b/gearbox-99"]->publishing_results);
}

// What a daemon does when a reload removes a machine: the reader sees the instance disposed,
// here (its last sample already taken) on an invalid sample carrying only the key.
TEST(ContractV3, ADisposedMachineHealthInstanceReachesTheReaderWithItsKey) {
  testing::LoopbackPair pair;
  testing::LoopbackLink<gearpath_MachineHealth> link(pair);
  ASSERT_TRUE(link.writer.WaitForReaders(1, seconds(10)));
  Owned<gearpath_MachineHealth> sent;
  ASSERT_TRUE(SetString(sent->daemon_id, "gearpathd-a"));
  ASSERT_TRUE(SetString(sent->machine_id, "gearbox-99"));
  sent->blocks_received = 1;
  ASSERT_TRUE(link.writer.Write(*sent));
  std::map<std::string, Owned<gearpath_MachineHealth>> got;
  ASSERT_TRUE(TakeSamples(link, 1, got));

  Owned<gearpath_MachineHealth> key;
  ASSERT_TRUE(SetString(key->daemon_id, "gearpathd-a"));
  ASSERT_TRUE(SetString(key->machine_id, "gearbox-99"));
  ASSERT_TRUE(link.writer.Dispose(*key));
  std::vector<Owned<gearpath_MachineHealth>> samples(4);
  std::vector<SampleInfo> infos(4);
  bool disposed = false;
  const auto deadline = std::chrono::steady_clock::now() + seconds(10);
  while (!disposed && std::chrono::steady_clock::now() < deadline) {
    std::array<dds_attach_t, 1> triggered{};
    ASSERT_TRUE(link.waitset.Wait(triggered, seconds(1)));
    auto n = link.reader.Take(samples, infos);
    ASSERT_TRUE(n);
    for (std::size_t i = 0; i < *n; ++i) {
      disposed = disposed || (infos[i].instance_state == DDS_NOT_ALIVE_DISPOSED_INSTANCE_STATE &&
                              GetString(samples[i]->machine_id) == "gearbox-99" &&
                              GetString(samples[i]->daemon_id) == "gearpathd-a");
    }
  }
  EXPECT_TRUE(disposed);
}

}  // namespace
}  // namespace gearpath::dds
