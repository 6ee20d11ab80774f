#include "core/model/lumped_gearbox_model.h"

#include <fmt/format.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <numbers>
#include <string>

namespace gearpath {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;
// Eigenvalues below this fraction of the largest one are rigid-body modes: a free mode comes
// out of the solver at ~eps * lambda_max, a physical one of this model is orders above 1e-10.
constexpr double kRigidModeTolerance = 1e-10;

bool IsFinite(double v) { return std::isfinite(v); }

Status CheckPerRotor(const std::vector<double>& values, int rotors, const char* field,
                     bool strictly_positive) {
  if (static_cast<int>(values.size()) != rotors) {
    return Error{
        fmt::format("gearbox parameters: {} has {} entries, expected {} (one per rotor "
                    "= stages + 1)",
                    field, values.size(), rotors)};
  }
  for (std::size_t i = 0; i < values.size(); ++i) {
    const double v = values[i];
    if (!IsFinite(v) || v < 0.0 || (strictly_positive && v == 0.0)) {
      return Error{fmt::format("gearbox parameters: {}[{}] = {} must be finite and {}", field, i, v,
                               strictly_positive ? "> 0" : ">= 0")};
    }
  }
  return Status::Ok();
}

Status CheckScalar(double v, const char* field, bool strictly_positive) {
  if (!IsFinite(v) || v < 0.0 || (strictly_positive && v == 0.0)) {
    return Error{fmt::format("gearbox parameters: {} = {} must be finite and {}", field, v,
                             strictly_positive ? "> 0" : ">= 0")};
  }
  return Status::Ok();
}

Status ValidateParameters(const GearboxParameters& p) {
  if (p.stages.empty()) {
    return Error{"gearbox parameters: stages is empty, need at least one gear stage"};
  }
  const int rotors = static_cast<int>(p.stages.size()) + 1;
  for (std::size_t s = 0; s < p.stages.size(); ++s) {
    const GearStage& st = p.stages[s];
    if (st.z_driver < 1 || st.z_driven < 1) {
      return Error{fmt::format("gearbox parameters: stages[{}] tooth counts ({}, {}) must be >= 1",
                               s, st.z_driver, st.z_driven)};
    }
    if (st.mesh_stiffness_n_per_m &&
        (!IsFinite(*st.mesh_stiffness_n_per_m) || *st.mesh_stiffness_n_per_m <= 0.0)) {
      return Error{fmt::format(
          "gearbox parameters: stages[{}].mesh_stiffness_n_per_m = {} must be finite and > 0", s,
          *st.mesh_stiffness_n_per_m)};
    }
  }
  struct PerRotor {
    const std::vector<double>* values;
    const char* field;
    bool positive;
  };
  const PerRotor per_rotor[] = {
      {&p.bearing_stiffness_n_per_m, "bearing_stiffness_n_per_m", true},
      {&p.bearing_damping_ns_per_m, "bearing_damping_ns_per_m", false},
      {&p.seat_mass_kg, "seat_mass_kg", true},
      {&p.seat_stiffness_n_per_m, "seat_stiffness_n_per_m", true},
      {&p.seat_damping_ns_per_m, "seat_damping_ns_per_m", false},
  };
  for (const PerRotor& r : per_rotor) {
    if (Status s = CheckPerRotor(*r.values, rotors, r.field, r.positive); !s) return s;
  }
  if (!p.torsional_stiffness_nm_per_rad.empty()) {
    if (Status s = CheckPerRotor(p.torsional_stiffness_nm_per_rad, rotors,
                                 "torsional_stiffness_nm_per_rad", false);
        !s) {
      return s;
    }
  }
  struct Scalar {
    double value;
    const char* field;
    bool positive;
  };
  const Scalar scalars[] = {
      {p.housing_mass_kg, "housing_mass_kg", true},
      // > 0: the housing must be held, so the only possible rigid-body mode is the free
      // (undamped) gear-train rotation and the 0 Hz limits below are exact.
      {p.ground_stiffness_n_per_m, "ground_stiffness_n_per_m", true},
      {p.ground_damping_ns_per_m, "ground_damping_ns_per_m", false},
      {p.module_m, "module_m", true},
      {p.face_width_m, "face_width_m", true},
      {p.addendum_coefficient, "addendum_coefficient", true},
      {p.density_kg_per_m3, "density_kg_per_m3", true},
      {p.shaft_radius_m, "shaft_radius_m", false},
      {p.shaft_length_m, "shaft_length_m", false},
      {p.mesh_damping_ratio, "mesh_damping_ratio", false},
      {p.single_tooth_stiffness_n_per_m2, "single_tooth_stiffness_n_per_m2", true},
  };
  for (const Scalar& s : scalars) {
    if (Status st = CheckScalar(s.value, s.field, s.positive); !st) return st;
  }
  if (!IsFinite(p.pressure_angle_deg) || p.pressure_angle_deg <= 0.0 ||
      p.pressure_angle_deg >= 45.0) {
    return Error{fmt::format("gearbox parameters: pressure_angle_deg = {} must be in (0, 45)",
                             p.pressure_angle_deg)};
  }
  return Status::Ok();
}

Status ValidateGrid(const Eigen::VectorXd& f) {
  if (f.size() == 0) return Error{"frequency grid is empty"};
  for (Eigen::Index k = 0; k < f.size(); ++k) {
    if (!IsFinite(f[k]) || f[k] < 0.0) {
      return Error{
          fmt::format("frequency grid: bin {} is {} Hz, must be finite and >= 0", k, f[k])};
    }
    if (k > 0 && !(f[k] > f[k - 1])) {
      return Error{fmt::format(
          "frequency grid: bin {} ({} Hz) does not exceed bin {} ({} Hz), must strictly increase",
          k, f[k], k - 1, f[k - 1])};
    }
  }
  return Status::Ok();
}

Status ValidateFrequency(double f) {
  if (!IsFinite(f) || f < 0.0) {
    return Error{fmt::format("frequency {} Hz must be finite and >= 0", f)};
  }
  return Status::Ok();
}

struct Disc {
  double mass;
  double inertia;
};

// Solid disc of radius r and thickness b.
Disc SolidDisc(double rho, double r, double b) {
  const double m = rho * std::numbers::pi * r * r * b;
  return {m, 0.5 * m * r * r};
}

// Slices an (n x n) matrix by index lists.
Eigen::MatrixXcd Block(const Eigen::MatrixXcd& h, const std::vector<Eigen::Index>& rows,
                       const std::vector<Eigen::Index>& cols) {
  return h(rows, cols);
}

}  // namespace

