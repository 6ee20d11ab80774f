// PlateHousing: the housing of the parametric_plate family, a thin rectangular plate simply
// supported on its four edges (Kirchhoff plate theory; A. W. Leissa, Vibration of Plates, NASA
// SP-160, 1969, section 4.1), with analytic modes:
//   D        = E h^3 / (12 (1 - nu^2))                          bending stiffness, N m
//   w_mn     = pi^2 sqrt(D / (rho h)) ((m / a)^2 + (n / b)^2)     rad/s, m, n = 1, 2, ...
//   phi_mn   = 2 / sqrt(rho h a b) sin(m pi x / a) sin(n pi y / b)  mass-normalised
//              (integral of rho h phi^2 over the plate = 1)
//   H(P, Q)  = sum_mn phi_mn(P) phi_mn(Q) (-w^2) / (w_mn^2 - w^2 + 2 j zeta_mn w_mn w)
// H is the accelerance: normal acceleration at P per normal force at Q, m/s^2/N (the sign
// convention of core/model: exp(+j w t), a = -w^2 x). The mode set is truncated at a cutoff
// frequency; each mode carries its own damping ratio (modal damping). Points are given in
// plate coordinates (0 < x < a, 0 < y < b); the family puts the three bearing seats and the
// extra measurement point m1 there.
#pragma once

#include <Eigen/Dense>
#include <vector>

#include "core/common/result.h"

namespace gearpath {

struct PlateGeometry {
  double length_m = 0.6;       // a, along x
  double width_m = 0.45;       // b, along y
  double thickness_m = 0.016;  // h
  double youngs_modulus_pa = 2.1e11;
  double poisson_ratio = 0.3;
  double density_kg_per_m3 = 7850.0;

  double BendingStiffness() const noexcept;  // D, N m
  double MassPerArea() const noexcept;       // rho h, kg/m^2
  // Natural frequency of mode (m, n), Hz.
  double ModeFrequencyHz(int m, int n) const noexcept;
};

struct PlatePoint {
  double x_m = 0.0;
  double y_m = 0.0;
};

struct PlateMode {
  int m = 1;
  int n = 1;
  double frequency_hz = 0.0;
  double damping_ratio = 0.0;
};

// Every mode (m, n) of the plate with frequency <= max_frequency_hz, ascending in frequency
// (ties by m, then n), damping 0 (the caller sets it).
std::vector<PlateMode> EnumeratePlateModes(const PlateGeometry& geometry, double max_frequency_hz);

class PlateHousing {
 public:
  PlateHousing() = default;
  // Fails on a non-positive dimension or material constant, a point outside the plate's
  // interior, an empty mode list or a mode with damping outside [0, 1) (messages name it).
  static Result<PlateHousing> Create(const PlateGeometry& geometry, std::vector<PlateMode> modes,
                                     std::vector<PlatePoint> points);

  const PlateGeometry& geometry() const noexcept { return geometry_; }
  const std::vector<PlateMode>& modes() const noexcept { return modes_; }
  const std::vector<PlatePoint>& points() const noexcept { return points_; }
  int mode_count() const noexcept { return static_cast<int>(modes_.size()); }
  int point_count() const noexcept { return static_cast<int>(points_.size()); }

  // Mass-normalised shape of mode r at (x, y).
  double Shape(int r, double x_m, double y_m) const noexcept;
  // Shapes at the points: points x modes.
  const Eigen::MatrixXd& shapes() const noexcept { return shapes_; }
  // Natural angular frequencies, rad/s, per mode.
  const Eigen::VectorXd& omega() const noexcept { return omega_; }

  // Accelerance between the listed points (rows: response points, cols: force points).
  Eigen::MatrixXcd Accelerance(double frequency_hz, const std::vector<int>& rows,
                               const std::vector<int>& cols) const;

 private:
  PlateGeometry geometry_;
  std::vector<PlateMode> modes_;
  std::vector<PlatePoint> points_;
  Eigen::MatrixXd shapes_;
  Eigen::VectorXd omega_;
};

}  // namespace gearpath
