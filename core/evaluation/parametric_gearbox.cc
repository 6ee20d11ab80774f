#include "core/evaluation/parametric_gearbox.h"

#include <fmt/format.h>

#include <cmath>
#include <numbers>

namespace gearpath {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

bool PositiveFinite(double v) { return v > 0.0 && std::isfinite(v); }
bool NonNegativeFinite(double v) { return v >= 0.0 && std::isfinite(v); }

}  // namespace

Result<ParametricGearbox> ParametricGearbox::Create(ParametricGearboxParameters parameters) {
  const ParametricGearboxParameters& p = parameters;
  const int shafts = static_cast<int>(p.shafts.size());
  if (shafts < 2 || p.stages.size() + 1 != p.shafts.size()) {
    return Error{fmt::format(
        "parametric gearbox: needs S >= 2 shafts and S - 1 stages, got {} shafts, {} stages",
        shafts, p.stages.size())};
  }
  if (p.plate.point_count() < shafts || p.plate.mode_count() < 1) {
    return Error{fmt::format(
        "parametric gearbox: the plate needs a mode and one point per shaft, has {} modes, {} "
        "points for {} shafts",
        p.plate.mode_count(), p.plate.point_count(), shafts)};
  }
  for (int i = 0; i < shafts; ++i) {
    const ShaftRotor& r = p.shafts[static_cast<std::size_t>(i)];
    if (!PositiveFinite(r.inertia_kg_m2) || !PositiveFinite(r.mass_kg) ||
        !PositiveFinite(r.bearing_stiffness_n_per_m) ||
        !NonNegativeFinite(r.bearing_damping_ns_per_m) || !PositiveFinite(r.revs_per_input_rev) ||
        (r.rotation_sign != 1 && r.rotation_sign != -1)) {
      return Error{fmt::format(
          "parametric gearbox: shafts[{}] needs inertia, mass, bearing stiffness and "
          "revs_per_input_rev > 0, bearing damping >= 0 and rotation_sign +/-1",
          i)};
    }
  }
  if (!PositiveFinite(p.motor_stiffness_nm_per_rad) ||
      !NonNegativeFinite(p.motor_damping_nms_per_rad) || !NonNegativeFinite(p.load_torque_nm) ||
      !NonNegativeFinite(p.load_damping_nms_per_rad)) {
    return Error{
        "parametric gearbox: motor_stiffness_nm_per_rad must be > 0; motor damping, load torque "
        "and load damping >= 0"};
  }
  ParametricGearbox g;
  for (std::size_t s = 0; s < p.stages.size(); ++s) {
    const MeshStage& st = p.stages[s];
    if (st.driver_shaft < 0 || st.driver_shaft >= shafts || st.driven_shaft < 0 ||
        st.driven_shaft >= shafts || st.driver_shaft == st.driven_shaft ||
        !PositiveFinite(st.driver_base_radius_m) || !PositiveFinite(st.driven_base_radius_m) ||
        !NonNegativeFinite(st.damping_ns_per_m)) {
      return Error{fmt::format(
          "parametric gearbox: stages[{}] needs two distinct shafts, base radii > 0 and damping "
          ">= 0",
          s)};
    }
    const ShaftRotor& a = p.shafts[static_cast<std::size_t>(st.driver_shaft)];
    const ShaftRotor& b = p.shafts[static_cast<std::size_t>(st.driven_shaft)];
    if (a.rotation_sign == b.rotation_sign ||
        std::abs(a.revs_per_input_rev * st.driver_base_radius_m -
                 b.revs_per_input_rev * st.driven_base_radius_m) >
            1e-9 * a.revs_per_input_rev * st.driver_base_radius_m) {
      return Error{fmt::format(
          "parametric gearbox: stages[{}]: the nominal motions must roll (opposite rotation "
          "signs, rho_a rb_a = rho_b rb_b)",
          s)};
    }
    Result<ToothMesh> mesh = ToothMesh::Create(st.mesh);
    if (!mesh) return Error{fmt::format("parametric gearbox: stages[{}]: {}", s, mesh.error())};
    g.meshes_.push_back(std::move(mesh).value());
    Eigen::VectorXd v = Eigen::VectorXd::Zero(2 * shafts);
    const double sigma = a.rotation_sign;
    v[st.driver_shaft] = sigma * st.driver_base_radius_m;
    v[st.driven_shaft] = sigma * st.driven_base_radius_m;
    v[shafts + st.driver_shaft] = 1.0;
    v[shafts + st.driven_shaft] = -1.0;
    g.mesh_vectors_.push_back(std::move(v));
  }
  g.p_ = std::move(parameters);
  return g;
}

