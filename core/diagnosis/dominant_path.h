// Dominant transfer path: the path whose contribution carries the fault (seed Sect. 4.2,
// Figs. 14-15: "the path with the highest contribution indicates the nearest gear").
//
// Criterion (docs/diagnosis.md). The seed compares whole contributions; on a gearbox most of
// that energy is the deterministic mesh tones, present when healthy and largest on the path
// nearest the stiffest mesh, whatever the fault. A localized tooth fault modulates its mesh at
// its shaft rate: its energy appears as SIDEBANDS h f_mesh +/- k f_shaft around the mesh
// harmonics. So the default criterion is each path's contribution energy (summed over
// channels) on the sideband lines of every mesh (both shafts of the pair, k = 1..K), mesh lines
// themselves excluded, inside the analysis band. Alternatives: the whole analysis-band energy
// (the seed's literal comparison) or the fault indicator of each path's contribution.
// The per-path energy SHARES published with every result are always the analysis-band
// energies normalised to sum to 1.
#pragma once

#include <array>
#include <cstdint>
#include <span>

namespace gearpath {

struct MeshLines {
  double mesh_hz = 0.0;              // fundamental mesh frequency
  std::array<double, 2> shaft_hz{};  // rates of the two shafts of the pair
};

// mask[k] = 1 where bin k (at k bin_hz) lies within +/- tolerance_bins of a sideband line
// h f_m +/- k f_s (k = 1..orders, s the pair's two shafts) with the line in [lo_hz, hi_hz], and
// not within +/- tolerance_bins of any mesh harmonic h f_m; 0 elsewhere. noexcept, no
// allocation; mask.size() = number of bins.
void BuildSidebandMask(double bin_hz, std::span<const MeshLines> meshes, int orders, double lo_hz,
                       double hi_hz, double tolerance_bins, std::span<std::uint8_t> mask) noexcept;

// mask[k] = 1 where bin k is within +/- tolerance_bins of a mesh harmonic h f_m (h >= 1, up to
// the last bin). Used to comb-remove the deterministic mesh tones before envelope analysis.
void BuildMeshHarmonicMask(double bin_hz, std::span<const MeshLines> meshes, double tolerance_bins,
                           std::span<std::uint8_t> mask) noexcept;

// Index of the largest criterion (first one on ties); -1 when empty or all are <= 0 or NaN.
int SelectDominantPath(std::span<const double> criterion) noexcept;

// share[i] = energy[i] / sum(energy) (all 0 when the sum is 0). Sizes must match.
void EnergyShares(std::span<const double> energy, std::span<double> share) noexcept;

}  // namespace gearpath