GearboxParameters Table1Parameters() {
  GearboxParameters p;
  p.stages = {GearStage{28, 40, std::nullopt}, GearStage{34, 34, std::nullopt}};
  p.bearing_stiffness_n_per_m = {1e7, 1e7, 1e7};  // k14, k25, k36
  p.bearing_damping_ns_per_m = {1e4, 1e4, 1e4};   // c14, c25, c36
  p.seat_mass_kg = {1.0, 2.0, 3.0};               // M4, M5, M6 (table: "M3 = 3")
  p.seat_stiffness_n_per_m = {1e8, 1e8, 1e8};     // k47, k57, k67
  p.seat_damping_ns_per_m = {1e3, 1e3, 1e3};      // c47, c57, c67
  p.housing_mass_kg = 23.5;                       // M7
  p.ground_stiffness_n_per_m = 1e8;               // k07: not in Table 1, see header
  p.ground_damping_ns_per_m = 1e3;                // c07: not in Table 1, see header
  p.module_m = 3e-3;
  p.face_width_m = 16e-3;
  p.pressure_angle_deg = 20.0;
  p.addendum_coefficient = 1.0;
  p.density_kg_per_m3 = 7850.0;
  p.shaft_radius_m = 24e-3;
  p.shaft_length_m = 0.0;
  p.mesh_damping_ratio = 0.02;
  return p;
}

