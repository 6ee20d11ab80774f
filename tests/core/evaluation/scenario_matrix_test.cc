// Scenario matrix: sizes, held-out filtering, seeds fixed by identity, quick inside full and
// covering every level.
#include "core/evaluation/scenario_matrix.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <iterator>
#include <map>
#include <set>

namespace gearpath {
namespace {

// Position of `s` in `all` (by key), to check that a subset keeps the matrix order.
std::size_t full_index(const std::vector<Scenario>& all, const Scenario& s) {
  for (std::size_t i = 0; i < all.size(); ++i) {
    if (all[i].Key() == s.Key()) return i;
  }
  return all.size();
}

TEST(ScenarioMatrix, FullIsTheWholeFactorial) {
  MatrixFilter all;
  all.held_out = HeldOutSelection::kInclude;
  const std::vector<Scenario> full = EnumerateScenarios(MatrixSize::kFull, all);
  // 4 families x 2 trains x (4 kinds x 4 gears + 4 healthy replicas) x 5 speeds x 3 noise
  // x 2 channel sets x 2 (unmodelled off / on).
  EXPECT_EQ(full.size(), 4u * 2u * 20u * 5u * 3u * 2u * 2u);
  std::set<std::string> keys;
  std::set<std::uint64_t> seeds;
  for (std::size_t i = 0; i < full.size(); ++i) {
    EXPECT_EQ(full[i].index, i);
    keys.insert(full[i].Key());
    seeds.insert(full[i].seed);
  }
  EXPECT_EQ(keys.size(), full.size());
  EXPECT_EQ(seeds.size(), full.size());
}

TEST(ScenarioMatrix, HeldOutFamiliesAreExcludedByDefault) {
  for (const Scenario& s : EnumerateScenarios(MatrixSize::kQuick)) {
    EXPECT_NE(s.family, PlantFamily::kParametricPlate);
    EXPECT_FALSE(s.held_out());
  }
  MatrixFilter only;
  only.held_out = HeldOutSelection::kOnly;
  const std::vector<Scenario> held = EnumerateScenarios(MatrixSize::kQuick, only);
  ASSERT_EQ(held.size(), std::size(kHeldOutFamilies) * 2u * 20u);  // per family: 2 trains x 20 cells
  for (const Scenario& s : held) EXPECT_TRUE(s.held_out());
  MatrixFilter plate;
  plate.held_out = HeldOutSelection::kOnly;
  plate.families = {PlantFamily::kParametricPlate};
  const std::vector<Scenario> plates = EnumerateScenarios(MatrixSize::kQuick, plate);
  ASSERT_EQ(plates.size(), 2u * 20u);
  for (const Scenario& s : plates) EXPECT_EQ(s.family, PlantFamily::kParametricPlate);
  MatrixFilter one;
  one.families = {PlantFamily::kLumpedTorsional};
  for (const Scenario& s : EnumerateScenarios(MatrixSize::kQuick, one)) {
    EXPECT_EQ(s.family, PlantFamily::kLumpedTorsional);
  }
}

TEST(ScenarioMatrix, QuickIsASubsetOfFullWithTheSameSeedsAndCoversEveryLevel) {
  MatrixFilter all;
  all.held_out = HeldOutSelection::kInclude;
  std::map<std::string, std::uint64_t> full;
  for (const Scenario& s : EnumerateScenarios(MatrixSize::kFull, all)) full[s.Key()] = s.seed;
  const std::vector<Scenario> quick = EnumerateScenarios(MatrixSize::kQuick, all);
  EXPECT_EQ(quick.size(), 4u * 2u * 20u);
  std::map<PlantFamily, std::set<std::string>> levels;
  for (const Scenario& s : quick) {
    ASSERT_TRUE(full.count(s.Key())) << s.Key();
    EXPECT_EQ(full[s.Key()], s.seed);
    EXPECT_EQ(s.seed, ScenarioSeed(s.Key()));
    std::set<std::string>& l = levels[s.family];
    l.insert("rpm" + std::to_string(static_cast<int>(s.input_rpm)));
    l.insert("noise" + std::to_string(static_cast<int>(s.noise * 100)));
    l.insert(std::string("ch") + std::string(ChannelSetName(s.channels)));
    l.insert(s.unmodelled ? "disturbed" : "clean");
    l.insert(std::string(TrainVariantName(s.variant)));
  }
  for (const auto& [family, l] : levels) {
    EXPECT_EQ(l.size(), 5u + 3u + 2u + 2u + 2u) << PlantFamilyName(family);
  }
}

TEST(ScenarioMatrix, KeyFilterKeepsOnlyMatchingScenarios) {
  MatrixFilter f;
  f.key_contains = "/mesh_am/G3/";
  const std::vector<Scenario> some = EnumerateScenarios(MatrixSize::kFull, f);
  // Tuning families (all but the held-out list) x 2 trains x 5 speeds x 3 noise x 2 channel
  // sets x 2 unmodelled.
  const std::size_t tuning_families = std::size(kAllPlantFamilies) - std::size(kHeldOutFamilies);
  ASSERT_EQ(some.size(), tuning_families * 2u * 5u * 3u * 2u * 2u);
  for (std::size_t i = 0; i < some.size(); ++i) {
    EXPECT_EQ(some[i].index, i);
    EXPECT_EQ(some[i].fault, PlantFaultKind::kMeshAm);
    EXPECT_EQ(some[i].gear, "G3");
  }
  f.key_contains = "no such key";
  EXPECT_TRUE(EnumerateScenarios(MatrixSize::kFull, f).empty());
}

TEST(ScenarioMatrix, SampleIsTheSmallestSeedsInMatrixOrder) {
  const std::vector<Scenario> full = EnumerateScenarios(MatrixSize::kFull);
  const std::vector<Scenario> sample = SampleScenarios(full, 300);
  ASSERT_EQ(sample.size(), 300u);
  std::vector<std::uint64_t> seeds;
  for (const Scenario& s : full) seeds.push_back(s.seed);
  std::sort(seeds.begin(), seeds.end());
  std::set<std::uint64_t> smallest(seeds.begin(), seeds.begin() + 300);
  std::size_t healthy = 0;
  std::map<double, std::size_t> by_speed;
  for (std::size_t i = 0; i < sample.size(); ++i) {
    EXPECT_EQ(sample[i].index, i);
    EXPECT_TRUE(smallest.count(sample[i].seed)) << sample[i].Key();
    if (i > 0) {
      EXPECT_LT(full_index(full, sample[i - 1]), full_index(full, sample[i]));
    }
    healthy += sample[i].fault == PlantFaultKind::kNone;
    ++by_speed[sample[i].input_rpm];
  }
  // A uniform draw: a fifth healthy and a fifth per speed, within ~4 binomial sigmas.
  EXPECT_NEAR(static_cast<double>(healthy), 60.0, 28.0);
  ASSERT_EQ(by_speed.size(), 5u);
  for (const auto& [rpm, n] : by_speed) EXPECT_NEAR(static_cast<double>(n), 60.0, 28.0) << rpm;
  EXPECT_EQ(SampleScenarios(full, 300).front().Key(), sample.front().Key());  // same every run
  EXPECT_EQ(SampleScenarios(full, full.size() + 1).size(), full.size());
}

TEST(ScenarioMatrix, SpeedBands) {
  EXPECT_EQ(SpeedBand(200), "below");
  EXPECT_EQ(SpeedBand(300), "nominal");
  EXPECT_EQ(SpeedBand(600), "nominal");
  EXPECT_EQ(SpeedBand(900), "above");
  EXPECT_EQ(ParseMatrixSize("quick"), MatrixSize::kQuick);
  EXPECT_FALSE(ParseMatrixSize("medium").has_value());
}

}  // namespace
}  // namespace gearpath
