#include "core/pipeline/frf_power_table.h"

#include <complex>

namespace gearpath {

FrfPowerTable FrfPowerTable::Build(const FrfGridMapping& map) {
  FrfPowerTable t;
  t.bins = static_cast<std::size_t>(map.frf.bins());
  if (t.bins == 0) return t;
  t.channels = static_cast<std::size_t>(map.frf.at[0].rows());
  t.paths = static_cast<std::size_t>(map.frf.at[0].cols());
  t.power.assign(t.paths * t.channels * t.bins, 0.0F);
  t.response.assign(t.paths * t.channels * t.bins, {});
  // Bin by bin: each per-bin matrix is read once (they are scattered on the heap).
  for (std::size_t i = 0; i < t.bins; ++i) {
    const Eigen::MatrixXcd& m = map.frf.at[i];
    for (std::size_t p = 0; p < t.paths; ++p) {
      for (std::size_t c = 0; c < t.channels; ++c) {
        const std::complex<double> h =
            m(static_cast<Eigen::Index>(c), static_cast<Eigen::Index>(p));
        const std::size_t at = (p * t.channels + c) * t.bins + i;
        t.power[at] = static_cast<float>(std::norm(h));
        t.response[at] = h;
      }
    }
  }
  return t;
}

}  // namespace gearpath
