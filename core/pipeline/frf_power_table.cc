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
  for (std::size_t p = 0; p < t.paths; ++p) {
    for (std::size_t c = 0; c < t.channels; ++c) {
      float* row = t.power.data() + (p * t.channels + c) * t.bins;
      for (std::size_t i = 0; i < t.bins; ++i) {
        row[i] = static_cast<float>(std::norm(
            map.frf.at[i](static_cast<Eigen::Index>(c), static_cast<Eigen::Index>(p))));
      }
    }
  }
  return t;
}

}  // namespace gearpath
