#include "core/pipeline/block_workspace.h"

#include <algorithm>
#include <utility>

#include "core/common/simd_clones.h"
#include "core/pipeline/shape_scratch.h"
#include "core/pipeline/shared_frf_operators.h"

namespace gearpath {

Result<BlockWorkspace> BlockWorkspace::Create(const MachineContext& machine, std::size_t n) {
  const double fs = machine.setup.options.sample_rate_hz;
  BlockWorkspace w;
  w.n = n;
  w.bins = n / 2 + 1;
  w.bin_hz = fs / static_cast<double>(n);
  // Machines on one shared FRF set share its mapped matrices (shared_frf_operators.h).
  auto map = machine.setup.shared_frf ? machine.setup.shared_frf->Mapping(n, fs)
                                      : MapFrfToBlockGrid(machine.setup.frf_set.decoupled, n, fs);
  if (!map) return Error{map.error()};
  w.map = std::move(map.value());
  if (machine.setup.shared_frf) {
    auto table = machine.setup.shared_frf->Power(n, fs);
    if (!table) return Error{table.error()};
    w.frf_table = std::move(table.value());
  } else {
    w.frf_table = std::make_shared<const FrfPowerTable>(FrfPowerTable::Build(w.map));
  }

  const std::size_t channels = machine.channels;
  const std::size_t paths = machine.paths;
  const auto in_range = static_cast<Eigen::Index>(w.map.frf.bins());
  w.meshes = machine.unit_meshes;
  if (w.frf_table->paths != paths || w.frf_table->channels != channels ||
      w.frf_table->bins != static_cast<std::size_t>(in_range)) {
    return Error{"the FRF tables do not match the machine's FRF shape"};
  }
  w.forces.setZero(static_cast<Eigen::Index>(paths), in_range);
  w.band_mask.assign(w.bins, 0);
  for (std::size_t k = 0; k < w.bins; ++k) {
    const double f = static_cast<double>(k) * w.bin_hz;
    w.band_mask[k] = w.map.InRange(k) && f >= machine.band_lo && f <= machine.band_hi ? 1 : 0;
  }
  w.sideband_mask.assign(w.bins, 0);
  w.mesh_mask.assign(w.bins, 0);
  w.path_channel_energy.assign(paths * channels, 0.0);
  w.path_sideband_energy.assign(paths, 0.0);
  w.path_energy.assign(paths, 0.0);
  w.path_share.assign(paths, 0.0);
  w.path_criterion.assign(paths, 0.0);
  w.best_channel.assign(paths, 0);
  w.indicators.assign(machine.indicator_count, 0.0);
  w.z.assign(machine.indicator_count, 0.0);
  w.excess.assign(machine.indicator_count, 0.0);
  const std::size_t slots = machine.condition_slots.size();
  w.slot_valid.assign(slots, 0);
  w.slot_shaft_hz.assign(slots, 0.0);
  w.slot_revolutions.assign(slots, 0);
  w.slot_transient_samples.assign(slots, 0);
  w.slot_residual_variance.assign(slots, 0.0);
  w.slot_score.assign(slots, 0.0);
  w.group_score.assign(machine.rate_groups.size(), 0.0);
  w.signature_sensors = std::max(channels, paths);
  w.signature_stride = static_cast<std::size_t>(kSignatureHarmonics) * w.signature_sensors *
                       static_cast<std::size_t>(2 * kSignatureSidebands + 1);
  w.signature_lines.assign(machine.signature_slots.size() * w.signature_stride, Cd{});
  return w;
}

namespace {

// out[i] = h[i] f[i] over n complex values given as interleaved (re, im) doubles.
GEARPATH_SIMD_CLONES
void MultiplyComplex(const double* __restrict h, const double* __restrict f,
                     double* __restrict out, std::size_t n) noexcept {
  for (std::size_t i = 0; i < n; ++i) {
    const double hr = h[2 * i];
    const double hi = h[2 * i + 1];
    const double fr = f[2 * i];
    const double fi = f[2 * i + 1];
    out[2 * i] = hr * fr - hi * fi;
    out[2 * i + 1] = hr * fi + hi * fr;
  }
}

}  // namespace

void BlockWorkspace::Contribution(std::size_t path, std::size_t channel,
                                  std::span<Cd> out) const noexcept {
  const std::size_t in_range = frf_table->bins;
  std::fill(out.begin(), out.begin() + static_cast<std::ptrdiff_t>(map.first_bin), Cd{});
  std::fill(out.begin() + static_cast<std::ptrdiff_t>(map.first_bin + in_range), out.end(), Cd{});
  MultiplyComplex(reinterpret_cast<const double*>(frf_table->Response(path, channel)),
                  reinterpret_cast<const double*>(forces.data() + path * in_range),
                  reinterpret_cast<double*>(out.data() + map.first_bin), in_range);
}

std::span<const double> BlockWorkspace::DominantTime(std::size_t row,
                                                     ShapeScratch& scratch) noexcept {
  if (dominant_time_row != row) {
    if (dominant >= 0) {
      Contribution(static_cast<std::size_t>(dominant), row, scratch.one_spec);
      (void)scratch.inverse->Process(scratch.one_spec, scratch.dominant_time);
    } else {
      std::fill(scratch.dominant_time.begin(), scratch.dominant_time.end(), 0.0);
    }
    dominant_time_row = row;
  }
  return scratch.dominant_time;
}

}  // namespace gearpath