Result<LumpedGearboxModel> LumpedGearboxModel::Create(const GearboxParameters& parameters) {
  if (Status s = ValidateParameters(parameters); !s) return Error{s.error()};
  LumpedGearboxModel model;
  model.parameters_ = parameters;
  model.Assemble();
  for (std::size_t s = 0; s < model.meshes_.size(); ++s) {
    const MeshProperties& mesh = model.meshes_[s];
    if (!(mesh.contact_ratio > 0.0) || !IsFinite(mesh.contact_ratio)) {
      return Error{fmt::format(
          "gearbox parameters: stages[{}] ({} / {} teeth) has no contact (contact ratio {}): "
          "check tooth counts, addendum coefficient and pressure angle",
          s, parameters.stages[s].z_driver, parameters.stages[s].z_driven, mesh.contact_ratio)};
    }
  }
  model.ComputeModes();
  return model;
}

void LumpedGearboxModel::Assemble() {
  const GearboxParameters& p = parameters_;
  const int n_stages = stage_count();
  const int n_rotors = rotor_count();
  const Eigen::Index n = 3 * n_rotors + 1;
  const double alpha = p.pressure_angle_deg * std::numbers::pi / 180.0;
  const double cos_alpha = std::cos(alpha);

  // Rotor masses and inertias: all gears on the rotor plus the optional shaft.
  rotors_.assign(n_rotors, RotorProperties{});
  auto add_gear = [&](int rotor, int teeth) {
    const Disc d = SolidDisc(p.density_kg_per_m3, 0.5 * p.module_m * teeth, p.face_width_m);
    rotors_[rotor].mass_kg += d.mass;
    rotors_[rotor].inertia_kg_m2 += d.inertia;
  };
  for (int s = 0; s < n_stages; ++s) {
    add_gear(s, p.stages[s].z_driver);
    add_gear(s + 1, p.stages[s].z_driven);
  }
  if (p.shaft_length_m > 0.0 && p.shaft_radius_m > 0.0) {
    const Disc shaft = SolidDisc(p.density_kg_per_m3, p.shaft_radius_m, p.shaft_length_m);
    for (RotorProperties& r : rotors_) {
      r.mass_kg += shaft.mass;
      r.inertia_kg_m2 += shaft.inertia;
    }
  }

  // Meshes: ISO 6336-1 mean mesh stiffness, damping from the ratio and the equivalent mass.
  meshes_.assign(n_stages, MeshProperties{});
  mesh_vectors_.assign(n_stages, Eigen::VectorXd::Zero(n));
  for (int s = 0; s < n_stages; ++s) {
    MeshProperties& mesh = meshes_[s];
    const double r1 = 0.5 * p.module_m * p.stages[s].z_driver;
    const double r2 = 0.5 * p.module_m * p.stages[s].z_driven;
    const double rb1 = r1 * cos_alpha;
    const double rb2 = r2 * cos_alpha;
    const double ra1 = r1 + p.addendum_coefficient * p.module_m;
    const double ra2 = r2 + p.addendum_coefficient * p.module_m;
    mesh.base_radius_driver_m = rb1;
    mesh.base_radius_driven_m = rb2;
    // Length of the path of contact over the base pitch (standard centre distance r1 + r2).
    mesh.contact_ratio = (std::sqrt(ra1 * ra1 - rb1 * rb1) + std::sqrt(ra2 * ra2 - rb2 * rb2) -
                          (r1 + r2) * std::sin(alpha)) /
                         (std::numbers::pi * p.module_m * cos_alpha);
    mesh.stiffness_n_per_m = p.stages[s].mesh_stiffness_n_per_m.value_or(
        p.single_tooth_stiffness_n_per_m2 * (0.75 * mesh.contact_ratio + 0.25) * p.face_width_m);
    const double m1 = rotors_[s].inertia_kg_m2 / (rb1 * rb1);
    const double m2 = rotors_[s + 1].inertia_kg_m2 / (rb2 * rb2);
    mesh.equivalent_mass_kg = m1 * m2 / (m1 + m2);
    mesh.damping_ns_per_m =
        2.0 * p.mesh_damping_ratio * std::sqrt(mesh.stiffness_n_per_m * mesh.equivalent_mass_kg);

    Eigen::VectorXd& v = mesh_vectors_[s];
    v[RotorTranslationDof(s)] = 1.0;
    v[RotorRotationDof(s)] = rb1;
    v[RotorTranslationDof(s + 1)] = -1.0;
    v[RotorRotationDof(s + 1)] = rb2;
  }

  mass_ = Eigen::MatrixXd::Zero(n, n);
  damping_ = Eigen::MatrixXd::Zero(n, n);
  stiffness_ = Eigen::MatrixXd::Zero(n, n);
  // A spring-damper between DOFs i and j (j < 0: ground).
  auto link = [&](Eigen::MatrixXd& m, Eigen::Index i, Eigen::Index j, double value) {
    m(i, i) += value;
    if (j >= 0) {
      m(j, j) += value;
      m(i, j) -= value;
      m(j, i) -= value;
    }
  };
  for (int r = 0; r < n_rotors; ++r) {
    mass_(RotorTranslationDof(r), RotorTranslationDof(r)) = rotors_[r].mass_kg;
    mass_(RotorRotationDof(r), RotorRotationDof(r)) = rotors_[r].inertia_kg_m2;
    mass_(SeatDof(r), SeatDof(r)) = p.seat_mass_kg[r];
    link(stiffness_, RotorTranslationDof(r), SeatDof(r), p.bearing_stiffness_n_per_m[r]);
    link(damping_, RotorTranslationDof(r), SeatDof(r), p.bearing_damping_ns_per_m[r]);
    link(stiffness_, SeatDof(r), HousingDof(), p.seat_stiffness_n_per_m[r]);
    link(damping_, SeatDof(r), HousingDof(), p.seat_damping_ns_per_m[r]);
    if (!p.torsional_stiffness_nm_per_rad.empty()) {
      link(stiffness_, RotorRotationDof(r), -1, p.torsional_stiffness_nm_per_rad[r]);
    }
  }
  mass_(HousingDof(), HousingDof()) = p.housing_mass_kg;
  link(stiffness_, HousingDof(), -1, p.ground_stiffness_n_per_m);
  link(damping_, HousingDof(), -1, p.ground_damping_ns_per_m);
  for (int s = 0; s < n_stages; ++s) {
    const Eigen::VectorXd& v = mesh_vectors_[s];
    stiffness_ += meshes_[s].stiffness_n_per_m * v * v.transpose();
    damping_ += meshes_[s].damping_ns_per_m * v * v.transpose();
  }

  // Housing alone (seed Eq. 7): the seat/housing/ground block of the coupled matrices without
  // the bearing links, i.e. the housing DOFs' rows and columns minus the bearing terms.
  const Eigen::Index first = SeatDof(0);
  const Eigen::Index nh = n - first;
  housing_mass_ = mass_.bottomRightCorner(nh, nh);
  housing_stiffness_ = stiffness_.bottomRightCorner(nh, nh);
  housing_damping_ = damping_.bottomRightCorner(nh, nh);
  for (int r = 0; r < n_rotors; ++r) {
    housing_stiffness_(r, r) -= p.bearing_stiffness_n_per_m[r];
    housing_damping_(r, r) -= p.bearing_damping_ns_per_m[r];
  }
}

