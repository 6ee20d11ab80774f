// LumpedGearboxModel: the seed's lumped-parameter model of a multistage parallel-axis gearbox
// (seed Eqs. 1-7, Table 1), generalised from two stages to N >= 1 stages.
//
// Masses and DOFs (N stages -> N+1 rotors, N+1 bearing seats, one central housing mass):
//   q = [x_0, th_0, x_1, th_1, ..., x_N, th_N,  s_0, ..., s_N,  h]       (3N + 4 DOFs)
// x_i, th_i: translation along the line of action [m] and rotation [rad] of rotor i (rotor 0
// carries the stage-0 driver; rotor i, 0 < i < N, the driven gear of stage i-1 and the driver of
// stage i; rotor N the last driven gear). s_i: translation of the bearing seat of rotor i, h:
// translation of the central housing mass. For N = 2 this is the seed's Eq. 2 order
// [x1, th1, x2, th2, x3, th3, x4, x5, x6, x7].
// Links (spring k parallel to damper c): rotor i <-> seat i (bearing, seed k14, k25, k36),
// seat i <-> housing (seed k47, k57, k67), housing <-> ground (k07), and one mesh per stage.
//
// Mesh of stage s (driver on rotor s, driven on rotor s+1), time-averaged (seed Eq. 6 uses
// time-averaged K and C): deflection d_s = x_s + rb_dr th_s - x_{s+1} + rb_dn th_{s+1} = v_s^T q,
// energy k_s (d_s - e_s)^2 / 2 with e_s the static transmission error, so the mesh adds
// k_s v_s v_s^T to K, c_s v_s v_s^T to C, and a TE e_s(w) acts as the generalized force
// (k_s + j w c_s) e_s v_s. Both rotations use one common sense (rolling without TE has
// rb_dr th_s = -rb_dn th_{s+1}, i.e. external gears turn opposite ways).
// Cross-check with the seed's printed K (Eq. 4, OCR): it matches k_s v_s v_s^T except that
// (a) entry (x2, th1) is printed as +rb1 k1 while (th1, x2) is -rb1 k1; the symmetric energy
// form gives -rb1 k1 for both; (b) the diagonal (x2, x2) and (x3, x3) omit the bearing
// stiffnesses k25 and k36 although their off-diagonal -k25, -k36 are present: the energy form
// has k1 + k2 + k25 and k2 + k36. Same for C (Eq. 5). The seed's Eq. 7 (housing alone) matches.
//
// Derived parameters (all documented in docs/model.md):
// - Gear i: solid steel disc of pitch radius r = m z / 2 and face width b: mass rho pi r^2 b,
//   inertia mass r^2 / 2; base radius rb = r cos(alpha). A rotor carries all its gears plus an
//   optional solid shaft (radius, length; length 0 = no shaft mass, Table 1 gives no length).
// - Mesh stiffness (time-averaged): ISO 6336-1 mean mesh stiffness c_gamma_alpha =
//   c' (0.75 eps_alpha + 0.25) per unit face width, c' = 14 N/(mm um) (ISO 6336-1's single
//   stiffness of solid standard spur gears), eps_alpha the transverse contact ratio from the
//   tip radii r + h_a* m; k_s = c_gamma_alpha b. ~21 N/(mm um) for Table 1. Overridable.
// - Mesh damping c_s = 2 zeta sqrt(k_s m_e), m_e = (J_a/rb_a^2)(J_b/rb_b^2)/(J_a/rb_a^2 +
//   J_b/rb_b^2) the equivalent mass of the two rotors along the line of action.
//
// Sign conventions: x positive along the line of action (the same axis for every mass),
// harmonic time dependence exp(+j w t), accelerance H = a / f = -w^2 (-w^2 M + j w C + K)^-1.
// The seed prints Eq. 6 without the minus sign; gearpath uses the physical accelerance so that
// the model's FRFs, its forced-response accelerations (-w^2 X) and measured FRFs all agree, and
// forces identified from simulated accelerations come out with their true sign. Bearing force F_i = (k_b,i + j w c_b,i)(X_rotor_i - X_seat_i) is the force the
// bearing exerts ON seat i, positive along +x (seed Eq. 44).
//
// Everything fixed per model (M, C, K, the housing-alone matrices, the undamped modes) is built
// once at construction; the per-frequency functions only factorise the dynamic stiffness.
#pragma once

#include <Eigen/Dense>
#include <optional>
#include <vector>

#include "core/common/frf_matrix.h"
#include "core/common/result.h"
#include "core/frf/coupled_blocks.h"

