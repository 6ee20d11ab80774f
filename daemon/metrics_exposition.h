// Prometheus text exposition format, version 0.0.4, written by hand.
//
// Debian 12 packages no Prometheus client library for C++ (prometheus-cpp is not in it), and
// the format is small: `# HELP` and `# TYPE` lines, then one `name{label="value"} number` line
// per sample. This writer does only the formatting (escaping, number spelling, cumulative
// histogram buckets); which metrics exist is gearpathd_metrics.h's business. Pure: no I/O,
// no clock, no global state.
#pragma once

#include <cstdint>
#include <initializer_list>
#include <span>
#include <string>
#include <string_view>

namespace gearpath::daemon {

enum class MetricType { kCounter, kGauge, kHistogram };

struct MetricLabel {
  std::string_view name;
  std::string_view value;
};
using MetricLabels = std::initializer_list<MetricLabel>;

// A label value with backslash, double quote and line feed escaped (\\, \", \n).
std::string EscapeLabelValue(std::string_view value);
// HELP text with backslash and line feed escaped (a double quote stays as it is).
std::string EscapeHelpText(std::string_view help);
// A sample value: integers without a fraction, others in the shortest exact form, and
// NaN, +Inf, -Inf spelled as Prometheus reads them.
std::string FormatSampleValue(double value);

class ExpositionWriter {
 public:
  // Appends to `out`.
  explicit ExpositionWriter(std::string& out) : out_(out) {}

  // The `# HELP` and `# TYPE` lines of a metric family; its samples follow.
  void Family(std::string_view name, std::string_view help, MetricType type);
  void Sample(std::string_view name, MetricLabels labels, double value);
  void Sample(std::string_view name, MetricLabels labels, std::uint64_t value);
  // One histogram: `name_bucket{...,le="b"}` for every upper bound (cumulative counts, as the
  // format requires) and `le="+Inf"`, then `name_sum` and `name_count`. `per_bucket[i]` counts
  // the observations in (bounds[i-1], bounds[i]]; per_bucket has one more entry than bounds,
  // the observations above the last bound.
  void Histogram(std::string_view name, MetricLabels labels, std::span<const double> bounds,
                 std::span<const std::uint64_t> per_bucket, double sum);

 private:
  void Line(std::string_view name, MetricLabels labels, const MetricLabel* extra,
            std::string_view value);
  std::string& out_;
};

}  // namespace gearpath::daemon
