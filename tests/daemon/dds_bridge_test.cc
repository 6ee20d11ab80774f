// The DDS bridge: wire samples <-> core types, field by field (no DDS traffic needed).
#include "daemon/dds_bridge.h"
#include "idl/dds/accel_block_wire.h"

#include <gtest/gtest.h>

#include <string>

#include "idl/dds/gearpath_topics.h"

namespace gearpath::daemon {
namespace {

using dds::GetString;
using dds::Owned;
using dds::View;

TEST(DdsBridge, ViewOfAnAccelBlockSharesTheSampleBufferAndCopiesTheChannelNames) {
  Owned<gearpath_AccelBlock> s;
  ASSERT_TRUE(dds::SetString(s->machine_id, "gb7"));
  s->sequence_number = 42;
  s->t0_ns = 123456789;
  s->sample_rate_hz = 8000.0;
  s->speed_hz = 10.0;
  s->speed_source = gearpath_SPEED_ACQUISITION_TACHOMETER;
  ASSERT_TRUE(dds::Resize(s->channels, 2));
  ASSERT_TRUE(dds::SetString(s->channels._buffer[0].sensor_id, "A4"));
  s->channels._buffer[0].axis = gearpath_AXIS_X;
  ASSERT_TRUE(dds::SetString(s->channels._buffer[1].sensor_id, "A5"));
  s->channels._buffer[1].axis = gearpath_AXIS_Z;
  s->samples_per_channel = 3;
  const float values[] = {1, 2, 3, 4, 5, 6};
  ASSERT_TRUE(dds::Assign(s->samples, std::span<const float>(values)));

  std::vector<ChannelInfo> channels;
  const AccelBlockView v = dds::ViewOfWireBlock(*s, channels);
  EXPECT_EQ(v.machine_id, "gb7");
  EXPECT_EQ(v.sequence, 42u);
  EXPECT_EQ(v.t0_ns, 123456789);
  EXPECT_EQ(v.sample_rate_hz, 8000.0);
  EXPECT_EQ(v.speed_hz, 10.0);
  EXPECT_EQ(v.speed_source, SpeedSource::kAcquisition);
  ASSERT_EQ(v.channels.size(), 2u);
  EXPECT_EQ(v.channels[0].sensor, "A4");
  EXPECT_EQ(v.channels[1].axis, Axis::kZ);
  EXPECT_EQ(v.samples.data(), s->samples._buffer);  // no copy of the samples
  EXPECT_EQ(v.channel(1)[0], 4.0f);
}

TEST(DdsBridge, AnAccelBlockWithoutSpeedSourceHasAnUnknownSpeed) {
  Owned<gearpath_AccelBlock> s;
  s->speed_source = gearpath_SPEED_UNKNOWN;
  std::vector<ChannelInfo> channels;
  EXPECT_EQ(dds::ViewOfWireBlock(*s, channels).speed_source, SpeedSource::kUnknown);
  EXPECT_TRUE(dds::ViewOfWireBlock(*s, channels).samples.empty());
}

BlockResult ExampleResult() {
  BlockResult r;
  r.sequence = 9;
  r.t0_ns = 77;
  r.speed_hz = 10.0;
  r.speed_source = SpeedSource::kConfiguration;
  r.dominant_path = 1;
  r.dominant_path_name = "B2x";
  r.criterion = AnalysisOptions::DominantCriterion::kBandEnergy;
  r.analysis_band_lo_hz = 5.0;
  r.analysis_band_hi_hz = 3000.0;
  r.paths = {{"B1x", "", 1.0, 0.25, 0.0}, {"B2x", "", 3.0, 0.75, 0.6}};
  r.reconstructed_band = {1200.0, 250.0, 4, 3.5, true};
  BlockShaftIndicator shaft;
  shaft.shaft = "input";
  shaft.characteristic_hz = 10.0;
  shaft.raw = 1.0;
  shaft.reconstructed = 3.0;
  shaft.enhancement_percent = 300.0;
  shaft.raw_threshold = 0.9;
  shaft.reconstructed_threshold = 2.5;
  shaft.raw_harmonics = {0.5, 0.2, 0.1, 0.1, 0.1};
  shaft.reconstructed_harmonics = {1.5, 0.6, 0.3, 0.3, 0.3};
  r.shafts = {shaft};
  r.verdict.state = FaultState::kSuspected;
  r.verdict.gear_name = "G3";
  r.verdict.shaft_name = "intermediate";
  r.verdict.characteristic_hz = 7.0;
  r.verdict.confidence = 0.8;
  r.verdict.candidate_names = {"G3", "G4"};
  r.verdict.reason.Assign("intermediate shaft harmonics; G3 and G4 share rate and mesh");
  return r;
}

TEST(DdsBridge, DominantPathCarriesEverySharesAndTheBand) {
  const BlockResult r = ExampleResult();
  Owned<gearpath_DominantPath> out;
  FillDominantPath("gb7", r, *out);
  EXPECT_EQ(GetString(out->machine_id), "gb7");
  EXPECT_EQ(out->block_sequence, 9u);
  EXPECT_EQ(out->block_t0_ns, 77);
  EXPECT_EQ(out->path_index, 1u);
  EXPECT_EQ(GetString(out->path_name), "B2x");
  ASSERT_EQ(out->paths._length, 2u);
  EXPECT_EQ(GetString(out->paths._buffer[0].name), "B1x");
  EXPECT_DOUBLE_EQ(out->paths._buffer[0].share + out->paths._buffer[1].share, 1.0);
  EXPECT_EQ(out->band_hi_hz, 3000.0);
  EXPECT_EQ(out->criterion, gearpath_CRITERION_BAND_ENERGY);
  EXPECT_EQ(out->paths._buffer[0].criterion, 0.0);
  EXPECT_EQ(out->paths._buffer[1].criterion, 0.6);  // the value the path was ranked by
}

TEST(DdsBridge, EveryCoreCriterionHasItsOwnWireCriterion) {
  BlockResult r = ExampleResult();
  Owned<gearpath_DominantPath> out;
  r.criterion = AnalysisOptions::DominantCriterion::kSidebandEnergy;
  FillDominantPath("gb7", r, *out);
  EXPECT_EQ(out->criterion, gearpath_CRITERION_SIDEBAND_ENERGY);
  r.criterion = AnalysisOptions::DominantCriterion::kIndicator;
  FillDominantPath("gb7", r, *out);
  EXPECT_EQ(out->criterion, gearpath_CRITERION_INDICATOR);
}

TEST(DdsBridge, SuspectedGearNamesTheGearAndItsIndistinguishableCandidates) {
  const BlockResult r = ExampleResult();
  Owned<gearpath_SuspectedGear> out;
  FillSuspectedGear("gb7", r, *out);
  EXPECT_EQ(out->state, gearpath_SUSPECTED);
  EXPECT_EQ(GetString(out->gear_name), "G3");
  EXPECT_EQ(GetString(out->shaft_name), "intermediate");
  EXPECT_EQ(out->characteristic_frequency_hz, 7.0);
  ASSERT_EQ(out->candidates._length, 2u);
  EXPECT_EQ(GetString(out->candidates._buffer[1]), "G4");
  EXPECT_EQ(GetString(out->reason), r.verdict.reason.view());
}

TEST(DdsBridge, NoFaultAndLearningNameNoGearAndLearningIsSaidSo) {
  BlockResult r = ExampleResult();
  for (FaultState state : {FaultState::kNoFault, FaultState::kLearning}) {
    r.verdict.state = state;
    Owned<gearpath_SuspectedGear> out;
    FillSuspectedGear("gb7", r, *out);
    EXPECT_EQ(out->state, state == FaultState::kLearning ? gearpath_LEARNING : gearpath_NO_FAULT);
    EXPECT_EQ(GetString(out->gear_name), "");
    EXPECT_EQ(out->candidates._length, 0u);
  }
}

TEST(DdsBridge, FaultStateKeepsTheVersion1NumbersAndLearningComesLast) {
  // Appending LEARNING must not renumber what subscribers already switch on.
  EXPECT_EQ(static_cast<int>(gearpath_NO_FAULT), 0);
  EXPECT_EQ(static_cast<int>(gearpath_SUSPECTED), 1);
  EXPECT_EQ(static_cast<int>(gearpath_ALARM), 2);
  EXPECT_EQ(static_cast<int>(gearpath_LEARNING), 3);
  EXPECT_EQ(gearpath_CONTRACT_VERSION, 4u);  // 3 added MachineHealth, 4 AccelBlockV2; no enumerator
}

TEST(DdsBridge, EnvelopeIndicatorsCarryTheReconstructedBandAndEveryHarmonic) {
  const BlockResult r = ExampleResult();
  Owned<gearpath_EnvelopeIndicators> out;
  FillEnvelopeIndicators("gb7", r, *out);
  EXPECT_EQ(out->band.centre_hz, 1200.0);
  EXPECT_EQ(out->band.level, 4.0);
  EXPECT_TRUE(out->band.significant);
  ASSERT_EQ(out->shafts._length, 1u);
  const gearpath_ShaftIndicator& s = out->shafts._buffer[0];
  EXPECT_EQ(GetString(s.shaft_name), "input");
  EXPECT_EQ(s.enhancement_percent, 300.0);
  EXPECT_EQ(s.raw_threshold, 0.9);
  EXPECT_EQ(s.reconstructed_threshold, 2.5);
  double sum = 0.0;
  for (double h : s.reconstructed_harmonics) sum += h;
  EXPECT_DOUBLE_EQ(sum, s.reconstructed_indicator);  // the indicator is the harmonics' sum
  EXPECT_EQ(out->speed_source, gearpath_SPEED_OTHER);
}

// Two signals x two rate groups, signal-major, with the processor's per-group names.
struct ConditionExample {
  std::vector<std::string> group0{"fm0", "fm4", "sideband_G1-G2"};
  std::vector<std::string> group1{"fm0", "fm4"};
  std::vector<std::vector<double>> values{{1, 2, 3}, {4, 5}, {6, 7, 8}, {9, 10}};
  std::vector<std::vector<double>> z{{0.1, 0.2, 0.3}, {0.4, 0.5}, {0.6, 0.7, 0.8}, {0.9, 1.0}};
  IndicatorNamesByGroup names{group0, group1};
  BlockResult result = ExampleResult();