namespace gearpath {

// One gear stage. Tooth counts are of the driver (on the upstream rotor) and the driven gear.
struct GearStage {
  int z_driver = 0;
  int z_driven = 0;
  std::optional<double> mesh_stiffness_n_per_m;  // overrides the ISO 6336 estimate when set
};

struct GearboxParameters {
  std::vector<GearStage> stages;  // N >= 1
  // Per rotor / per seat, N + 1 entries each (seed: k14, k25, k36; c14, ...; M4, M5, M6; ...).
  std::vector<double> bearing_stiffness_n_per_m;  // rotor i <-> seat i, > 0
  std::vector<double> bearing_damping_ns_per_m;   // >= 0
  std::vector<double> seat_mass_kg;               // > 0
  std::vector<double> seat_stiffness_n_per_m;     // seat i <-> central housing mass, > 0
  std::vector<double> seat_damping_ns_per_m;      // >= 0
  // Optional torsional spring of each rotor to ground (motor / load couplings), N + 1 entries
  // or empty (= none, the seed's model: the gear train then has one free rotation mode).
  std::vector<double> torsional_stiffness_nm_per_rad;
  double housing_mass_kg = 0.0;           // > 0 (seed M7)
  double ground_stiffness_n_per_m = 0.0;  // >= 0 (seed k07)
  double ground_damping_ns_per_m = 0.0;   // >= 0 (seed c07)
  // Gear geometry and material (one module for the whole train, as in Table 1).
  double module_m = 3e-3;
  double face_width_m = 16e-3;
  double pressure_angle_deg = 20.0;
  double addendum_coefficient = 1.0;
  double density_kg_per_m3 = 7850.0;
  double shaft_radius_m = 24e-3;
  double shaft_length_m = 0.0;  // 0 = gears only (Table 1 has no shaft length)
  double mesh_damping_ratio = 0.02;
  double single_tooth_stiffness_n_per_m2 = 14e9;  // c' = 14 N/(mm um) = 14e9 N/m^2
};

// Table 1 of the seed. Values the table leaves out, and why (see docs/model.md):
// - "M3 = 3" is read as M6 = 3 kg (M3 is a rotor, and the seats are listed M4, M5, ..., M7).
// - k07 = 1e8 N/m, c07 = 1e3 N s/m: the housing-to-ground link is given the same values as the
//   housing-internal links k47/c47 (a bolted foundation as stiff as the housing itself); it
//   puts the housing's bounce mode (29.5 kg) near 300 Hz, inside the 1-4000 Hz band.
// - No shaft mass (no shaft length in the table), no torsional couplings.
GearboxParameters Table1Parameters();

// Static mechanics of one rotor (all its gears plus the optional shaft).
struct RotorProperties {
  double mass_kg = 0.0;
  double inertia_kg_m2 = 0.0;
};

struct MeshProperties {
  double base_radius_driver_m = 0.0;
  double base_radius_driven_m = 0.0;
  double contact_ratio = 0.0;  // transverse contact ratio eps_alpha
  double stiffness_n_per_m = 0.0;
  double equivalent_mass_kg = 0.0;
  double damping_ns_per_m = 0.0;
};

// Response to a harmonic generalized force at one frequency.
struct ForcedResponse {
  Eigen::VectorXcd acceleration;   // all DOFs, m/s^2 (rad/s^2 for rotations)
  Eigen::VectorXcd bearing_force;  // N + 1, force of bearing i on seat i, N (seed Eq. 44)
};

// Transfer from mesh transmission error (one column per stage, m) to the housing, on a grid.
struct TransmissionErrorTransfer {
  FrfMatrix seat_acceleration;     // (N + 1) x N, m/s^2 per m of TE
  FrfMatrix housing_acceleration;  // 1 x N
  FrfMatrix bearing_force;         // (N + 1) x N, N per m of TE
};

class LumpedGearboxModel {
 public:
  // Validates the parameters (messages name the field and why) and assembles M, C, K.
  static Result<LumpedGearboxModel> Create(const GearboxParameters& parameters);

  const GearboxParameters& parameters() const { return parameters_; }
  int stage_count() const { return static_cast<int>(parameters_.stages.size()); }
  int rotor_count() const { return stage_count() + 1; }
  Eigen::Index dof_count() const { return mass_.rows(); }
  Eigen::Index housing_dof_count() const { return housing_mass_.rows(); }

  // DOF indices in the coupled q (see the file comment).
  Eigen::Index RotorTranslationDof(int rotor) const { return 2 * rotor; }
  Eigen::Index RotorRotationDof(int rotor) const { return 2 * rotor + 1; }
  Eigen::Index SeatDof(int seat) const { return 2 * rotor_count() + seat; }
  Eigen::Index HousingDof() const { return 3 * rotor_count(); }
  // Roles for virtual decoupling: a = rotor translations, p = seats, m = central housing mass.
  std::vector<Eigen::Index> ActiveDofs() const;
  std::vector<Eigen::Index> PassiveDofs() const;
  std::vector<Eigen::Index> MeasurementDofs() const;

  const std::vector<RotorProperties>& rotors() const { return rotors_; }
  const std::vector<MeshProperties>& meshes() const { return meshes_; }
  // v_s: mesh deflection d_s = v_s^T q of stage s.
  const Eigen::VectorXd& MeshVector(int stage) const { return mesh_vectors_[stage]; }

