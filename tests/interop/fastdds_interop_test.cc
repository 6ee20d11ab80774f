// Fast DDS interoperability (issue 12): a plant client on Fast DDS (fastdds_plant_client, types
// from fastddsgen, participant from config/fastdds-profiles.xml) against a running gearpathd on
// Cyclone DDS, over loopback.
//
// The client publishes AccelBlocks, and its last block as an AccelBlockV2 with its load (contract
// version 4), that gearpathd must process, and subscribes to every result
// topic. Meanwhile this test's Cyclone readers (the project's own binding) receive the same
// result samples from the daemon. Every result of every block, and every Status and
// MachineHealth sample both saw, must decode to the same value field by field in both stacks;
// the daemon's counters, read through Cyclone, must say that the Fast DDS blocks were processed.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdint>
#include <fstream>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "tests/integration/gearpathd_fixture.h"
#include "tests/interop/cyclone_sample_json.h"

namespace gearpath::testing {
namespace {

using namespace std::chrono_literals;
using nlohmann::json;

constexpr int kBlocks = 6;  // more than the test baseline (4 blocks): LEARNING and after
constexpr int kClientTimeoutS = 150;

// NaN and infinities become null, numbers take one representation: the form both decodings
// are compared in (the client's lines went through the same dump and parse).
json Normalised(const json& j) { return json::parse(j.dump()); }

std::string AxisName(Axis axis) { return axis == Axis::kY ? "y" : axis == Axis::kZ ? "z" : "x"; }

// The client's decodings: topic -> its samples in arrival order.
std::map<std::string, std::vector<json>> ReadClientSamples(const std::string& path) {
  std::map<std::string, std::vector<json>> samples;
  std::ifstream in(path);
  for (std::string line; std::getline(in, line);) {
    json j = json::parse(line, nullptr, /*allow_exceptions=*/false);
    if (j.is_discarded() || !j.contains("topic") || !j.contains("sample")) continue;
    samples[j["topic"].get<std::string>()].push_back(j["sample"]);
  }
  return samples;
}

// One field-by-field comparison: the differences as a JSON patch (path, Fast DDS value).
void ExpectSameDecoding(const json& cyclone, const json& fastdds, const std::string& what) {
  const json differences = json::diff(cyclone, fastdds);
  EXPECT_TRUE(differences.empty())
      << what << " decodes differently in Fast DDS than in Cyclone "
      << "(JSON patch from the Cyclone decoding to Fast DDS'): " << differences.dump()
      << "\nCyclone: " << cyclone.dump();
}

class FastDdsInterop : public GearpathdOverDds {
 protected:
  // Takes what `reader` has for our machine into `by_sequence`, until it holds every block's
  // result or `timeout` passes.
  template <typename T>
  bool CollectResults(dds::Reader<T>& reader, std::map<std::uint64_t, json>& by_sequence,
                      std::chrono::milliseconds timeout) {
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    std::vector<dds::Owned<T>> samples(8);
    std::vector<dds::SampleInfo> infos(8);
    for (;;) {
      auto n = reader.Take(samples, infos);
      if (!n) return false;
      for (std::size_t i = 0; i < *n; ++i) {
        if (infos[i].valid_data && dds::GetString(samples[i]->machine_id) == machine_id_) {
          by_sequence[samples[i]->block_sequence] = Normalised(ToJson(*samples[i]));
        }
      }
      if (by_sequence.size() >= static_cast<std::size_t>(kBlocks)) return true;
      if (std::chrono::steady_clock::now() >= deadline) return false;
      std::this_thread::sleep_for(20ms);
    }
  }

