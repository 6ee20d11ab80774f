#include "daemon/metrics_exposition.h"

#include <fmt/format.h>

#include <cmath>

namespace gearpath::daemon {

std::string EscapeLabelValue(std::string_view value) {
  std::string out;
  out.reserve(value.size());
  for (char c : value) {
    switch (c) {
      case '\\': out += "\\\\"; break;
      case '"': out += "\\\""; break;
      case '\n': out += "\\n"; break;
      default: out += c;
    }
  }
  return out;
}

std::string EscapeHelpText(std::string_view help) {
  std::string out;
  out.reserve(help.size());
  for (char c : help) {
    switch (c) {
      case '\\': out += "\\\\"; break;
      case '\n': out += "\\n"; break;
      default: out += c;
    }
  }
  return out;
}

std::string FormatSampleValue(double value) {
  if (std::isnan(value)) return "NaN";
  if (std::isinf(value)) return value > 0 ? "+Inf" : "-Inf";
  // Whole numbers below 2^53 are exact as integers: "3", not "3.0" or "3e+00".
  if (value == std::floor(value) && std::abs(value) < 0x1p53) {
    return fmt::format("{}", static_cast<std::int64_t>(value));
  }
  return fmt::format("{}", value);  // shortest form that reads back to the same double
}

namespace {

std::string_view TypeName(MetricType type) {
  switch (type) {
    case MetricType::kCounter: return "counter";
    case MetricType::kGauge: return "gauge";
    case MetricType::kHistogram: return "histogram";
  }
  return "untyped";
}

}  // namespace

void ExpositionWriter::Family(std::string_view name, std::string_view help, MetricType type) {
  out_ += fmt::format("# HELP {} {}\n# TYPE {} {}\n", name, EscapeHelpText(help), name,
                      TypeName(type));
}

void ExpositionWriter::Line(std::string_view name, MetricLabels labels, const MetricLabel* extra,
                            std::string_view value) {
  out_ += name;
  if (labels.size() > 0 || extra != nullptr) {
    out_ += '{';
    bool first = true;
    auto append = [&](const MetricLabel& l) {
      if (!first) out_ += ',';
      first = false;
      out_ += l.name;
      out_ += "=\"";
      out_ += EscapeLabelValue(l.value);
      out_ += '"';
    };
    for (const MetricLabel& l : labels) append(l);
    if (extra != nullptr) append(*extra);
    out_ += '}';
  }
  out_ += ' ';
  out_ += value;
  out_ += '\n';
}

void ExpositionWriter::Sample(std::string_view name, MetricLabels labels, double value) {
  Line(name, labels, nullptr, FormatSampleValue(value));
}

void ExpositionWriter::Sample(std::string_view name, MetricLabels labels, std::uint64_t value) {
  Line(name, labels, nullptr, fmt::format("{}", value));  // exact beyond 2^53
}

void ExpositionWriter::Histogram(std::string_view name, MetricLabels labels,
                                 std::span<const double> bounds,
                                 std::span<const std::uint64_t> per_bucket, double sum) {
  const std::string bucket = fmt::format("{}_bucket", name);
  std::uint64_t cumulative = 0;
  for (std::size_t i = 0; i < bounds.size(); ++i) {
    cumulative += i < per_bucket.size() ? per_bucket[i] : 0;
    const std::string le = FormatSampleValue(bounds[i]);
    const MetricLabel le_label{"le", le};
    Line(bucket, labels, &le_label, fmt::format("{}", cumulative));
  }
  for (std::size_t i = bounds.size(); i < per_bucket.size(); ++i) cumulative += per_bucket[i];
  const MetricLabel inf_label{"le", "+Inf"};
  Line(bucket, labels, &inf_label, fmt::format("{}", cumulative));
  Line(fmt::format("{}_sum", name), labels, nullptr, FormatSampleValue(sum));
  Line(fmt::format("{}_count", name), labels, nullptr, fmt::format("{}", cumulative));
}

}  // namespace gearpath::daemon