  // Coupled system (seed Eqs. 3-5, time-averaged).
  const Eigen::MatrixXd& mass() const { return mass_; }
  const Eigen::MatrixXd& damping() const { return damping_; }
  const Eigen::MatrixXd& stiffness() const { return stiffness_; }
  // Housing alone, physically decoupled (seed Eq. 7): q_h = [s_0, ..., s_N, h].
  const Eigen::MatrixXd& housing_mass() const { return housing_mass_; }
  const Eigen::MatrixXd& housing_damping() const { return housing_damping_; }
  const Eigen::MatrixXd& housing_stiffness() const { return housing_stiffness_; }

  // Undamped natural frequencies of the coupled model (K phi = w^2 M phi), ascending, Hz;
  // rigid-body modes (the free gear-train rotation) appear as 0.
  const Eigen::VectorXd& NaturalFrequenciesHz() const { return natural_frequencies_hz_; }

  // Coupled accelerance H = w^2 (-w^2 M + j w C + K)^-1 (seed Eq. 6), dof_count() square.
  // At 0 Hz the w -> 0 limit is returned (non-zero only along rigid-body modes). Frequencies
  // must be finite and >= 0; grids also strictly increasing.
  Result<Eigen::MatrixXcd> Accelerance(double frequency_hz) const;
  Result<FrfMatrix> Accelerance(const Eigen::VectorXd& frequency_hz) const;
  // Housing-alone accelerance (seed Eq. 7), housing_dof_count() square, q_h order.
  Result<Eigen::MatrixXcd> HousingAccelerance(double frequency_hz) const;
  Result<FrfMatrix> HousingAccelerance(const Eigen::VectorXd& frequency_hz) const;

  // The coupled FRF split by role (a, p, m as above) on a grid: the input of virtual
  // decoupling. include_ap = false leaves `ap` empty (as when only H_pa was measured).
  Result<CoupledBlocks> CoupledBlocksOnGrid(const Eigen::VectorXd& frequency_hz,
                                            bool include_ap = true) const;
  // Physically decoupled references: H_d,pp = seats x seats and H_d,mp = housing x seats of
  // the housing-alone accelerance.
  Result<FrfMatrix> PhysicalDecoupledPp(const Eigen::VectorXd& frequency_hz) const;
  Result<FrfMatrix> PhysicalDecoupledMp(const Eigen::VectorXd& frequency_hz) const;

  // Generalized force of a harmonic static transmission error e (one complex amplitude per
  // stage, m): sum_s (k_s + j w c_s) e_s v_s.
  Result<Eigen::VectorXcd> MeshForce(double frequency_hz,
                                     const Eigen::VectorXcd& transmission_error) const;
  // Steady-state response to a harmonic generalized force (dof_count() entries, N or N m).
  // At 0 Hz: static response (the load must not excite a rigid-body mode), accelerations 0.
  Result<ForcedResponse> Respond(double frequency_hz,
                                 const Eigen::VectorXcd& generalized_force) const;
  Result<ForcedResponse> RespondToTransmissionError(
      double frequency_hz, const Eigen::VectorXcd& transmission_error) const;
  // Transfer from TE to seat and housing accelerations and bearing forces on a grid; column s
  // is the response to a unit TE of stage s. Multiply by a TE spectrum and inverse-FFT to
  // synthesize signals.
  Result<TransmissionErrorTransfer> TransmissionErrorTransferOnGrid(
      const Eigen::VectorXd& frequency_hz) const;

 private:
  LumpedGearboxModel() = default;
  void Assemble();
  void ComputeModes();
  // K - w^2 M + j w C.
  Eigen::MatrixXcd DynamicStiffness(double omega) const;
  // Receptance (dof_count() square) of the coupled system; at w = 0 the static flexibility on
  // the elastic subspace (pseudo-inverse of K in the mass metric).
  Eigen::MatrixXcd Receptance(double omega) const;
  Eigen::MatrixXcd CoupledAccelerance(double omega) const;
  Eigen::MatrixXcd HousingAcceleranceAt(double omega) const;
  ForcedResponse RespondAt(double omega, const Eigen::VectorXcd& generalized_force) const;
  Eigen::VectorXcd MeshForceAt(double omega, const Eigen::VectorXcd& transmission_error) const;

  GearboxParameters parameters_;
  std::vector<RotorProperties> rotors_;
  std::vector<MeshProperties> meshes_;
  std::vector<Eigen::VectorXd> mesh_vectors_;
  Eigen::MatrixXd mass_, damping_, stiffness_;
  Eigen::MatrixXd housing_mass_, housing_damping_, housing_stiffness_;
  Eigen::VectorXd natural_frequencies_hz_;
  Eigen::MatrixXd rigid_modes_;         // mass-normalised rigid-body modes (columns)
  Eigen::MatrixXd static_flexibility_;  // sum over elastic modes of phi phi^T / w_n^2
};

}  // namespace gearpath