  ConditionExample() {
    const ConditionSource sources[] = {ConditionSource::kMeasured, ConditionSource::kForce};
    const std::string_view signals[] = {"A1/x", "B2x"};
    const std::string_view shafts[] = {"input", "output"};
    for (std::size_t i = 0; i < 4; ++i) {
      BlockConditionIndicators c;
      c.source = sources[i / 2];
      c.index = static_cast<int>(i / 2);
      c.signal = signals[i / 2];
      c.shaft = shafts[i % 2];
      c.shaft_hz = i % 2 == 0 ? 10.0 : 3.5;
      c.revolutions = 20;
      c.value = values[i];
      c.z = z[i];
      c.score = 0.1 * static_cast<double>(i);
      result.condition.push_back(c);
    }
    BlockScore& s = result.score;
    s.limit_z = 6.1;
    s.clear_level = 0.7;
    s.score = 0.42;
    s.indicator = "fm4";
    s.signal = "B2x";
    s.shaft = "output";
    s.exceed_count = 1;
    s.window = 5;
    s.baseline_blocks_learned = 20;
    s.baseline_blocks_needed = 20;
  }
};

TEST(DdsBridge, ConditionIndicatorsCarryEverySetWithItsGroupsNamesAndTheBlockScore) {
  const ConditionExample ex;
  Owned<gearpath_ConditionIndicators> out;
  const OmittedIndicators omitted = FillConditionIndicators("gb7", ex.result, ex.names, *out);
  EXPECT_FALSE(omitted.any());
  EXPECT_EQ(GetString(out->machine_id), "gb7");
  EXPECT_EQ(out->block_sequence, 9u);
  EXPECT_EQ(out->block_t0_ns, 77);
  EXPECT_EQ(out->limit_z, 6.1);
  EXPECT_EQ(out->clear_level, 0.7);
  EXPECT_EQ(out->score, 0.42);
  EXPECT_EQ(GetString(out->top_indicator), "fm4");
  EXPECT_EQ(GetString(out->top_signal), "B2x");
  EXPECT_EQ(GetString(out->top_shaft), "output");
  EXPECT_EQ(out->exceed_count, 1u);
  EXPECT_EQ(out->window, 5u);
  EXPECT_EQ(out->baseline_blocks_learned, 20u);
  EXPECT_EQ(out->baseline_blocks_needed, 20u);
  EXPECT_EQ(out->sets_omitted, 0u);
  EXPECT_EQ(out->values_omitted, 0u);
  ASSERT_EQ(out->sets._length, 4u);
  const auto sets = View(out->sets);
  EXPECT_EQ(sets[0].source, gearpath_SIGNAL_MEASURED);
  EXPECT_EQ(sets[3].source, gearpath_SIGNAL_FORCE);
  EXPECT_EQ(GetString(sets[2].signal), "B2x");
  EXPECT_EQ(GetString(sets[3].shaft), "output");
  EXPECT_EQ(sets[3].shaft_hz, 3.5);
  EXPECT_EQ(sets[3].revolutions, 20);
  EXPECT_DOUBLE_EQ(sets[3].score, 0.3);
  // Set i has group i % 2: three names in group 0, two in group 1.
  ASSERT_EQ(sets[2].values._length, 3u);
  EXPECT_EQ(GetString(View(sets[2].values)[2].name), "sideband_G1-G2");
  EXPECT_EQ(View(sets[2].values)[2].value, 8.0);
  EXPECT_EQ(View(sets[2].values)[2].z, 0.8);
  ASSERT_EQ(sets[1].values._length, 2u);
  EXPECT_EQ(GetString(View(sets[1].values)[1].name), "fm4");
  EXPECT_EQ(View(sets[1].values)[1].z, 0.5);
}

TEST(DdsBridge, ConditionIndicatorsOverTheIdlBoundsAreLeftOutAndCountedNeverRefused) {
  ConditionExample ex;
  // More sets than MAX_INDICATOR_SETS, one set with more values than MAX_INDICATORS_PER_SET,
  // and a name longer than INDICATOR_NAME_LENGTH.
  std::vector<double> many(gearpath_MAX_INDICATORS_PER_SET + 3, 1.0);
  std::vector<std::string> long_names(many.size(), "x");
  long_names[0] = std::string(gearpath_INDICATOR_NAME_LENGTH + 5, 'n');
  const IndicatorNamesByGroup names{long_names, ex.group1};
  const std::size_t total = gearpath_MAX_INDICATOR_SETS + 7;
  while (ex.result.condition.size() < total) {
    ex.result.condition.push_back(ex.result.condition[ex.result.condition.size() - 2]);
  }
  ex.result.condition[0].value = many;
  ex.result.condition[0].z = many;
  Owned<gearpath_ConditionIndicators> out;
  const OmittedIndicators omitted = FillConditionIndicators("gb7", ex.result, names, *out);
  EXPECT_EQ(omitted.sets, 7u);
  EXPECT_EQ(omitted.values, 3u);
  EXPECT_GE(omitted.names, 1u);
  EXPECT_EQ(out->sets._length, gearpath_MAX_INDICATOR_SETS);
  EXPECT_EQ(out->sets_omitted, 7u);
  EXPECT_EQ(out->values_omitted, 3u);
  EXPECT_EQ(out->sets._buffer[0].values._length, gearpath_MAX_INDICATORS_PER_SET);
  EXPECT_EQ(GetString(out->sets._buffer[0].values._buffer[0].name).size(),
            std::size_t{gearpath_INDICATOR_NAME_LENGTH});
}

TEST(DdsBridge, ResultSamplesAreReusedWhenTheNextResultIsSmaller) {
  BlockResult r = ExampleResult();
  Owned<gearpath_DominantPath> out;
  FillDominantPath("gb7", r, *out);
  const auto* buffer = out->paths._buffer;
  r.paths.pop_back();
  FillDominantPath("gb7", r, *out);
  EXPECT_EQ(out->paths._length, 1u);
  EXPECT_EQ(out->paths._buffer, buffer);
}

TEST(DdsBridge, StatusListsEveryConfiguredMachineWithItsCountersAndLastRejection) {
  std::map<std::string, MachineCounters, std::less<>> counters;
  counters["gb1"].received = 5;
  counters["gb1"].processed = 3;
  counters["gb1"].rejected = 2;
  counters["gb1"].last_rejection = "non_finite: sample 17 of channel 0 is NaN";
  const std::vector<std::string> ids{"gb1", "gb2"};
  Owned<gearpath_Status> out;
  FillStatus({"d1", gearpath_RUNNING, 5, 1.5}, ids, counters, *out);
  EXPECT_EQ(GetString(out->daemon_id), "d1");
  EXPECT_EQ(out->uptime_s, 1.5);
  ASSERT_EQ(out->machines._length, 2u);
  EXPECT_EQ(out->machines._buffer[0].blocks_received, 5u);
  EXPECT_EQ(out->machines._buffer[0].blocks_processed + out->machines._buffer[0].blocks_rejected,
            5u);
  EXPECT_EQ(GetString(out->machines._buffer[0].last_rejection_reason),
            "non_finite: sample 17 of channel 0 is NaN");
  EXPECT_EQ(GetString(out->machines._buffer[1].machine_id), "gb2");
  EXPECT_EQ(out->machines._buffer[1].blocks_received, 0u);
}

TEST(DdsBridge, StatusCarriesTheFirstSixtyFourOfAHundredMachinesInConfigurationOrder) {
  std::map<std::string, MachineCounters, std::less<>> counters;
  std::vector<std::string> ids;
  for (int i = 0; i < 100; ++i) {
    ids.push_back("gb" + std::to_string(i));
    counters[ids.back()].received = static_cast<std::uint64_t>(i);
  }
  Owned<gearpath_Status> out;
  FillStatus({"d1", gearpath_RUNNING, 5, 1.5}, ids, counters, *out);
  ASSERT_EQ(out->machines._length, std::uint32_t{gearpath_MAX_MACHINES});
  for (std::uint32_t i = 0; i < out->machines._length; ++i) {
    EXPECT_EQ(GetString(out->machines._buffer[i].machine_id), ids[i]);
    EXPECT_EQ(out->machines._buffer[i].blocks_received, i);
  }
}

TEST(DdsBridge, MachineHealthCarriesTheDaemonTheMachineItsPlaceAndEveryCounter) {
  MachineCounters c;
  c.received = 9;
  c.processed = 6;
  c.rejected = 3;
  c.lost = 2;
  c.last_rejection = "queue_full: 1 block(s) arrived while 32 were queued";
  c.last_alpha = 0.01;
  c.last_condition = 55.0;
  c.last_residual = 0.25;
  c.latency_last_ms = 4.5;
  c.latency_max_ms = 9.5;
  c.fault_state = FaultState::kAlarm;
  c.last_sequence = 41;
  c.last_t0_ns = 41'000'000'000;
  MachineHealthFigures figures;
  figures.daemon_id = "standby";
  figures.state = gearpath_DEGRADED;
  figures.timestamp_ns = 77;
  figures.machine_count = 100;
  figures.publishing_results = false;
  Owned<gearpath_MachineHealth> out;
  FillMachineHealth(figures, "gb99", 99, c, *out);
  EXPECT_EQ(GetString(out->daemon_id), "standby");
  EXPECT_EQ(GetString(out->machine_id), "gb99");
  EXPECT_EQ(out->daemon_state, gearpath_DEGRADED);
  EXPECT_EQ(out->timestamp_ns, 77);
  EXPECT_EQ(out->machine_index, 99u);
  EXPECT_EQ(out->machine_count, 100u);
  EXPECT_EQ(out->fault_state, gearpath_ALARM);
  EXPECT_FALSE(out->publishing_results);
  EXPECT_EQ(out->last_block_sequence, 41u);
  EXPECT_EQ(out->last_block_t0_ns, 41'000'000'000);
  EXPECT_EQ(out->blocks_received, 9u);
  EXPECT_EQ(out->blocks_processed, 6u);
  EXPECT_EQ(out->blocks_rejected, 3u);
  EXPECT_EQ(out->blocks_lost, 2u);
  EXPECT_EQ(GetString(out->last_rejection_reason),
            "queue_full: 1 block(s) arrived while 32 were queued");
  EXPECT_EQ(out->last_alpha, 0.01);
  EXPECT_EQ(out->last_condition_number, 55.0);
  EXPECT_EQ(out->last_relative_residual, 0.25);
  EXPECT_EQ(out->latency_last_ms, 4.5);
  EXPECT_EQ(out->latency_max_ms, 9.5);
  // A machine that has seen no block is still learning.
  FillMachineHealth(figures, "gb0", 0, MachineCounters{}, *out);
  EXPECT_EQ(out->fault_state, gearpath_LEARNING);
  EXPECT_EQ(out->blocks_received, 0u);
}

TEST(DdsBridge, AnOverlongTextIsTruncatedToTheIdlBound) {
  char id[gearpath_ID_LENGTH + 1];
  CopyTruncated(id, std::string(100, 'x'));
  EXPECT_EQ(std::string(id).size(), std::size_t{gearpath_ID_LENGTH});
}

}  // namespace
}  // namespace gearpath::daemon