  // Takes our daemon's Status and our machine's MachineHealth samples, keyed by timestamp_ns.
  void CollectStatus(dds::Reader<gearpath_MachineHealth>& health_reader) {
    std::vector<dds::Owned<gearpath_Status>> status(8);
    std::vector<dds::Owned<gearpath_MachineHealth>> health(8);
    std::vector<dds::SampleInfo> infos(8);
    auto n = status_reader_->Take(status, infos);
    ASSERT_TRUE(n.ok()) << n.error();
    for (std::size_t i = 0; i < *n; ++i) {
      if (infos[i].valid_data && dds::GetString(status[i]->daemon_id) == daemon_id_) {
        cyclone_status_[status[i]->timestamp_ns] = Normalised(ToJson(*status[i]));
      }
    }
    n = health_reader.Take(health, infos);
    ASSERT_TRUE(n.ok()) << n.error();
    for (std::size_t i = 0; i < *n; ++i) {
      if (infos[i].valid_data && dds::GetString(health[i]->daemon_id) == daemon_id_ &&
          dds::GetString(health[i]->machine_id) == machine_id_) {
        cyclone_health_[health[i]->timestamp_ns] = Normalised(ToJson(*health[i]));
        last_health_ = *health[i];
      }
    }
  }

  std::vector<std::string> ClientArguments(const std::string& out_path) const {
    std::vector<std::string> args = {
        "--domain",
        std::to_string(domain_id_),
        "--profiles",
        std::string(GEARPATH_SOURCE_DIR) + "/config/fastdds-profiles.xml",
        "--participant-profile",
        "gearpath_loopback",
        "--daemon",
        daemon_id_,
        "--machine",
        machine_id_,
        "--blocks",
        std::to_string(kBlocks),
        "--samples-per-channel",
        std::to_string(kBlockLength),
        "--sample-rate-hz",
        std::to_string(kSampleRate),
        "--speed-hz",
        "10",
        "--timeout-s",
        std::to_string(kClientTimeoutS),
        "--out",
        out_path};
    for (const ChannelInfo& c : channels_) {
      args.insert(args.end(), {"--channel", c.sensor + ":" + AxisName(c.axis)});
    }
    return args;
  }