void ParametricGearbox::Assemble(const std::vector<double>& mesh_stiffness, Eigen::MatrixXd& mass,
                                 Eigen::MatrixXd& damping, Eigen::MatrixXd& stiffness) const {
  const int n = dof_count();
  const int shafts = shaft_count();
  mass = Eigen::MatrixXd::Zero(n, n);
  damping = Eigen::MatrixXd::Zero(n, n);
  stiffness = Eigen::MatrixXd::Zero(n, n);
  for (int i = 0; i < shafts; ++i) {
    const ShaftRotor& r = p_.shafts[static_cast<std::size_t>(i)];
    mass(RotationDof(i), RotationDof(i)) = r.inertia_kg_m2;
    mass(LateralDof(i), LateralDof(i)) = r.mass_kg;
  }
  stiffness(RotationDof(0), RotationDof(0)) += p_.motor_stiffness_nm_per_rad;
  damping(RotationDof(0), RotationDof(0)) += p_.motor_damping_nms_per_rad;
  damping(RotationDof(shafts - 1), RotationDof(shafts - 1)) += p_.load_damping_nms_per_rad;
  for (int s = 0; s < stage_count(); ++s) {
    const Eigen::VectorXd& v = mesh_vectors_[static_cast<std::size_t>(s)];
    const double k = mesh_stiffness[static_cast<std::size_t>(s)];
    const double c = p_.stages[static_cast<std::size_t>(s)].damping_ns_per_m;
    stiffness.topLeftCorner(rotor_dofs(), rotor_dofs()) += k * v * v.transpose();
    damping.topLeftCorner(rotor_dofs(), rotor_dofs()) += c * v * v.transpose();
  }
  const PlateHousing& plate = p_.plate;
  for (int r = 0; r < plate.mode_count(); ++r) {
    const double w = plate.omega()[r];
    mass(ModalDof(r), ModalDof(r)) = 1.0;
    stiffness(ModalDof(r), ModalDof(r)) += w * w;
    damping(ModalDof(r), ModalDof(r)) +=
        2.0 * plate.modes()[static_cast<std::size_t>(r)].damping_ratio * w;
  }
  // Bearing i: relative displacement x_i - sum_r phi_r(P_i) q_r.
  for (int i = 0; i < shafts; ++i) {
    Eigen::VectorXd l = Eigen::VectorXd::Zero(n);
    l[LateralDof(i)] = 1.0;
    for (int r = 0; r < plate.mode_count(); ++r) l[ModalDof(r)] = -plate.shapes()(i, r);
    const ShaftRotor& rot = p_.shafts[static_cast<std::size_t>(i)];
    stiffness += rot.bearing_stiffness_n_per_m * l * l.transpose();
    damping += rot.bearing_damping_ns_per_m * l * l.transpose();
  }
}

void ParametricGearbox::NominalForce(double speed_hz, double speed_rate,
                                     Eigen::VectorXd& force) const {
  const int shafts = shaft_count();
  force.setZero(rotor_dofs());
  for (int i = 0; i < shafts; ++i) {
    const ShaftRotor& r = p_.shafts[static_cast<std::size_t>(i)];
    const double sigma_rho = r.rotation_sign * r.revs_per_input_rev;
    force[RotationDof(i)] = -r.inertia_kg_m2 * sigma_rho * kTwoPi * speed_rate;
  }
  const ShaftRotor& out = p_.shafts.back();
  force[RotationDof(shafts - 1)] -=
      out.rotation_sign * (p_.load_torque_nm + p_.load_damping_nms_per_rad *
                                                   out.revs_per_input_rev * kTwoPi * speed_hz);
}

}  // namespace gearpath