void LumpedGearboxModel::ComputeModes() {
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eig(stiffness_, mass_);
  const Eigen::VectorXd& lambda = eig.eigenvalues();
  const Eigen::MatrixXd& phi = eig.eigenvectors();  // mass-normalised: phi^T M phi = I
  const Eigen::Index n = lambda.size();
  const double threshold = kRigidModeTolerance * lambda.cwiseAbs().maxCoeff();
  natural_frequencies_hz_.resize(n);
  static_flexibility_ = Eigen::MatrixXd::Zero(n, n);
  std::vector<Eigen::Index> rigid;
  for (Eigen::Index k = 0; k < n; ++k) {
    if (lambda[k] <= threshold) {
      natural_frequencies_hz_[k] = 0.0;
      rigid.push_back(k);
    } else {
      natural_frequencies_hz_[k] = std::sqrt(lambda[k]) / kTwoPi;
      static_flexibility_ += phi.col(k) * phi.col(k).transpose() / lambda[k];
    }
  }
  rigid_modes_ = phi(Eigen::all, rigid);
}

std::vector<Eigen::Index> LumpedGearboxModel::ActiveDofs() const {
  std::vector<Eigen::Index> dofs;
  for (int r = 0; r < rotor_count(); ++r) dofs.push_back(RotorTranslationDof(r));
  return dofs;
}