  std::map<std::int64_t, json> cyclone_status_;  // our daemon's Status by timestamp_ns
  std::map<std::int64_t, json> cyclone_health_;  // our machine's MachineHealth by timestamp_ns
  gearpath_MachineHealth last_health_{};
};

TEST_F(FastDdsInterop, GearpathdProcessesFastDdsBlocksAndFastDdsDecodesEveryResultAsCycloneDoes) {
  dds::Topic<gearpath_MachineHealth> health_topic(*participant_);
  dds::Reader<gearpath_MachineHealth> health_reader(health_topic);

  const std::string out_path = (dir_ / "fastdds_samples.jsonl").string();
  ChildProcess client(FASTDDS_PLANT_CLIENT_PATH, ClientArguments(out_path),
                      (dir_ / "fastdds_plant_client.log").string());
  ASSERT_TRUE(client.started());
  const auto logs = [&] {
    return "\n--- fastdds_plant_client log:\n" + client.Log() + "\n--- gearpathd log:\n" +
           daemon_->Log();
  };

  // The client discovers the daemon, publishes its blocks and exits once it has every result;
  // meanwhile our Cyclone readers keep the Status and MachineHealth samples to compare with.
  const auto deadline =
      std::chrono::steady_clock::now() + std::chrono::seconds(kClientTimeoutS + 30);
  std::optional<int> exit_code;
  while (!(exit_code = client.WaitExit(50ms)).has_value()) {
    ASSERT_NO_FATAL_FAILURE(CollectStatus(health_reader));
    ASSERT_LT(std::chrono::steady_clock::now(), deadline) << "the client did not exit" << logs();
  }
  ASSERT_EQ(*exit_code, 0) << "the Fast DDS client failed" << logs();

  // 1. gearpathd processed the Fast DDS-published blocks: its own counters, read by Cyclone.
  const auto counted_deadline = std::chrono::steady_clock::now() + 30s;
  while (last_health_.blocks_processed < kBlocks &&
         std::chrono::steady_clock::now() < counted_deadline) {
    ASSERT_NO_FATAL_FAILURE(CollectStatus(health_reader));
    std::this_thread::sleep_for(20ms);
  }
  EXPECT_EQ(last_health_.blocks_received, static_cast<std::uint64_t>(kBlocks)) << logs();
  EXPECT_EQ(last_health_.blocks_processed, static_cast<std::uint64_t>(kBlocks)) << logs();
  EXPECT_EQ(last_health_.blocks_rejected, 0u) << dds::GetString(last_health_.last_rejection_reason);
  EXPECT_EQ(last_health_.blocks_lost, 0u);
  EXPECT_EQ(last_health_.last_block_sequence, static_cast<std::uint64_t>(kBlocks));

  // 2. Every result of every block, as Cyclone decoded it.
  std::map<std::string, std::map<std::uint64_t, json>> cyclone;
  EXPECT_TRUE(CollectResults(*dominant_reader_, cyclone["DominantPath"], 30s));
  EXPECT_TRUE(CollectResults(*gear_reader_, cyclone["SuspectedGear"], 30s));
  EXPECT_TRUE(CollectResults(*indicators_reader_, cyclone["EnvelopeIndicators"], 30s));
  EXPECT_TRUE(CollectResults(*condition_reader_, cyclone["ConditionIndicators"], 30s));

  // 3. ... and as Fast DDS decoded it: the same, field by field.
  auto fastdds = ReadClientSamples(out_path);
  for (const auto& [topic, by_sequence] : cyclone) {
    std::map<std::uint64_t, json> fastdds_by_sequence;
    for (const json& s : fastdds[topic]) {
      if (s["machine_id"] == machine_id_) {
        fastdds_by_sequence[s["block_sequence"].get<std::uint64_t>()] = s;
      }
    }
    for (std::uint64_t seq = 1; seq <= kBlocks; ++seq) {
      SCOPED_TRACE(topic + " of block " + std::to_string(seq));
      ASSERT_TRUE(by_sequence.count(seq)) << "Cyclone did not receive it";
      ASSERT_TRUE(fastdds_by_sequence.count(seq)) << "Fast DDS did not receive it";
      ExpectSameDecoding(by_sequence.at(seq), fastdds_by_sequence.at(seq),
                         topic + " #" + std::to_string(seq));
    }
  }

  // The verdicts also meet the contract's invariants (docs/topics.md), so the comparison is
  // not between two equally wrong decodings: the baseline (4 blocks) is learned first.
  for (const auto& [seq, verdict] : cyclone["SuspectedGear"]) {
    SCOPED_TRACE("SuspectedGear of block " + std::to_string(seq));
    EXPECT_EQ(verdict["machine_id"], machine_id_);
    const int state = verdict["state"];
    EXPECT_GE(state, gearpath_NO_FAULT);
    EXPECT_LE(state, gearpath_LEARNING);
    if (seq == 1) {
      EXPECT_EQ(state, gearpath_LEARNING);
    }
    const double confidence = verdict["confidence"];
    EXPECT_GE(confidence, 0.0);
    EXPECT_LE(confidence, 1.0);
    if (state == gearpath_LEARNING || state == gearpath_NO_FAULT) {
      EXPECT_EQ(verdict["gear_name"], "");
    }
  }

  // 4. Status and MachineHealth: every sample both stacks received is decoded alike.
  const auto compare_status = [&](const std::string& topic,
                                  const std::map<std::int64_t, json>& by_time) {
    int common = 0;
    for (const json& s : fastdds[topic]) {
      if (s["daemon_id"] != daemon_id_ ||
          (s.contains("machine_id") && s["machine_id"] != machine_id_)) {
        continue;
      }
      const auto it = by_time.find(s["timestamp_ns"].get<std::int64_t>());
      if (it == by_time.end()) continue;
      ++common;
      ExpectSameDecoding(it->second, s, topic + " at " + std::to_string(it->first));
    }
    EXPECT_GT(common, 0) << "no " << topic << " sample was received by both stacks (Fast DDS "
                         << fastdds[topic].size() << ", Cyclone " << by_time.size() << ")";
  };
  compare_status("Status", cyclone_status_);
  compare_status("MachineHealth", cyclone_health_);
}

}  // namespace
}  // namespace gearpath::testing
