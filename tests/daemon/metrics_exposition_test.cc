// The Prometheus text format writer (daemon/metrics_exposition.h) against hand-written
// exposition text: escaping, number spelling, cumulative histogram buckets with +Inf.
#include "daemon/metrics_exposition.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>

namespace gearpath::daemon {
namespace {

TEST(MetricsExposition, EscapesBackslashQuoteAndNewlineInLabelValues) {
  EXPECT_EQ(EscapeLabelValue(R"(a\b"c)" "\n" "d"), R"(a\\b\"c\nd)");
  EXPECT_EQ(EscapeLabelValue("plain_id-1.x"), "plain_id-1.x");
  EXPECT_EQ(EscapeLabelValue(""), "");
}

TEST(MetricsExposition, EscapesBackslashAndNewlineInHelpButNotQuotes) {
  EXPECT_EQ(EscapeHelpText("a \"quoted\" \\ word\nnext"), "a \"quoted\" \\\\ word\\nnext");
}

TEST(MetricsExposition, SpellsNumbersAsPrometheusReadsThem) {
  EXPECT_EQ(FormatSampleValue(0.0), "0");
  EXPECT_EQ(FormatSampleValue(3.0), "3");
  EXPECT_EQ(FormatSampleValue(-2.0), "-2");
  EXPECT_EQ(FormatSampleValue(0.25), "0.25");
  EXPECT_EQ(FormatSampleValue(0.1), "0.1");
  EXPECT_EQ(FormatSampleValue(1e-5), "1e-05");
  EXPECT_EQ(FormatSampleValue(1e300), "1e+300");
  EXPECT_EQ(FormatSampleValue(std::numeric_limits<double>::infinity()), "+Inf");
  EXPECT_EQ(FormatSampleValue(-std::numeric_limits<double>::infinity()), "-Inf");
  EXPECT_EQ(FormatSampleValue(std::nan("")), "NaN");
}

TEST(MetricsExposition, WritesFamiliesAndSamplesWithLabels) {
  std::string out;
  ExpositionWriter w(out);
  w.Family("x_total", "Things counted.\nSecond line \\ here.", MetricType::kCounter);
  w.Sample("x_total", {{"machine", "gb\"1"}, {"reason", "non_finite"}},
           std::uint64_t{18446744073709551615u});
  w.Sample("x_total", {}, std::uint64_t{0});
  w.Family("y", "A gauge.", MetricType::kGauge);
  w.Sample("y", {{"machine", "a\\b\nc"}}, 0.5);
  EXPECT_EQ(out,
            "# HELP x_total Things counted.\\nSecond line \\\\ here.\n"
            "# TYPE x_total counter\n"
            "x_total{machine=\"gb\\\"1\",reason=\"non_finite\"} 18446744073709551615\n"
            "x_total 0\n"
            "# HELP y A gauge.\n"
            "# TYPE y gauge\n"
            "y{machine=\"a\\\\b\\nc\"} 0.5\n");
}

TEST(MetricsExposition, HistogramBucketsAreCumulativeWithInfSumAndCount) {
  std::string out;
  ExpositionWriter w(out);
  const std::array<double, 3> bounds = {0.01, 0.1, 1.0};
  // 2 in (0, 0.01], 0 in (0.01, 0.1], 3 in (0.1, 1], 1 above 1.
  const std::array<std::uint64_t, 4> per_bucket = {2, 0, 3, 1};
  w.Family("lat_seconds", "Latency.", MetricType::kHistogram);
  w.Histogram("lat_seconds", {{"machine", "m1"}}, bounds, per_bucket, 4.75);
  EXPECT_EQ(out,
            "# HELP lat_seconds Latency.\n"
            "# TYPE lat_seconds histogram\n"
            "lat_seconds_bucket{machine=\"m1\",le=\"0.01\"} 2\n"
            "lat_seconds_bucket{machine=\"m1\",le=\"0.1\"} 2\n"
            "lat_seconds_bucket{machine=\"m1\",le=\"1\"} 5\n"
            "lat_seconds_bucket{machine=\"m1\",le=\"+Inf\"} 6\n"
            "lat_seconds_sum{machine=\"m1\"} 4.75\n"
            "lat_seconds_count{machine=\"m1\"} 6\n");
}

TEST(MetricsExposition, EmptyHistogramWithoutLabelsHasZeroBucketsAndCount) {
  std::string out;
  ExpositionWriter w(out);
  const std::array<double, 1> bounds = {0.5};
  const std::array<std::uint64_t, 2> per_bucket = {0, 0};
  w.Histogram("h", {}, bounds, per_bucket, 0.0);
  EXPECT_EQ(out,
            "h_bucket{le=\"0.5\"} 0\n"
            "h_bucket{le=\"+Inf\"} 0\n"
            "h_sum 0\n"
            "h_count 0\n");
}

}  // namespace
}  // namespace gearpath::daemon
