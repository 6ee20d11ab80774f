// MeshSignature: does the energy around a mesh harmonic travel like that mesh's own tone?
//
// A mesh's transmission error reaches every sensor (or every identified bearing force)
// through that mesh's own transfer G_m(f), so at a mesh harmonic h f_m the vector of
// synchronous-average lines across sensors is G_m(h f_m) E_h: its direction is the mesh's
// transfer signature there. Sidebands h f_m +/- k f_s (k small) caused by the SAME mesh (its
// eccentricity, a tooth fault on one of its gears, additive or modulating) travel the same way,
// G_m being smooth over a few shaft orders, so they are parallel to the tone. Lines caused by
// the OTHER mesh's excitation travel through that mesh's transfer and point elsewhere. So near
// each mesh harmonic the sideband energy splits into a part parallel to the tone (explained by
// this mesh) and an orthogonal part (not explained by it). A fault on mesh m raises the
// parallel part near m's harmonics and, when broadband (a pulse, a dip), the orthogonal part
// near the other meshes' harmonics. Needs at least two sensors (or paths).
//
// lines: sensors x (2K + 1) complex lines, sensor-major; entry K of each sensor is the tone
// (offset 0), entries K +/- k the sidebands at offset +/- k. Energies in units^2 (|.|^2 / 2 per
// line, as a mean square).
#pragma once

#include <complex>
#include <cstddef>
#include <span>

namespace gearpath {

struct MeshSignatureEnergy {
  double parallel = 0.0;    // sideband energy along the tone's direction
  double orthogonal = 0.0;  // sideband energy orthogonal to it
};

// Adds one mesh harmonic's sideband energies to `sum`. Tone of zero norm: everything counts as
// orthogonal (no direction to compare with). noexcept, no allocation.
void AccumulateMeshSignature(std::span<const std::complex<double>> lines, std::size_t sensors,
                             int sideband_orders, MeshSignatureEnergy& sum) noexcept;

}  // namespace gearpath
