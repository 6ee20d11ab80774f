#include "core/pipeline/frf_grid_mapping.h"

#include <fmt/format.h>

#include <cmath>
#include <memory>
#include <string>
#include <utility>

namespace gearpath {

Result<FrfGridMapping> MapFrfToBlockGrid(const FrfMatrix& frf, std::size_t block_length,
                                         double sample_rate_hz) {
  const Eigen::Index n = frf.bins();
  if (n == 0 || frf.at.empty()) return Error{"FRF grid mapping: the FRF matrix is empty"};
  if (static_cast<std::size_t>(n) != frf.at.size()) {
    return Error{fmt::format("FRF grid mapping: {} frequencies but {} matrices", n, frf.at.size())};
  }
  for (Eigen::Index i = 0; i < n; ++i) {
    const Eigen::MatrixXcd& m = frf.at[i];
    if (m.rows() != frf.outputs() || m.cols() != frf.inputs() || m.size() == 0) {
      return Error{fmt::format("FRF grid mapping: matrix at {} Hz is {}x{}, expected {}x{}",
                               frf.frequency_hz[i], m.rows(), m.cols(), frf.outputs(),
                               frf.inputs())};
    }
    if (!m.allFinite() || !std::isfinite(frf.frequency_hz[i])) {
      return Error{
          fmt::format("FRF grid mapping: non-finite FRF value at {} Hz", frf.frequency_hz[i])};
    }
    if (i > 0 && !(frf.frequency_hz[i] > frf.frequency_hz[i - 1])) {
      return Error{fmt::format("FRF grid mapping: frequencies not strictly increasing at {} Hz",
                               frf.frequency_hz[i])};
    }
  }
  if (block_length < 2) {
    return Error{fmt::format("FRF grid mapping: block length {} is too short", block_length)};
  }
  if (!(sample_rate_hz > 0.0) || !std::isfinite(sample_rate_hz)) {
    return Error{fmt::format("FRF grid mapping: sample rate {} Hz must be > 0", sample_rate_hz)};
  }
  const double df = sample_rate_hz / static_cast<double>(block_length);
  const double eps = 1e-9 * df;
  const std::size_t bins = block_length / 2 + 1;
  const double f_lo = frf.frequency_hz[0];
  const double f_hi = frf.frequency_hz[n - 1];
  std::size_t first = bins;
  std::size_t last = 0;
  for (std::size_t k = 0; k < bins; ++k) {
    const double f = static_cast<double>(k) * df;
    if (f >= f_lo - eps && f <= f_hi + eps) {
      if (first == bins) first = k;
      last = k;
    }
  }
  if (first == bins) {
    return Error{fmt::format(
        "FRF grid mapping: no bin of a {}-sample block at {} Hz (0..{} Hz, step {} Hz) lies in "
        "the FRF range {}..{} Hz",
        block_length, sample_rate_hz, static_cast<double>(bins - 1) * df, df, f_lo, f_hi)};
  }
  FrfGridMapping map;
  map.block_length = block_length;
  map.sample_rate_hz = sample_rate_hz;
  map.block_bins = bins;
  map.first_bin = first;
  const std::size_t count = last - first + 1;
  map.bins_outside = bins - count;
  auto mapped = std::make_shared<FrfMatrix>();
  mapped->frequency_hz.resize(static_cast<Eigen::Index>(count));
  mapped->at.resize(count);
  Eigen::Index j = 0;  // FRF interval [j, j+1] bracketing f
  for (std::size_t i = 0; i < count; ++i) {
    const double f = static_cast<double>(first + i) * df;
    mapped->frequency_hz[static_cast<Eigen::Index>(i)] = f;
    while (j + 1 < n && frf.frequency_hz[j + 1] <= f + eps) ++j;
    if (std::abs(frf.frequency_hz[j] - f) <= eps || j + 1 >= n) {
      mapped->at[i] = frf.at[j];
    } else {
      const double t = (f - frf.frequency_hz[j]) / (frf.frequency_hz[j + 1] - frf.frequency_hz[j]);
      mapped->at[i] = (1.0 - t) * frf.at[j] + t * frf.at[j + 1];
    }
  }
  map.frf.at = mapped->at;
  map.in_range = std::move(mapped);
  return map;
}

}  // namespace gearpath
