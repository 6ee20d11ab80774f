// gearpathd's metric catalogue (daemon/gearpathd_metrics.h) on hand-made counters: every
// family is typed once, counters and states per machine, every reject reason from 0, the
// latency histogram from LatencyHistogram, indicator series only after an accepted block.
#include "daemon/gearpathd_metrics.h"

#include <gtest/gtest.h>

#include <map>
#include <sstream>

namespace gearpath::daemon {
namespace {

bool Has(const std::string& text, const std::string& line) {
  return text.find("\n" + line + "\n") != std::string::npos ||
         text.rfind(line + "\n", 0) == 0;
}

std::size_t CountLinesStartingWith(const std::string& text, const std::string& prefix) {
  std::istringstream in(text);
  std::size_t n = 0;
  for (std::string line; std::getline(in, line);) n += line.rfind(prefix, 0) == 0 ? 1 : 0;
  return n;
}

DaemonMetrics TwoMachines() {
  DaemonMetrics m;
  m.daemon_id = "gpd";
  m.version = "1.2.3";
  m.state = "running";
  m.uptime_s = 12.5;
  m.foreign_blocks = 4;
  MachineMetrics a;
  a.id = "a";
  a.baseline_epoch = "2026-11-29 \"G1\" replaced";  // a quote, escaped in the label
  a.counters.received = 7;
  a.counters.processed = 5;
  a.counters.rejected = 2;
  a.counters.rejected_by_reason = {{"non_finite", 2}};
  a.counters.lost = 1;
  a.counters.not_judged[static_cast<std::size_t>(NotJudgedCause::kLoadOutside)] = 3;
  a.counters.fault_state = FaultState::kAlarm;
  a.counters.latency.Observe(0.00390625);  // exact in binary: the sum compares exactly
  a.counters.latency.Observe(0.25);        // a bound belongs to its bucket (le)
  a.counters.latency.Observe(20.0);
  a.counters.latest.valid = true;
  a.counters.latest.score = 1.5;
  a.counters.latest.dominant_path.Assign("B5x");
  a.counters.latest.dominant_path_share = 0.25;
  a.counters.latest.shaft_count = 1;
  a.counters.latest.shafts[0].shaft.Assign("input");
  a.counters.latest.shafts[0].raw = 2.0;
  a.counters.latest.shafts[0].reconstructed_threshold = 3.0;
  MachineMetrics b;
  b.id = "b";  // nothing accepted yet: learning, no indicator series
  m.machines = {a, b};
  return m;
}

TEST(MetricsCatalogue, DaemonFiguresAndBuildInfo) {
  const std::string text = RenderMetrics(TwoMachines());
  EXPECT_TRUE(Has(text, "gearpath_build_info{version=\"1.2.3\",daemon=\"gpd\"} 1")) << text;
  EXPECT_TRUE(Has(text, "gearpath_daemon_uptime_seconds 12.5"));
  EXPECT_TRUE(Has(text, "gearpath_daemon_state{state=\"running\"} 1"));
  EXPECT_TRUE(Has(text, "gearpath_daemon_state{state=\"degraded\"} 0"));
  EXPECT_TRUE(Has(text, "gearpath_machines 2"));
  EXPECT_TRUE(Has(text, "gearpath_foreign_blocks_total 4"));
}

TEST(MetricsCatalogue, EveryFamilyHasOneHelpAndOneTypeLine) {
  const std::string text = RenderMetrics(TwoMachines());
  std::istringstream in(text);
  std::map<std::string, int> types;
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("# TYPE ", 0) == 0) ++types[line.substr(7, line.find(' ', 7) - 7)];
  }
  EXPECT_GE(types.size(), 20u);
  for (const auto& [name, n] : types) {
    EXPECT_EQ(n, 1) << name;
    EXPECT_EQ(CountLinesStartingWith(text, "# HELP " + name + " "), 1u) << name;
  }
}

