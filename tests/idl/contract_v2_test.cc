// Contract version 2 (idl/gearpath.idl, "Evolution rule"): every topic is encoded in XCDR1, the
// encoding Fast DDS 2.x reads; ConditionIndicators and the new fields of the older types
// survive a trip over loopback UDP.
#include <dds/dds.h>
#include <gtest/gtest.h>

#include <array>
#include <chrono>
#include <string>

#include "idl/dds/gearpath_topics.h"
#include "tests/idl/loopback_test_domains.h"

namespace gearpath::dds {
namespace {

using std::chrono::seconds;

// ExpectWrittenInXcdr1: loopback_test_domains.h.
TEST(ContractV2, EveryTopicIsWrittenInXcdr1WhichFastDds2Reads) {
  testing::LoopbackPair pair;
  testing::ExpectWrittenInXcdr1<gearpath_AccelBlock>(pair.publisher);
  testing::ExpectWrittenInXcdr1<gearpath_DominantPath>(pair.publisher);
  testing::ExpectWrittenInXcdr1<gearpath_SuspectedGear>(pair.publisher);
  testing::ExpectWrittenInXcdr1<gearpath_EnvelopeIndicators>(pair.publisher);
  testing::ExpectWrittenInXcdr1<gearpath_ConditionIndicators>(pair.publisher);
  testing::ExpectWrittenInXcdr1<gearpath_Status>(pair.publisher);
}

TEST(ContractV2, TheVersionAndTheNewTopicNameAreThoseDocumented) {
  // Version 3 (contract_v3_test.cc) added a topic and changed no version-2 type.
  EXPECT_GE(gearpath_CONTRACT_VERSION, 2u);
  EXPECT_EQ(TopicTraits<gearpath_ConditionIndicators>::kName, "gearpath/ConditionIndicators");
  EXPECT_EQ(TopicTraits<gearpath_ConditionIndicators>::kClass, TopicClass::kLatestResult);
  // LEARNING was appended: the version-1 values are unchanged.
  EXPECT_EQ(gearpath_NO_FAULT, 0);
  EXPECT_EQ(gearpath_SUSPECTED, 1);
  EXPECT_EQ(gearpath_ALARM, 2);
  EXPECT_EQ(gearpath_LEARNING, 3);
}

// Waits for one sample on `link` (10 s deadline).
template <typename T>
bool TakeOne(testing::LoopbackLink<T>& link, Owned<T>& out) {
  std::vector<Owned<T>> samples(1);
  std::vector<SampleInfo> infos(1);
  const auto deadline = std::chrono::steady_clock::now() + seconds(10);
  while (std::chrono::steady_clock::now() < deadline) {
    std::array<dds_attach_t, 1> triggered{};
    if (!link.waitset.Wait(triggered, seconds(1))) return false;
    auto n = link.reader.Take(samples, infos);
    if (!n) return false;
    if (*n == 1 && infos[0].valid_data) {
      out = std::move(samples[0]);
      return true;
    }
  }
  return false;
}

void FillConditionIndicators(gearpath_ConditionIndicators& s) {
  ASSERT_TRUE(SetString(s.machine_id, "gearbox-7"));
  s.block_sequence = 123456789012ULL;
  s.block_t0_ns = 1'763'769'600'123'456'789LL;
  s.limit_z = 6.1;
  s.clear_level = 0.7;
  s.score = 0.42;
  ASSERT_TRUE(SetString(s.top_indicator, "sideband_G1-G2"));
  ASSERT_TRUE(SetString(s.top_signal, "B2x"));
  ASSERT_TRUE(SetString(s.top_shaft, "intermediate"));
  s.exceed_count = 2;
  s.window = 5;
  s.baseline_blocks_learned = 20;
  s.baseline_blocks_needed = 20;
  s.sets_omitted = 3;
  s.values_omitted = 4;
  ASSERT_TRUE(Resize(s.sets, 3));
  const gearpath_SignalSource sources[] = {gearpath_SIGNAL_MEASURED, gearpath_SIGNAL_CONTRIBUTION,
                                           gearpath_SIGNAL_FORCE};
  for (std::uint32_t i = 0; i < 3; ++i) {
    gearpath_IndicatorSet& set = MutableView(s.sets)[i];
    set.source = sources[i];
    ASSERT_TRUE(SetString(set.signal, i == 0 ? "A1/x" : "B2x"));
    ASSERT_TRUE(SetString(set.shaft, "input"));
    set.shaft_hz = 10.0 + i;
    set.revolutions = 19 + static_cast<std::int32_t>(i);
    set.score = -0.25 * i;
    ASSERT_TRUE(Resize(set.values, i + 1));
    for (std::uint32_t k = 0; k <= i; ++k) {
      gearpath_IndicatorValue& v = MutableView(set.values)[k];
      const std::string name(gearpath_INDICATOR_NAME_LENGTH, static_cast<char>('a' + k));
      ASSERT_TRUE(SetString(v.name, name));
      v.value = 1.0 / 3.0 + k;
      v.z = -2.0 * k;
    }
  }
}

TEST(ContractV2, ConditionIndicatorsArriveFieldByField) {
  testing::LoopbackPair pair;
  testing::LoopbackLink<gearpath_ConditionIndicators> link(pair);
  ASSERT_TRUE(link.writer.WaitForReaders(1, seconds(10)));
  Owned<gearpath_ConditionIndicators> sent;
  FillConditionIndicators(*sent);
  ASSERT_TRUE(link.writer.Write(*sent));
  Owned<gearpath_ConditionIndicators> got;
  ASSERT_TRUE(TakeOne(link, got));

  EXPECT_EQ(GetString(got->machine_id), "gearbox-7");
  EXPECT_EQ(got->block_sequence, sent->block_sequence);
  EXPECT_EQ(got->block_t0_ns, sent->block_t0_ns);
  EXPECT_EQ(got->limit_z, 6.1);
  EXPECT_EQ(got->clear_level, 0.7);
  EXPECT_EQ(got->score, 0.42);
  EXPECT_EQ(GetString(got->top_indicator), "sideband_G1-G2");
  EXPECT_EQ(GetString(got->top_signal), "B2x");
  EXPECT_EQ(GetString(got->top_shaft), "intermediate");
  EXPECT_EQ(got->exceed_count, 2u);
  EXPECT_EQ(got->window, 5u);
  EXPECT_EQ(got->baseline_blocks_learned, 20u);
  EXPECT_EQ(got->baseline_blocks_needed, 20u);
  EXPECT_EQ(got->sets_omitted, 3u);
  EXPECT_EQ(got->values_omitted, 4u);
  ASSERT_EQ(got->sets._length, 3u);
  for (std::uint32_t i = 0; i < 3; ++i) {
    const gearpath_IndicatorSet& a = View(sent->sets)[i];
    const gearpath_IndicatorSet& b = View(got->sets)[i];
    EXPECT_EQ(b.source, a.source);
    EXPECT_EQ(GetString(b.signal), GetString(a.signal));
    EXPECT_EQ(GetString(b.shaft), "input");
    EXPECT_EQ(b.shaft_hz, a.shaft_hz);
    EXPECT_EQ(b.revolutions, a.revolutions);
    EXPECT_EQ(b.score, a.score);
    ASSERT_EQ(b.values._length, i + 1);
    for (std::uint32_t k = 0; k <= i; ++k) {
      EXPECT_EQ(GetString(View(b.values)[k].name), GetString(View(a.values)[k].name));
      EXPECT_EQ(View(b.values)[k].value, View(a.values)[k].value);
      EXPECT_EQ(View(b.values)[k].z, View(a.values)[k].z);
    }
  }
}

TEST(ContractV2, TheNewFieldsOfTheOlderTopicsArriveToo) {
  testing::LoopbackPair pair;
  testing::LoopbackLink<gearpath_SuspectedGear> gears(pair);
  testing::LoopbackLink<gearpath_DominantPath> paths(pair);
  testing::LoopbackLink<gearpath_EnvelopeIndicators> envelope(pair);
  ASSERT_TRUE(gears.writer.WaitForReaders(1, seconds(10)));
  ASSERT_TRUE(paths.writer.WaitForReaders(1, seconds(10)));
  ASSERT_TRUE(envelope.writer.WaitForReaders(1, seconds(10)));

  Owned<gearpath_SuspectedGear> verdict;
  ASSERT_TRUE(SetString(verdict->machine_id, "gearbox-7"));
  verdict->state = gearpath_LEARNING;
  ASSERT_TRUE(gears.writer.Write(*verdict));
  Owned<gearpath_DominantPath> dominant;
  ASSERT_TRUE(SetString(dominant->machine_id, "gearbox-7"));
  dominant->criterion = gearpath_CRITERION_SIDEBAND_ENERGY;
  ASSERT_TRUE(Resize(dominant->paths, 2));
  MutableView(dominant->paths)[0].share = 0.34;
  MutableView(dominant->paths)[0].criterion = 7.5;
  MutableView(dominant->paths)[1].share = 0.66;
  MutableView(dominant->paths)[1].criterion = 2.5;
  ASSERT_TRUE(paths.writer.Write(*dominant));
  Owned<gearpath_EnvelopeIndicators> indicators;
  ASSERT_TRUE(SetString(indicators->machine_id, "gearbox-7"));
  ASSERT_TRUE(Resize(indicators->shafts, 1));
  MutableView(indicators->shafts)[0].raw_threshold = 0.125;
  MutableView(indicators->shafts)[0].reconstructed_threshold = 0.375;
  MutableView(indicators->shafts)[0].reconstructed_harmonics[4] = 9.0;
  ASSERT_TRUE(envelope.writer.Write(*indicators));

  Owned<gearpath_SuspectedGear> v;
  ASSERT_TRUE(TakeOne(gears, v));
  EXPECT_EQ(v->state, gearpath_LEARNING);
  Owned<gearpath_DominantPath> d;
  ASSERT_TRUE(TakeOne(paths, d));
  EXPECT_EQ(d->criterion, gearpath_CRITERION_SIDEBAND_ENERGY);
  ASSERT_EQ(d->paths._length, 2u);
  EXPECT_EQ(View(d->paths)[0].criterion, 7.5);
  EXPECT_EQ(View(d->paths)[1].share, 0.66);
  Owned<gearpath_EnvelopeIndicators> e;
  ASSERT_TRUE(TakeOne(envelope, e));
  ASSERT_EQ(e->shafts._length, 1u);
  EXPECT_EQ(View(e->shafts)[0].raw_threshold, 0.125);
  EXPECT_EQ(View(e->shafts)[0].reconstructed_threshold, 0.375);
  EXPECT_EQ(View(e->shafts)[0].reconstructed_harmonics[4], 9.0);
}

}  // namespace
}  // namespace gearpath::dds
