#include "core/evaluation/plate_housing.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>

namespace gearpath {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kTwoPi = 2.0 * std::numbers::pi;

bool Positive(double v) { return v > 0.0 && std::isfinite(v); }

}  // namespace

double PlateGeometry::BendingStiffness() const noexcept {
  return youngs_modulus_pa * thickness_m * thickness_m * thickness_m /
         (12.0 * (1.0 - poisson_ratio * poisson_ratio));
}

double PlateGeometry::MassPerArea() const noexcept { return density_kg_per_m3 * thickness_m; }

double PlateGeometry::ModeFrequencyHz(int m, int n) const noexcept {
  const double km = static_cast<double>(m) / length_m;
  const double kn = static_cast<double>(n) / width_m;
  const double w = kPi * kPi * std::sqrt(BendingStiffness() / MassPerArea()) * (km * km + kn * kn);
  return w / kTwoPi;
}

std::vector<PlateMode> EnumeratePlateModes(const PlateGeometry& geometry,
                                           double max_frequency_hz) {
  std::vector<PlateMode> modes;
  if (!Positive(geometry.BendingStiffness()) || !Positive(geometry.MassPerArea()) ||
      !Positive(max_frequency_hz)) {
    return modes;
  }
  for (int m = 1; geometry.ModeFrequencyHz(m, 1) <= max_frequency_hz; ++m) {
    for (int n = 1; geometry.ModeFrequencyHz(m, n) <= max_frequency_hz; ++n) {
      modes.push_back({m, n, geometry.ModeFrequencyHz(m, n), 0.0});
    }
  }
  std::sort(modes.begin(), modes.end(), [](const PlateMode& p, const PlateMode& q) {
    if (p.frequency_hz != q.frequency_hz) return p.frequency_hz < q.frequency_hz;
    if (p.m != q.m) return p.m < q.m;
    return p.n < q.n;
  });
  return modes;
}

Result<PlateHousing> PlateHousing::Create(const PlateGeometry& geometry,
                                          std::vector<PlateMode> modes,
                                          std::vector<PlatePoint> points) {
  const PlateGeometry& g = geometry;
  if (!Positive(g.length_m) || !Positive(g.width_m) || !Positive(g.thickness_m) ||
      !Positive(g.youngs_modulus_pa) || !Positive(g.density_kg_per_m3) ||
      !(g.poisson_ratio >= 0.0 && g.poisson_ratio < 0.5)) {
    return Error{fmt::format(
        "plate housing: length_m, width_m, thickness_m, youngs_modulus_pa and "
        "density_kg_per_m3 must be > 0 and poisson_ratio in [0, 0.5), got {}, {}, {}, {}, {}, {}",
        g.length_m, g.width_m, g.thickness_m, g.youngs_modulus_pa, g.density_kg_per_m3,
        g.poisson_ratio)};
  }
  if (modes.empty()) return Error{"plate housing: no modes"};
  for (std::size_t r = 0; r < modes.size(); ++r) {
    const PlateMode& m = modes[r];
    if (m.m < 1 || m.n < 1 || !(m.damping_ratio >= 0.0 && m.damping_ratio < 1.0)) {
      return Error{fmt::format(
          "plate housing: modes[{}] ({}, {}) needs m, n >= 1 and damping_ratio in [0, 1), got "
          "{}",
          r, m.m, m.n, m.damping_ratio)};
    }
  }
  for (std::size_t p = 0; p < points.size(); ++p) {
    const PlatePoint& q = points[p];
    if (!(q.x_m > 0.0 && q.x_m < g.length_m && q.y_m > 0.0 && q.y_m < g.width_m)) {
      return Error{fmt::format("plate housing: points[{}] ({}, {}) m lies outside the plate's "
                               "interior (0, {}) x (0, {})",
                               p, q.x_m, q.y_m, g.length_m, g.width_m)};
    }
  }
  PlateHousing plate;
  plate.geometry_ = g;
  plate.modes_ = std::move(modes);
  plate.points_ = std::move(points);
  const Eigen::Index nm = plate.mode_count();
  const Eigen::Index np = plate.point_count();
  plate.omega_.resize(nm);
  plate.shapes_.resize(np, nm);
  for (Eigen::Index r = 0; r < nm; ++r) {
    PlateMode& mode = plate.modes_[static_cast<std::size_t>(r)];
    mode.frequency_hz = g.ModeFrequencyHz(mode.m, mode.n);
    plate.omega_[r] = kTwoPi * mode.frequency_hz;
    for (Eigen::Index p = 0; p < np; ++p) {
      const PlatePoint& q = plate.points_[static_cast<std::size_t>(p)];
      plate.shapes_(p, r) = plate.Shape(static_cast<int>(r), q.x_m, q.y_m);
    }
  }
  return plate;
}

double PlateHousing::Shape(int r, double x_m, double y_m) const noexcept {
  const PlateMode& mode = modes_[static_cast<std::size_t>(r)];
  const double scale =
      2.0 / std::sqrt(geometry_.MassPerArea() * geometry_.length_m * geometry_.width_m);
  return scale * std::sin(static_cast<double>(mode.m) * kPi * x_m / geometry_.length_m) *
         std::sin(static_cast<double>(mode.n) * kPi * y_m / geometry_.width_m);
}

Eigen::MatrixXcd PlateHousing::Accelerance(double frequency_hz, const std::vector<int>& rows,
                                           const std::vector<int>& cols) const {
  const double w = kTwoPi * frequency_hz;
  Eigen::MatrixXcd h = Eigen::MatrixXcd::Zero(static_cast<Eigen::Index>(rows.size()),
                                              static_cast<Eigen::Index>(cols.size()));
  for (Eigen::Index r = 0; r < omega_.size(); ++r) {
    const double wr = omega_[r];
    const double zeta = modes_[static_cast<std::size_t>(r)].damping_ratio;
    const std::complex<double> g = -w * w / std::complex<double>(wr * wr - w * w, 2.0 * zeta * wr * w);
    for (std::size_t i = 0; i < rows.size(); ++i) {
      for (std::size_t j = 0; j < cols.size(); ++j) {
        h(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) +=
            g * shapes_(rows[i], r) * shapes_(cols[j], r);
      }
    }
  }
  return h;
}

}  // namespace gearpath