TEST(MetricsCatalogue, BlockCountersPerMachineAndEveryRejectReasonFromZero) {
  const std::string text = RenderMetrics(TwoMachines());
  EXPECT_TRUE(Has(text, "gearpath_blocks_received_total{machine=\"a\"} 7"));
  EXPECT_TRUE(Has(text, "gearpath_blocks_processed_total{machine=\"a\"} 5"));
  EXPECT_TRUE(Has(text, "gearpath_blocks_processed_total{machine=\"b\"} 0"));
  EXPECT_TRUE(Has(text, "gearpath_blocks_lost_total{machine=\"a\"} 1"));
  EXPECT_TRUE(Has(text, "gearpath_blocks_rejected_total{machine=\"a\",reason=\"non_finite\"} 2"));
  EXPECT_TRUE(Has(text, "gearpath_blocks_rejected_total{machine=\"b\",reason=\"non_finite\"} 0"));
  EXPECT_TRUE(Has(text, "gearpath_blocks_rejected_total{machine=\"b\",reason=\"queue_full\"} 0"));
  EXPECT_TRUE(
      Has(text, "gearpath_blocks_rejected_total{machine=\"a\",reason=\"wrong_sample_rate\"} 0"));
  // Not judged by a learned machine, every cause from 0.
  EXPECT_TRUE(
      Has(text, "gearpath_blocks_not_judged_total{machine=\"a\",cause=\"load_outside\"} 3"));
  EXPECT_TRUE(
      Has(text, "gearpath_blocks_not_judged_total{machine=\"a\",cause=\"speed_outside\"} 0"));
  EXPECT_TRUE(
      Has(text, "gearpath_blocks_not_judged_total{machine=\"b\",cause=\"speed_unknown\"} 0"));
  EXPECT_EQ(CountLinesStartingWith(text, "gearpath_blocks_not_judged_total{machine=\"b\""), 4u);
  // The 15 validation reasons and queue_full, per machine.
  EXPECT_EQ(CountLinesStartingWith(text, "gearpath_blocks_rejected_total{machine=\"a\""), 16u);
}

TEST(MetricsCatalogue, LatencyHistogramIsCumulativeOverTheFixedBuckets) {
  const std::string text = RenderMetrics(TwoMachines());
  const std::string b = "gearpath_block_latency_seconds_bucket{machine=\"a\",le=";
  EXPECT_TRUE(Has(text, b + "\"0.005\"} 1")) << text;
  EXPECT_TRUE(Has(text, b + "\"0.1\"} 1"));
  EXPECT_TRUE(Has(text, b + "\"0.25\"} 2"));
  EXPECT_TRUE(Has(text, b + "\"10\"} 2"));
  EXPECT_TRUE(Has(text, b + "\"+Inf\"} 3"));
  EXPECT_TRUE(Has(text, "gearpath_block_latency_seconds_sum{machine=\"a\"} 20.25390625"));
  EXPECT_TRUE(Has(text, "gearpath_block_latency_seconds_count{machine=\"a\"} 3"));
  EXPECT_TRUE(Has(text, "gearpath_block_latency_seconds_count{machine=\"b\"} 0"));
  EXPECT_EQ(CountLinesStartingWith(text, "gearpath_block_latency_seconds_bucket{machine=\"b\""),
            12u);
}

TEST(MetricsCatalogue, MachineStateIsOneHotOverTheFourVerdictStates) {
  const std::string text = RenderMetrics(TwoMachines());
  for (const char* s : {"learning", "no_fault", "suspected"}) {
    EXPECT_TRUE(Has(text, std::string("gearpath_machine_state{machine=\"a\",state=\"") + s +
                              "\"} 0"));
  }
  EXPECT_TRUE(Has(text, "gearpath_machine_state{machine=\"a\",state=\"alarm\"} 1"));
  EXPECT_TRUE(Has(text, "gearpath_machine_state{machine=\"b\",state=\"learning\"} 1"));
  EXPECT_EQ(CountLinesStartingWith(text, "gearpath_machine_state{"), 8u);
}

TEST(MetricsCatalogue, BaselineEpochOfEveryMachineEvenWithoutOne) {
  const std::string text = RenderMetrics(TwoMachines());
  EXPECT_TRUE(Has(text,
                  "gearpath_machine_baseline_epoch{machine=\"a\",epoch=\"2026-11-29 "
                  "\\\"G1\\\" replaced\"} 1"))
      << text;
  EXPECT_TRUE(Has(text, "gearpath_machine_baseline_epoch{machine=\"b\",epoch=\"\"} 1")) << text;
  EXPECT_EQ(CountLinesStartingWith(text, "gearpath_machine_baseline_epoch{"), 2u);
}

TEST(MetricsCatalogue, IndicatorSeriesOnlyForMachinesWithAnAcceptedBlock) {
  const std::string text = RenderMetrics(TwoMachines());
  EXPECT_TRUE(Has(text, "gearpath_machine_score{machine=\"a\"} 1.5"));
  EXPECT_TRUE(Has(text, "gearpath_machine_dominant_path_share{machine=\"a\",path=\"B5x\"} 0.25"));
  EXPECT_TRUE(Has(text, "gearpath_machine_envelope_indicator{machine=\"a\",shaft=\"input\","
                        "signal=\"raw\"} 2"));
  EXPECT_TRUE(Has(text, "gearpath_machine_envelope_threshold{machine=\"a\",shaft=\"input\","
                        "signal=\"reconstructed\"} 3"));
  EXPECT_EQ(text.find("gearpath_machine_score{machine=\"b\"}"), std::string::npos);
  EXPECT_EQ(text.find("gearpath_machine_envelope_indicator{machine=\"b\""), std::string::npos);
}

}  // namespace
}  // namespace gearpath::daemon