std::vector<Eigen::Index> LumpedGearboxModel::PassiveDofs() const {
  std::vector<Eigen::Index> dofs;
  for (int r = 0; r < rotor_count(); ++r) dofs.push_back(SeatDof(r));
  return dofs;
}

std::vector<Eigen::Index> LumpedGearboxModel::MeasurementDofs() const { return {HousingDof()}; }

Eigen::MatrixXcd LumpedGearboxModel::DynamicStiffness(double omega) const {
  return stiffness_.cast<Complex>() - omega * omega * mass_.cast<Complex>() +
         Complex(0.0, omega) * damping_.cast<Complex>();
}

Eigen::MatrixXcd LumpedGearboxModel::Receptance(double omega) const {
  if (omega == 0.0) return static_flexibility_.cast<Complex>();
  const Eigen::MatrixXcd z = DynamicStiffness(omega);
  return z.partialPivLu().solve(Eigen::MatrixXcd::Identity(z.rows(), z.cols()));
}

Eigen::MatrixXcd LumpedGearboxModel::CoupledAccelerance(double omega) const {
  // Physical accelerance a / f = -w^2 X / f (see the header on the seed's Eq. 6 sign).
  // w -> 0: -w^2 sum phi phi^T / (w_n^2 - w^2) -> +sum over rigid modes of phi phi^T (they are
  // undamped: only mesh dampers touch the rotations and a rigid rotation does not stretch them).
  if (omega == 0.0) return (rigid_modes_ * rigid_modes_.transpose()).cast<Complex>();
  return -omega * omega * Receptance(omega);
}

Eigen::MatrixXcd LumpedGearboxModel::HousingAcceleranceAt(double omega) const {
  // The housing is grounded (k07 > 0), so its accelerance vanishes at 0 Hz.
  const Eigen::Index n = housing_mass_.rows();
  if (omega == 0.0) return Eigen::MatrixXcd::Zero(n, n);
  const Eigen::MatrixXcd z = housing_stiffness_.cast<Complex>() -
                             omega * omega * housing_mass_.cast<Complex>() +
                             Complex(0.0, omega) * housing_damping_.cast<Complex>();
  return -omega * omega * z.partialPivLu().solve(Eigen::MatrixXcd::Identity(n, n));
}

Result<Eigen::MatrixXcd> LumpedGearboxModel::Accelerance(double frequency_hz) const {
  if (Status s = ValidateFrequency(frequency_hz); !s) return Error{"accelerance: " + s.error()};
  return CoupledAccelerance(kTwoPi * frequency_hz);
}

Result<FrfMatrix> LumpedGearboxModel::Accelerance(const Eigen::VectorXd& frequency_hz) const {
  if (Status s = ValidateGrid(frequency_hz); !s) return Error{"accelerance: " + s.error()};
  FrfMatrix frf{frequency_hz, {}};
  frf.at.reserve(frequency_hz.size());
  for (Eigen::Index k = 0; k < frequency_hz.size(); ++k) {
    frf.at.push_back(CoupledAccelerance(kTwoPi * frequency_hz[k]));
  }
  return frf;
}

Result<Eigen::MatrixXcd> LumpedGearboxModel::HousingAccelerance(double frequency_hz) const {
  if (Status s = ValidateFrequency(frequency_hz); !s) {
    return Error{"housing accelerance: " + s.error()};
  }
  return HousingAcceleranceAt(kTwoPi * frequency_hz);
}

Result<FrfMatrix> LumpedGearboxModel::HousingAccelerance(
    const Eigen::VectorXd& frequency_hz) const {
  if (Status s = ValidateGrid(frequency_hz); !s) return Error{"housing accelerance: " + s.error()};
  FrfMatrix frf{frequency_hz, {}};
  frf.at.reserve(frequency_hz.size());
  for (Eigen::Index k = 0; k < frequency_hz.size(); ++k) {
    frf.at.push_back(HousingAcceleranceAt(kTwoPi * frequency_hz[k]));
  }
  return frf;
}

