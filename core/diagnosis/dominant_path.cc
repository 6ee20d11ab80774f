#include "core/diagnosis/dominant_path.h"

#include <algorithm>
#include <cmath>

namespace gearpath {
namespace {

void MarkLine(double bin_hz, double f, double tolerance_bins, std::uint8_t value,
              std::span<std::uint8_t> mask) noexcept {
  const double centre = f / bin_hz;
  const double lo = std::ceil(centre - tolerance_bins);
  const double hi = std::floor(centre + tolerance_bins);
  const double last = static_cast<double>(mask.size()) - 1.0;
  for (double b = std::max(lo, 0.0); b <= std::min(hi, last); b += 1.0) {
    mask[static_cast<std::size_t>(b)] = value;
  }
}

}  // namespace

void BuildSidebandMask(double bin_hz, std::span<const MeshLines> meshes, int orders, double lo_hz,
                       double hi_hz, double tolerance_bins, std::span<std::uint8_t> mask) noexcept {
  std::fill(mask.begin(), mask.end(), std::uint8_t{0});
  if (!(bin_hz > 0.0) || mask.empty()) return;
  const double top = bin_hz * static_cast<double>(mask.size() - 1);
  for (const MeshLines& m : meshes) {
    if (!(m.mesh_hz > 0.0)) continue;
    for (int h = 1; h * m.mesh_hz <= top + orders * std::max(m.shaft_hz[0], m.shaft_hz[1]); ++h) {
      for (double fs : m.shaft_hz) {
        if (!(fs > 0.0)) continue;
        for (int k = 1; k <= orders; ++k) {
          for (int sign : {-1, 1}) {
            const double f = h * m.mesh_hz + sign * k * fs;
            if (f >= lo_hz && f <= hi_hz && f > 0.0) MarkLine(bin_hz, f, tolerance_bins, 1, mask);
          }
        }
      }
    }
  }
  // Mesh lines themselves carry the healthy, deterministic tone: never sidebands.
  for (const MeshLines& m : meshes) {
    if (!(m.mesh_hz > 0.0)) continue;
    for (int h = 1; h * m.mesh_hz <= top + bin_hz * tolerance_bins; ++h) {
      MarkLine(bin_hz, h * m.mesh_hz, tolerance_bins, 0, mask);
    }
  }
}

void BuildMeshHarmonicMask(double bin_hz, std::span<const MeshLines> meshes, double tolerance_bins,
                           std::span<std::uint8_t> mask) noexcept {
  std::fill(mask.begin(), mask.end(), std::uint8_t{0});
  if (!(bin_hz > 0.0) || mask.empty()) return;
  const double top = bin_hz * static_cast<double>(mask.size() - 1);
  for (const MeshLines& m : meshes) {
    if (!(m.mesh_hz > 0.0)) continue;
    for (int h = 1; h * m.mesh_hz <= top + bin_hz * tolerance_bins; ++h) {
      MarkLine(bin_hz, h * m.mesh_hz, tolerance_bins, 1, mask);
    }
  }
}

int SelectDominantPath(std::span<const double> criterion) noexcept {
  int best = -1;
  for (std::size_t i = 0; i < criterion.size(); ++i) {
    if (!(criterion[i] > 0.0)) continue;
    if (best < 0 || criterion[i] > criterion[static_cast<std::size_t>(best)]) {
      best = static_cast<int>(i);
    }
  }
  return best;
}

void EnergyShares(std::span<const double> energy, std::span<double> share) noexcept {
  if (energy.size() != share.size()) return;
  double total = 0.0;
  for (double e : energy) total += std::isfinite(e) && e > 0.0 ? e : 0.0;
  for (std::size_t i = 0; i < energy.size(); ++i) {
    const double e = std::isfinite(energy[i]) && energy[i] > 0.0 ? energy[i] : 0.0;
    share[i] = total > 0.0 ? e / total : 0.0;
  }
}

}  // namespace gearpath
