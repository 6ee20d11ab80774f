#include "tools/report/signal_statistics.h"

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace gearpath::tools {

SignalStatistics ComputeSignalStatistics(std::span<const double> x) {
  SignalStatistics st;
  double sum = 0.0;
  std::size_t n = 0;
  for (const double v : x) {
    if (!std::isfinite(v)) continue;
    sum += v;
    ++n;
  }
  if (n == 0) return st;
  const double mean = sum / static_cast<double>(n);
  double m2 = 0.0;
  double m4 = 0.0;
  for (const double v : x) {
    if (!std::isfinite(v)) continue;
    const double d = v - mean;
    const double d2 = d * d;
    m2 += d2;
    m4 += d2 * d2;
    st.peak = std::max(st.peak, std::abs(d));
  }
  m2 /= static_cast<double>(n);
  m4 /= static_cast<double>(n);
  st.rms = std::sqrt(m2);
  if (m2 > 0.0) {
    st.crest_factor = st.peak / st.rms;
    st.kurtosis = m4 / (m2 * m2);
  }
  return st;
}

}  // namespace gearpath::tools