Result<CoupledBlocks> LumpedGearboxModel::CoupledBlocksOnGrid(const Eigen::VectorXd& frequency_hz,
                                                              bool include_ap) const {
  if (Status s = ValidateGrid(frequency_hz); !s) return Error{"coupled blocks: " + s.error()};
  const std::vector<Eigen::Index> a = ActiveDofs();
  const std::vector<Eigen::Index> p = PassiveDofs();
  const std::vector<Eigen::Index> m = MeasurementDofs();
  CoupledBlocks blocks;
  blocks.frequency_hz = frequency_hz;
  for (Eigen::Index k = 0; k < frequency_hz.size(); ++k) {
    const Eigen::MatrixXcd h = CoupledAccelerance(kTwoPi * frequency_hz[k]);
    blocks.aa.push_back(Block(h, a, a));
    blocks.pa.push_back(Block(h, p, a));
    blocks.pp.push_back(Block(h, p, p));
    if (include_ap) blocks.ap.push_back(Block(h, a, p));
    blocks.ma.push_back(Block(h, m, a));
    blocks.mp.push_back(Block(h, m, p));
  }
  return blocks;
}

Result<FrfMatrix> LumpedGearboxModel::PhysicalDecoupledPp(
    const Eigen::VectorXd& frequency_hz) const {
  Result<FrfMatrix> housing = HousingAccelerance(frequency_hz);
  if (!housing) return housing;
  const Eigen::Index seats = rotor_count();
  for (Eigen::MatrixXcd& h : housing->at) h = h.topLeftCorner(seats, seats).eval();
  return housing;
}

Result<FrfMatrix> LumpedGearboxModel::PhysicalDecoupledMp(
    const Eigen::VectorXd& frequency_hz) const {
  Result<FrfMatrix> housing = HousingAccelerance(frequency_hz);
  if (!housing) return housing;
  const Eigen::Index seats = rotor_count();
  for (Eigen::MatrixXcd& h : housing->at) h = h.bottomLeftCorner(1, seats).eval();
  return housing;
}

Eigen::VectorXcd LumpedGearboxModel::MeshForceAt(double omega,
                                                 const Eigen::VectorXcd& transmission_error) const {
  Eigen::VectorXcd f = Eigen::VectorXcd::Zero(dof_count());
  for (int s = 0; s < stage_count(); ++s) {
    const Complex mesh_impedance(meshes_[s].stiffness_n_per_m, omega * meshes_[s].damping_ns_per_m);
    f += (mesh_impedance * transmission_error[s]) * mesh_vectors_[s].cast<Complex>();
  }
  return f;
}

Result<Eigen::VectorXcd> LumpedGearboxModel::MeshForce(
    double frequency_hz, const Eigen::VectorXcd& transmission_error) const {
  if (Status s = ValidateFrequency(frequency_hz); !s) return Error{"mesh force: " + s.error()};
  if (transmission_error.size() != stage_count()) {
    return Error{
        fmt::format("mesh force: transmission_error has {} entries, expected {} (one "
                    "per stage)",
                    transmission_error.size(), stage_count())};
  }
  return MeshForceAt(kTwoPi * frequency_hz, transmission_error);
}

ForcedResponse LumpedGearboxModel::RespondAt(double omega,
                                             const Eigen::VectorXcd& generalized_force) const {
  Eigen::VectorXcd x;
  if (omega == 0.0) {
    x = static_flexibility_.cast<Complex>() * generalized_force;
  } else {
    x = DynamicStiffness(omega).partialPivLu().solve(generalized_force);
  }
  ForcedResponse response;
  response.acceleration = -omega * omega * x;
  response.bearing_force.resize(rotor_count());
  for (int r = 0; r < rotor_count(); ++r) {
    const Complex link(parameters_.bearing_stiffness_n_per_m[r],
                       omega * parameters_.bearing_damping_ns_per_m[r]);
    response.bearing_force[r] = link * (x[RotorTranslationDof(r)] - x[SeatDof(r)]);
  }
  return response;
}

