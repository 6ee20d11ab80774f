// ParametricGearbox: the truth of the parametric_plate family, a two-stage (in general N-stage)
// gear train with time-varying mesh stiffness (ToothMesh) on bearings mounted on a plate
// housing (PlateHousing), simulated in the time domain (GearboxIntegrator).
//
// Degrees of freedom (rotor side, 2 per shaft, then the plate's modal coordinates):
//   u = [phi_0 .. phi_{S-1}, x_0 .. x_{S-1}, q_1 .. q_N]
// phi_i: rotation of shaft i relative to its NOMINAL rotation theta_i^nom(t) = sigma_i rho_i
// 2 pi r(t) (r the input revolutions, rho_i the shaft's revolutions per input revolution,
// sigma_i = +/-1: external gears turn opposite ways), rad; x_i: lateral displacement of shaft
// i along the line of action (the plate normal: the train's pedestal bearings stand on the
// plate and the lines of action are normal to it), m; q_r: mass-normalised plate modal
// coordinates.
// Links:
//   - motor: a torsional coupling k_m, c_m from shaft 0 to the prescribed motor angle
//     theta_0^nom(t) (the input is driven at the block's speed profile, drift included);
//   - load: on the last shaft, a constant torque T_L against its rotation plus a viscous load
//     c_L d theta / dt;
//   - mesh s (driver shaft a, driven shaft b): approach delta_s = sigma_a (rb_a phi_a +
//     rb_b phi_b) + x_a - x_b (the nominal motions roll without approach);
//     force F_s = k_s(t) delta_s - error_force_s + c_s (d delta_s / dt - error_rate_s)
//     (ToothMesh), acting -F_s d delta_s / du on the DOFs;
//   - bearing i (shaft i <-> plate point i): F_b,i = k_b,i (x_i - w_i) + c_b,i (dx_i/dt -
//     dw_i/dt), w_i = sum_r phi_r(P_i) q_r; -F_b,i on the shaft, +F_b,i on the plate (the force
//     the bearing exerts on its seat, seed Eq. 44, what the daemon identifies);
//   - plate: q_r'' + 2 zeta_r w_r q_r' + w_r^2 q_r = sum_i phi_r(P_i) F_b,i.
// Inertial forcing of the nominal motion: -J_i d^2 theta_i^nom / dt^2 on phi_i (speed drift).
// The coupling is two-way: the plate's motion at the seats feeds back through the bearings.
#pragma once

#include <Eigen/Dense>
#include <vector>

#include "core/common/result.h"
#include "core/evaluation/plate_housing.h"
#include "core/evaluation/tooth_mesh.h"

namespace gearpath {

struct ShaftRotor {
  double inertia_kg_m2 = 0.0;             // J_i, gears + shaft
  double mass_kg = 0.0;                   // lateral mass
  double bearing_stiffness_n_per_m = 0.0;  // k_b,i
  double bearing_damping_ns_per_m = 0.0;   // c_b,i
  double revs_per_input_rev = 1.0;         // rho_i > 0
  int rotation_sign = 1;                   // sigma_i
};

struct MeshStage {
  int driver_shaft = 0;
  int driven_shaft = 1;
  double driver_base_radius_m = 0.0;
  double driven_base_radius_m = 0.0;
  double damping_ns_per_m = 0.0;  // c_s
  ToothMeshParameters mesh;
};

struct ParametricGearboxParameters {
  std::vector<ShaftRotor> shafts;  // shaft i's bearing sits at plate point i
  std::vector<MeshStage> stages;
  double motor_stiffness_nm_per_rad = 0.0;
  double motor_damping_nms_per_rad = 0.0;
  double load_torque_nm = 0.0;
  double load_damping_nms_per_rad = 0.0;
  PlateHousing plate;  // points: one bearing seat per shaft, then any measurement points
};

class ParametricGearbox {
 public:
  ParametricGearbox() = default;
  // Validates (messages name the field) and builds the meshes.
  static Result<ParametricGearbox> Create(ParametricGearboxParameters parameters);

  const ParametricGearboxParameters& parameters() const noexcept { return p_; }
  const std::vector<ToothMesh>& meshes() const noexcept { return meshes_; }
  const PlateHousing& plate() const noexcept { return p_.plate; }
  int shaft_count() const noexcept { return static_cast<int>(p_.shafts.size()); }
  int stage_count() const noexcept { return static_cast<int>(p_.stages.size()); }
  int rotor_dofs() const noexcept { return 2 * shaft_count(); }
  int dof_count() const noexcept { return rotor_dofs() + p_.plate.mode_count(); }
  int RotationDof(int shaft) const noexcept { return shaft; }
  int LateralDof(int shaft) const noexcept { return shaft_count() + shaft; }
  int ModalDof(int mode) const noexcept { return rotor_dofs() + mode; }

  // d delta_s / du over the rotor DOFs (rotor_dofs() entries).
  const Eigen::VectorXd& MeshVector(int stage) const noexcept { return mesh_vectors_[stage]; }

  // The full matrices (dof_count() square) with mesh stiffnesses k_s (one per stage).
  void Assemble(const std::vector<double>& mesh_stiffness, Eigen::MatrixXd& mass,
                Eigen::MatrixXd& damping, Eigen::MatrixXd& stiffness) const;

  // Generalised force of the nominal motion on the rotor DOFs at input speed `speed_hz` (rev/s)
  // and its rate `speed_rate` (rev/s^2): load torque, viscous load, inertial forcing.
  void NominalForce(double speed_hz, double speed_rate, Eigen::VectorXd& force) const;

 private:
  ParametricGearboxParameters p_;
  std::vector<ToothMesh> meshes_;
  std::vector<Eigen::VectorXd> mesh_vectors_;
};

}  // namespace gearpath
