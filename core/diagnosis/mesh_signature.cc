#include "core/diagnosis/mesh_signature.h"

#include <cmath>

namespace gearpath {

void AccumulateMeshSignature(std::span<const std::complex<double>> lines, std::size_t sensors,
                             int sideband_orders, MeshSignatureEnergy& sum) noexcept {
  const auto width = static_cast<std::size_t>(2 * sideband_orders + 1);
  if (sensors == 0 || lines.size() < sensors * width) return;
  const auto centre = static_cast<std::size_t>(sideband_orders);
  double tone_norm2 = 0.0;
  for (std::size_t s = 0; s < sensors; ++s) tone_norm2 += std::norm(lines[s * width + centre]);
  for (std::size_t j = 0; j < width; ++j) {
    if (j == centre) continue;
    double total = 0.0;
    std::complex<double> projection{};
    for (std::size_t s = 0; s < sensors; ++s) {
      const std::complex<double> v = lines[s * width + j];
      total += std::norm(v);
      projection += std::conj(lines[s * width + centre]) * v;
    }
    const double parallel = tone_norm2 > 0.0 ? std::norm(projection) / tone_norm2 : 0.0;
    sum.parallel += 0.5 * parallel;
    sum.orthogonal += 0.5 * std::max(0.0, total - parallel);
  }
}

}  // namespace gearpath
