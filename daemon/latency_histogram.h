// LatencyHistogram: per-machine counts of block latencies in fixed buckets, for the metrics
// endpoint (docs/deployment.md, "Metrics").
//
// The latency is from the block being taken from the DDS reader to its results written
// (seconds, the daemon's steady clock: no publisher clock involved). Observe() is a short
// loop over a fixed array, done by the worker under the lane's counters_mutex that it takes
// for the other counters anyway: no extra lock, no allocation on the processing path.
#pragma once

#include <array>
#include <cstdint>

namespace gearpath::daemon {

// Upper bounds, seconds (Prometheus' default buckets: a block of 8192 samples takes tens of
// milliseconds; a machine whose queue backs up reaches seconds).
inline constexpr std::array<double, 11> kLatencyBucketBounds = {
    0.005, 0.01, 0.025, 0.05, 0.1, 0.25, 0.5, 1.0, 2.5, 5.0, 10.0};

struct LatencyHistogram {
  // per_bucket[i]: observations in (bound[i-1], bound[i]]; the last entry: above 10 s.
  std::array<std::uint64_t, kLatencyBucketBounds.size() + 1> per_bucket{};
  double sum_s = 0.0;

  void Observe(double seconds) noexcept {
    std::size_t i = 0;
    while (i < kLatencyBucketBounds.size() && seconds > kLatencyBucketBounds[i]) ++i;
    ++per_bucket[i];
    sum_s += seconds;
  }
};

}  // namespace gearpath::daemon