Result<ForcedResponse> LumpedGearboxModel::Respond(
    double frequency_hz, const Eigen::VectorXcd& generalized_force) const {
  if (Status s = ValidateFrequency(frequency_hz); !s) return Error{"forced response: " + s.error()};
  if (generalized_force.size() != dof_count()) {
    return Error{fmt::format("forced response: generalized_force has {} entries, expected {}",
                             generalized_force.size(), dof_count())};
  }
  if (frequency_hz == 0.0 && rigid_modes_.cols() > 0) {
    // A static load with a component along a free mode (a net torque on the free gear train)
    // has no static equilibrium.
    // Phi is mass-normalised, so |Phi^T f| <= |M^-1/2 f|: compare the two.
    const Eigen::VectorXcd modal = rigid_modes_.transpose().cast<Complex>() * generalized_force;
    const Eigen::VectorXcd scaled =
        mass_.diagonal().cwiseSqrt().cwiseInverse().cast<Complex>().cwiseProduct(generalized_force);
    const double along_rigid = modal.norm();
    const double scale = scaled.norm();
    if (along_rigid > 1e-9 * scale) {
      return Error{
          "forced response: the static (0 Hz) load drives the free rotation of the gear "
          "train (a net torque nothing reacts), so it has no static equilibrium"};
    }
  }
  return RespondAt(kTwoPi * frequency_hz, generalized_force);
}

Result<ForcedResponse> LumpedGearboxModel::RespondToTransmissionError(
    double frequency_hz, const Eigen::VectorXcd& transmission_error) const {
  Result<Eigen::VectorXcd> force = MeshForce(frequency_hz, transmission_error);
  if (!force) return Error{force.error()};
  // A mesh load is orthogonal to every rigid mode (a rigid mode does not deflect the mesh).
  return RespondAt(kTwoPi * frequency_hz, *force);
}

Result<TransmissionErrorTransfer> LumpedGearboxModel::TransmissionErrorTransferOnGrid(
    const Eigen::VectorXd& frequency_hz) const {
  if (Status s = ValidateGrid(frequency_hz); !s) {
    return Error{"transmission error transfer: " + s.error()};
  }
  const int n_stages = stage_count();
  const int n_rotors = rotor_count();
  TransmissionErrorTransfer t;
  t.seat_acceleration.frequency_hz = frequency_hz;
  t.housing_acceleration.frequency_hz = frequency_hz;
  t.bearing_force.frequency_hz = frequency_hz;
  for (Eigen::Index k = 0; k < frequency_hz.size(); ++k) {
    const double omega = kTwoPi * frequency_hz[k];
    // One factorisation per bin, one right-hand side per stage.
    Eigen::MatrixXcd forces(dof_count(), n_stages);
    for (int s = 0; s < n_stages; ++s) {
      Eigen::VectorXcd unit = Eigen::VectorXcd::Zero(n_stages);
      unit[s] = 1.0;
      forces.col(s) = MeshForceAt(omega, unit);
    }
    const Eigen::MatrixXcd x =
        omega == 0.0 ? Eigen::MatrixXcd(static_flexibility_.cast<Complex>() * forces)
                     : Eigen::MatrixXcd(DynamicStiffness(omega).partialPivLu().solve(forces));
    Eigen::MatrixXcd seat(n_rotors, n_stages);
    Eigen::MatrixXcd bearing(n_rotors, n_stages);
    for (int i = 0; i < n_rotors; ++i) {
      seat.row(i) = -omega * omega * x.row(SeatDof(i));
      const Complex link(parameters_.bearing_stiffness_n_per_m[i],
                         omega * parameters_.bearing_damping_ns_per_m[i]);
      bearing.row(i) = link * (x.row(RotorTranslationDof(i)) - x.row(SeatDof(i)));
    }
    Eigen::MatrixXcd housing = -omega * omega * x.row(HousingDof());
    t.seat_acceleration.at.push_back(std::move(seat));
    t.housing_acceleration.at.push_back(std::move(housing));
    t.bearing_force.at.push_back(std::move(bearing));
  }
  return t;
}

}  // namespace gearpath
