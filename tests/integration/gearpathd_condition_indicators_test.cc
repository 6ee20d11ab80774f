// Contract version 2 end to end over loopback DDS: LEARNING on the wire while the baseline is
// learned, the ConditionIndicators topic with the block score, the thresholds and criterion
// values on the older topics; and a machine monitored before its FRFs are measured
// (`"frf_set": "identity"`) starts and processes blocks.
#include <cmath>
#include <map>
#include <string>
#include <string_view>
#include <utility>

#include "tests/integration/gearpathd_fixture.h"

namespace gearpath::testing {
namespace {

constexpr int kLearningBlocks = 4;  // the fixture's baseline.learning_blocks


bool IsBlock(std::uint64_t sequence, std::uint64_t want) { return sequence == want; }

TEST_F(GearpathdOverDds, TheWireSaysLearningWithProgressThenScoresAgainstALimit) {
  // Half the baseline: every verdict is LEARNING and nothing is judged yet.
  std::uint64_t seq = 1;
  for (; seq <= kLearningBlocks / 2; ++seq) Publish(NoiseBlock(seq));
  std::uint64_t last = seq - 1;
  ASSERT_TRUE(WaitStatus([&](const auto& m) { return m.blocks_processed == last; }, 60s))
      << last_status_.last_rejection_reason;

  auto gear = WaitResult<gearpath_SuspectedGear>(
      *gear_reader_, [&](const auto& r) { return IsBlock(r.block_sequence, last); }, 10s);
  ASSERT_TRUE(gear.has_value());
  EXPECT_EQ((*gear)->state, gearpath_LEARNING) << (*gear)->reason;
  EXPECT_EQ(dds::GetString((*gear)->gear_name), "");

  auto learning = WaitResult<gearpath_ConditionIndicators>(
      *condition_reader_, [&](const auto& r) { return IsBlock(r.block_sequence, last); }, 10s);
  ASSERT_TRUE(learning.has_value());
  EXPECT_EQ((*learning)->limit_z, 0.0);
  EXPECT_EQ((*learning)->baseline_blocks_needed, std::uint32_t{kLearningBlocks});
  EXPECT_LE((*learning)->baseline_blocks_learned, std::uint32_t{kLearningBlocks / 2});
  EXPECT_EQ((*learning)->sets_omitted, 0u);
  EXPECT_EQ((*learning)->values_omitted, 0u);
  // Every (signal, rate) set: the measured channels, the paths' contributions and forces.
  std::map<int, int> sources;
  ASSERT_GT((*learning)->sets._length, 0u);
  for (const auto& set : dds::View((*learning)->sets)) {
    ++sources[static_cast<int>(set.source)];
    EXPECT_FALSE(dds::GetString(set.signal).empty());
    EXPECT_FALSE(dds::GetString(set.shaft).empty());
    EXPECT_GT(set.shaft_hz, 0.0);
    ASSERT_GT(set.values._length, 0u);
    for (const auto& v : dds::View(set.values)) {
      EXPECT_FALSE(dds::GetString(v.name).empty());
      EXPECT_TRUE(std::isfinite(v.value)) << dds::GetString(v.name);
      EXPECT_EQ(v.z, 0.0) << "no z-score before the baseline is complete";
    }
  }
  EXPECT_GT(sources[gearpath_SIGNAL_MEASURED], 0);
  EXPECT_GT(sources[gearpath_SIGNAL_CONTRIBUTION], 0);
  EXPECT_EQ(sources[gearpath_SIGNAL_CONTRIBUTION], sources[gearpath_SIGNAL_FORCE]);

  auto envelope = WaitResult<gearpath_EnvelopeIndicators>(
      *indicators_reader_, [&](const auto& r) { return IsBlock(r.block_sequence, last); }, 10s);
  ASSERT_TRUE(envelope.has_value());
  for (const auto& s : dds::View((*envelope)->shafts)) {
    EXPECT_EQ(s.raw_threshold, 0.0);
    EXPECT_EQ(s.reconstructed_threshold, 0.0);
  }

  // The rest of the baseline and two more: judged against a limit, the baseline complete.
  for (; seq <= kLearningBlocks + 2; ++seq) Publish(NoiseBlock(seq));
  last = seq - 1;
  ASSERT_TRUE(WaitStatus([&](const auto& m) { return m.blocks_processed == last; }, 60s))
      << last_status_.last_rejection_reason;
  gear = WaitResult<gearpath_SuspectedGear>(
      *gear_reader_, [&](const auto& r) { return IsBlock(r.block_sequence, last); }, 10s);
  ASSERT_TRUE(gear.has_value());
  EXPECT_NE((*gear)->state, gearpath_LEARNING) << (*gear)->reason;
  auto judged = WaitResult<gearpath_ConditionIndicators>(
      *condition_reader_, [&](const auto& r) { return IsBlock(r.block_sequence, last); }, 10s);
  ASSERT_TRUE(judged.has_value());
  EXPECT_GT((*judged)->limit_z, 0.0);
  EXPECT_GT((*judged)->window, 0u);
  EXPECT_LE((*judged)->exceed_count, (*judged)->window);
  EXPECT_EQ((*judged)->baseline_blocks_learned, (*judged)->baseline_blocks_needed);
  EXPECT_TRUE(std::isfinite((*judged)->score));
  EXPECT_FALSE(dds::GetString((*judged)->top_indicator).empty());
  envelope = WaitResult<gearpath_EnvelopeIndicators>(
      *indicators_reader_, [&](const auto& r) { return IsBlock(r.block_sequence, last); }, 10s);
  ASSERT_TRUE(envelope.has_value());
  for (const auto& s : dds::View((*envelope)->shafts)) {
    EXPECT_GT(s.raw_threshold, 0.0) << dds::GetString(s.shaft_name);
    EXPECT_GT(s.reconstructed_threshold, 0.0) << dds::GetString(s.shaft_name);
  }
  auto dominant = WaitResult<gearpath_DominantPath>(
      *dominant_reader_, [&](const auto& r) { return IsBlock(r.block_sequence, last); }, 10s);
  ASSERT_TRUE(dominant.has_value());
  // The dominant path is the one with the largest criterion value, whatever its share.
  const auto paths = dds::View((*dominant)->paths);
  ASSERT_LT((*dominant)->path_index, paths.size());
  for (const auto& p : paths) {
    EXPECT_GE(p.criterion, 0.0);
    EXPECT_LE(p.criterion, paths[(*dominant)->path_index].criterion) << dds::GetString(p.name);
  }
}

// Monitoring before the hammer test: the built-in set's channels, each its own path with the
// gears of its bearing seat.
class GearpathdIdentityFrfSet : public GearpathdOverDds {
 protected:
  void Configure(json& config) override {
    auto set = daemon::BuiltinFrfSet("table1");
    ASSERT_TRUE(set.ok()) << set.error();
    json channels = json::array();
    for (std::size_t i = 0; i < set->channels.size(); ++i) {
      channels.push_back({{"sensor", set->channels[i].sensor},
                          {"axis", set->channels[i].axis},
                          {"gears", set->paths[i].gears}});
    }
    config["machines"][0]["frf_set"] = "identity";
    config["machines"][0]["channels"] = channels;
  }
};

TEST_F(GearpathdIdentityFrfSet, AMachineWithoutMeasuredFrfsStartsAndProcessesBlocks) {
  std::uint64_t seq = 1;
  for (; seq <= kLearningBlocks + 1; ++seq) Publish(NoiseBlock(seq));
  const std::uint64_t last = seq - 1;
  ASSERT_TRUE(WaitStatus([&](const auto& m) { return m.blocks_processed == last; }, 60s))
      << "processed " << last_status_.blocks_processed << ", rejected "
      << last_status_.blocks_rejected << ": " << last_status_.last_rejection_reason;
  EXPECT_EQ(last_status_.blocks_rejected, 0u);

  // One path per sensor channel, named "<sensor>/<axis>".
  auto dominant = WaitResult<gearpath_DominantPath>(
      *dominant_reader_, [&](const auto& r) { return IsBlock(r.block_sequence, last); }, 10s);
  ASSERT_TRUE(dominant.has_value());
  ASSERT_EQ((*dominant)->paths._length, channels_.size());
  EXPECT_EQ(dds::GetString((*dominant)->paths._buffer[0].name), channels_[0].sensor + "/x");

  // The alarm model runs: the baseline completed and the block was judged against a limit.
  auto gear = WaitResult<gearpath_SuspectedGear>(
      *gear_reader_, [&](const auto& r) { return IsBlock(r.block_sequence, last); }, 10s);
  ASSERT_TRUE(gear.has_value());
  EXPECT_NE((*gear)->state, gearpath_LEARNING) << (*gear)->reason;
  auto condition = WaitResult<gearpath_ConditionIndicators>(
      *condition_reader_, [&](const auto& r) { return IsBlock(r.block_sequence, last); }, 10s);
  ASSERT_TRUE(condition.has_value());
  EXPECT_GT((*condition)->limit_z, 0.0);

  // H = I: a path's force and its contribution are the measured signal of its own channel, so
  // their indicators are the measured channel's (up to the regulariser's filter factor).
  std::map<std::pair<std::string, std::string>, const gearpath_IndicatorSet*> measured;
  const auto sets = dds::View((*condition)->sets);
  for (const auto& set : sets) {
    if (set.source == gearpath_SIGNAL_MEASURED) {
      measured[{std::string(dds::GetString(set.signal)), std::string(dds::GetString(set.shaft))}] =
          &set;
    }
  }
  int compared = 0;
  for (const auto& set : sets) {
    if (set.source == gearpath_SIGNAL_MEASURED || set.revolutions == 0) continue;
    const auto it = measured.find(
        {std::string(dds::GetString(set.signal)), std::string(dds::GetString(set.shaft))});
    ASSERT_NE(it, measured.end()) << "no measured channel named " << dds::GetString(set.signal);
    const auto a = dds::View(set.values);
    const auto b = dds::View(it->second->values);
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t k = 0; k < a.size(); ++k) {
      // Computed for the measured channels only (docs/condition_indicators.md): 0 here.
      if (std::string_view(dds::GetString(a[k].name)) == "synchronous_low_orders") {
        EXPECT_EQ(a[k].value, 0.0);
        continue;
      }
      EXPECT_NEAR(a[k].value, b[k].value, 1e-3 * std::max(1.0, std::abs(b[k].value)))
          << dds::GetString(set.signal) << " " << dds::GetString(a[k].name);
    }
    ++compared;
  }
  EXPECT_EQ(compared, 2 * static_cast<int>(measured.size()));
}

}  // namespace
}  // namespace gearpath::testing
