#include "core/evaluation/gearbox_integrator.h"

#include <cmath>

namespace gearpath {
namespace {

constexpr int kMaxContactIterations = 6;

// Solves m x = b in place (b becomes x) for a small dense row-major n x n m, Gaussian
// elimination with partial pivoting; m is overwritten. No allocation.
void SolveSmall(double* m, double* b, int n) noexcept {
  for (int c = 0; c < n; ++c) {
    int pivot = c;
    for (int r = c + 1; r < n; ++r) {
      if (std::abs(m[r * n + c]) > std::abs(m[pivot * n + c])) pivot = r;
    }
    if (pivot != c) {
      for (int k = 0; k < n; ++k) std::swap(m[c * n + k], m[pivot * n + k]);
      std::swap(b[c], b[pivot]);
    }
    for (int r = c + 1; r < n; ++r) {
      const double f = m[r * n + c] / m[c * n + c];
      for (int k = c; k < n; ++k) m[r * n + k] -= f * m[c * n + k];
      b[r] -= f * b[c];
    }
  }
  for (int c = n - 1; c >= 0; --c) {
    double sum = b[c];
    for (int k = c + 1; k < n; ++k) sum -= m[c * n + k] * b[k];
    b[c] = sum / m[c * n + c];
  }
}

std::vector<double> RowMajor(const Eigen::MatrixXd& m) {
  std::vector<double> out(static_cast<std::size_t>(m.size()));
  for (Eigen::Index r = 0; r < m.rows(); ++r) {
    for (Eigen::Index c = 0; c < m.cols(); ++c) {
      out[static_cast<std::size_t>(r * m.cols() + c)] = m(r, c);
    }
  }
  return out;
}

}  // namespace

GearboxIntegrator::GearboxIntegrator(const ParametricGearbox& gearbox, double step_s,
                                     std::vector<int> output_points)
    : gearbox_(&gearbox), h_(step_s) {
  a0_ = 4.0 / (h_ * h_);
  a1_ = 2.0 / h_;
  a2_ = 4.0 / h_;
  ns_ = gearbox.shaft_count();
  nr_ = gearbox.rotor_dofs();
  nm_ = gearbox.plate().mode_count();
  stages_ = gearbox.stage_count();
  no_ = static_cast<int>(output_points.size());
  const ParametricGearboxParameters& p = gearbox.parameters();
  const PlateHousing& plate = gearbox.plate();

  Eigen::VectorXd mass_r(nr_), kb(ns_);
  bearing_c_.resize(static_cast<std::size_t>(ns_));
  for (int i = 0; i < ns_; ++i) {
    const ShaftRotor& r = p.shafts[static_cast<std::size_t>(i)];
    mass_r[gearbox.RotationDof(i)] = r.inertia_kg_m2;
    mass_r[gearbox.LateralDof(i)] = r.mass_kg;
    bearing_c_[static_cast<std::size_t>(i)] = r.bearing_damping_ns_per_m;
    kb[i] = r.bearing_stiffness_n_per_m + a1_ * r.bearing_damping_ns_per_m;
  }
  mass_r_.assign(mass_r.data(), mass_r.data() + nr_);
  // The meshes (stiffness and damping) stay out of the damping and A_0: their contact changes.
  Eigen::MatrixXd damp_r = Eigen::MatrixXd::Zero(nr_, nr_);
  Eigen::MatrixXd stiff_r = Eigen::MatrixXd::Zero(nr_, nr_);
  damp_r(0, 0) += p.motor_damping_nms_per_rad;
  stiff_r(0, 0) += p.motor_stiffness_nm_per_rad;
  damp_r(ns_ - 1, ns_ - 1) += p.load_damping_nms_per_rad;
  damp_r_ = RowMajor(damp_r);
  Eigen::MatrixXd mesh_v(nr_, stages_);
  for (int s = 0; s < stages_; ++s) {
    mesh_v.col(s) = gearbox.MeshVector(s);
    mesh_c_.push_back(p.stages[static_cast<std::size_t>(s)].damping_ns_per_m);
  }
  mesh_v_ = RowMajor(mesh_v.transpose());

  Eigen::VectorXd inv_d(nm_);
  plate_c_.resize(static_cast<std::size_t>(nm_));
  for (int r = 0; r < nm_; ++r) {
    const double w = plate.omega()[r];
    plate_c_[static_cast<std::size_t>(r)] =
        2.0 * plate.modes()[static_cast<std::size_t>(r)].damping_ratio * w;
    inv_d[r] = 1.0 / (w * w + a0_ + a1_ * plate_c_[static_cast<std::size_t>(r)]);
  }
  inv_d_.assign(inv_d.data(), inv_d.data() + nm_);
  const Eigen::MatrixXd shapes_b = plate.shapes().topRows(ns_);
  shapes_b_ = RowMajor(shapes_b);
  shapes_all_ = plate.shapes();
  Eigen::MatrixXd shapes_o(no_, nm_);
  for (int o = 0; o < no_; ++o) shapes_o.row(o) = plate.shapes().row(output_points[static_cast<std::size_t>(o)]);
  shapes_o_ = RowMajor(shapes_o);

  const Eigen::MatrixXd g = shapes_b * inv_d.asDiagonal() * shapes_b.transpose();
  const Eigen::MatrixXd gk = g * kb.asDiagonal();
  const Eigen::MatrixXd r = (Eigen::MatrixXd::Identity(ns_, ns_) + gk).inverse();
  const Eigen::MatrixXd q = r * gk;
  r_ = RowMajor(r);
  q_ = RowMajor(q);
  Eigen::MatrixXd a0m = stiff_r + a1_ * damp_r;
  a0m.diagonal() += a0_ * mass_r;
  for (int i = 0; i < ns_; ++i) {
    for (int j = 0; j < ns_; ++j) {
      a0m(ns_ + i, ns_ + j) += (i == j ? kb[i] : 0.0) - kb[i] * q(i, j);
    }
  }
  const Eigen::MatrixXd inv_a0 = a0m.inverse();
  inv_a0_ = RowMajor(inv_a0);
  const Eigen::MatrixXd inv_a0_v = inv_a0 * mesh_v;
  inv_a0_v_ = RowMajor(inv_a0_v.transpose());
  vt_inv_a0_v_ = RowMajor(mesh_v.transpose() * inv_a0_v);
  er_ = RowMajor(kb.asDiagonal() * r);
  w_ = RowMajor(inv_d.asDiagonal() * shapes_b.transpose() * kb.asDiagonal());

  const int n = gearbox.dof_count();
  state_.u = Eigen::VectorXd::Zero(n);
  state_.v = Eigen::VectorXd::Zero(n);
  state_.a = Eigen::VectorXd::Zero(n);
  const auto z = [](int k) { return std::vector<double>(static_cast<std::size_t>(k), 0.0); };
  u_new_q_ = z(nm_);
  ym_r_ = z(nr_);
  yc_r_ = z(nr_);
  b_r_ = z(nr_);
  wv_ = z(nr_);
  delta_ = z(ns_);
  g_ = z(ns_);
  x_ = z(ns_);
  keff_ = z(stages_);
  load_ = z(stages_);
  vtw_ = z(stages_);
  vyc_ = z(stages_);
  approach_ = z(stages_);
  alpha_ = z(stages_);
  beta_ = z(stages_);
  small_ = z(stages_ * stages_);
  active_.assign(static_cast<std::size_t>(2 * stages_), 1);
  outputs_ = z(no_);
}

void GearboxIntegrator::SetStatic(const std::vector<MeshSample>& mesh,
                                  const Eigen::VectorXd& rotor_force) {
  std::vector<double> k;
  for (const MeshSample& m : mesh) k.push_back(m.TotalStiffness());
  Eigen::MatrixXd mass, damping, stiffness;
  gearbox_->Assemble(k, mass, damping, stiffness);
  Eigen::VectorXd f = Eigen::VectorXd::Zero(gearbox_->dof_count());
  f.head(nr_) = rotor_force;
  for (int s = 0; s < stages_; ++s) {
    const MeshSample& m = mesh[static_cast<std::size_t>(s)];
    f.head(nr_) += (m.ErrorForce() + mesh_c_[static_cast<std::size_t>(s)] * m.error_rate) *
                   gearbox_->MeshVector(s);
  }
  // Assemble() puts the mesh damping in; at rest it does not matter.
  state_.u = stiffness.fullPivLu().solve(f);
  state_.v.setZero();
  state_.a.setZero();
  for (int s = 0; s < stages_; ++s) approach_[static_cast<std::size_t>(s)] = Approach(s);
  Outputs();
}

void GearboxIntegrator::Outputs() noexcept {
  const double* aq = state_.a.data() + nr_;
  for (int o = 0; o < no_; ++o) {
    const double* phi = shapes_o_.data() + static_cast<std::size_t>(o) * nm_;
    double acc = 0.0;
    for (int r = 0; r < nm_; ++r) acc += phi[r] * aq[r];
    outputs_[static_cast<std::size_t>(o)] = acc;
  }
}

void GearboxIntegrator::Step(const std::vector<MeshSample>& mesh,
                             const Eigen::VectorXd& rotor_force) noexcept {
  double* u = state_.u.data();
  double* v = state_.v.data();
  double* a = state_.a.data();
  double* uq = u + nr_;
  double* vq = v + nr_;
  double* aq = a + nr_;
  const int nm = nm_, ns = ns_, nr = nr_, st = stages_;
  // Newmark predictors (average acceleration: a3 = a4 = 1, a5 = 0): ym = a0 u + a2 v + a,
  // yc = a1 u + v. Plate: its yc only through the bearing dampers' relative motion.
  for (int i = 0; i < nr; ++i) {
    ym_r_[i] = a0_ * u[i] + a2_ * v[i] + a[i];
    yc_r_[i] = a1_ * u[i] + v[i];
  }
  for (int i = 0; i < ns; ++i) {
    const double* pi = shapes_b_.data() + static_cast<std::size_t>(i) * nm;
    double seat = 0.0;
    for (int r = 0; r < nm; ++r) seat += pi[r] * (a1_ * uq[r] + vq[r]);
    // Bearing damper force predictor: c_b (shaft - seat).
    delta_[i] = bearing_c_[i] * (yc_r_[ns + i] - seat);
  }
  // Plate right-hand side and y = D^-1 b_q (into u_new_q_), g = P^T y.
  for (int i = 0; i < ns; ++i) g_[i] = 0.0;
  double* y = u_new_q_.data();
  for (int r = 0; r < nm; ++r) {
    double b = a0_ * uq[r] + a2_ * vq[r] + aq[r] + plate_c_[r] * (a1_ * uq[r] + vq[r]);
    for (int i = 0; i < ns; ++i) b -= shapes_b_[static_cast<std::size_t>(i) * nm + r] * delta_[i];
    y[r] = inv_d_[r] * b;
  }
  for (int i = 0; i < ns; ++i) {
    const double* pi = shapes_b_.data() + static_cast<std::size_t>(i) * nm;
    double sum = 0.0;
    for (int r = 0; r < nm; ++r) sum += pi[r] * y[r];
    g_[i] = sum;
  }
  // Rotor right-hand side + E Kb R g.
  for (int i = 0; i < nr; ++i) {
    double b = rotor_force[i] + mass_r_[i] * ym_r_[i];
    const double* d = damp_r_.data() + static_cast<std::size_t>(i) * nr;
    for (int j = 0; j < nr; ++j) b += d[j] * yc_r_[j];
    b_r_[i] = b;
  }
  for (int i = 0; i < ns; ++i) {
    double b = delta_[i];
    for (int j = 0; j < ns; ++j) b += er_[static_cast<std::size_t>(i) * ns + j] * g_[j];
    b_r_[ns + i] += b;
  }

  // Rotor: A(t) u_r = b_r + sum_s v_s m_s, A(t) = A_0 + sum_s keff_s v_s v_s^T. With
  // w = A_0^-1 b_r and U = A_0^-1 V, Woodbury gives u_r = w + U (m - beta),
  // (I + Keff V^T U) beta = Keff V^T (w + U m); the approaches V^T u_r follow in stage space,
  // so the contact of every tooth pair (delta_s > gap_j) is iterated there (active set).
  for (int i = 0; i < nr; ++i) {
    const double* row = inv_a0_.data() + static_cast<std::size_t>(i) * nr;
    double sum = 0.0;
    for (int j = 0; j < nr; ++j) sum += row[j] * b_r_[j];
    wv_[i] = sum;
  }
  for (int s = 0; s < st; ++s) {
    const double* vs = mesh_v_.data() + static_cast<std::size_t>(s) * nr;
    double vyc = 0.0, vtw = 0.0;
    for (int j = 0; j < nr; ++j) {
      vyc += vs[j] * yc_r_[j];
      vtw += vs[j] * wv_[j];
    }
    vyc_[s] = vyc;
    vtw_[s] = vtw;
    // First guess of the contact: the last step's approach.
    const MeshSample& m = mesh[static_cast<std::size_t>(s)];
    for (int j = 0; j < 2; ++j) {
      active_[static_cast<std::size_t>(2 * s + j)] =
          m.bilateral || (j < m.pairs && approach_[s] > m.gap[j]);
    }
  }
  for (int iteration = 0; iteration < kMaxContactIterations; ++iteration) {
    for (int s = 0; s < st; ++s) {
      const MeshSample& m = mesh[static_cast<std::size_t>(s)];
      double k = 0.0, kg = 0.0;
      for (int j = 0; j < m.pairs; ++j) {
        if (!active_[static_cast<std::size_t>(2 * s + j)]) continue;
        k += m.stiffness[j];
        kg += m.stiffness[j] * m.gap[j];
      }
      const double total = m.TotalStiffness();
      const double c = total > 0.0 ? mesh_c_[static_cast<std::size_t>(s)] * k / total : 0.0;
      keff_[s] = k + a1_ * c;
      load_[s] = kg + c * (m.error_rate + vyc_[s]);
    }
    for (int s = 0; s < st; ++s) {
      double vtw = vtw_[s];
      for (int t = 0; t < st; ++t) vtw += vt_inv_a0_v_[static_cast<std::size_t>(s * st + t)] * load_[t];
      alpha_[s] = vtw;  // V^T (w + U m)
      beta_[s] = keff_[s] * vtw;
      for (int t = 0; t < st; ++t) {
        small_[static_cast<std::size_t>(s * st + t)] =
            (s == t ? 1.0 : 0.0) + keff_[s] * vt_inv_a0_v_[static_cast<std::size_t>(s * st + t)];
      }
    }
    SolveSmall(small_.data(), beta_.data(), st);
    bool consistent = true;
    for (int s = 0; s < st; ++s) {
      double approach = alpha_[s];
      for (int t = 0; t < st; ++t) approach -= vt_inv_a0_v_[static_cast<std::size_t>(s * st + t)] * beta_[t];
      approach_[s] = approach;
      const MeshSample& m = mesh[static_cast<std::size_t>(s)];
      for (int j = 0; j < 2; ++j) {
        const char want = m.bilateral || (j < m.pairs && approach > m.gap[j]);
        char& is = active_[static_cast<std::size_t>(2 * s + j)];
        if (j < m.pairs && want != is) consistent = false;
        is = want;
      }
    }
    if (consistent) break;
  }
  // Rotor update (u_r new = w + U (m - beta)), then Newmark for the rotor DOFs.
  for (int i = 0; i < nr; ++i) {
    double un = wv_[i];
    for (int s = 0; s < st; ++s) un += inv_a0_v_[static_cast<std::size_t>(s) * nr + i] * (load_[s] - beta_[s]);
    const double an = a0_ * (un - u[i]) - a2_ * v[i] - a[i];
    v[i] += 0.5 * h_ * (a[i] + an);
    a[i] = an;
    u[i] = un;
  }
  // Seats: z = R g + Q x; plate: q = y + W (x - z), then Newmark and the outputs.
  for (int i = 0; i < ns; ++i) {
    double z = 0.0;
    for (int j = 0; j < ns; ++j) {
      z += r_[static_cast<std::size_t>(i) * ns + j] * g_[j] +
           q_[static_cast<std::size_t>(i) * ns + j] * u[ns + j];
    }
    x_[i] = u[ns + i] - z;
  }
  for (int r = 0; r < nm; ++r) {
    double qn = y[r];
    const double* wr = w_.data() + static_cast<std::size_t>(r) * ns;
    for (int i = 0; i < ns; ++i) qn += wr[i] * x_[i];
    const double an = a0_ * (qn - uq[r]) - a2_ * vq[r] - aq[r];
    vq[r] += 0.5 * h_ * (aq[r] + an);
    aq[r] = an;
    uq[r] = qn;
  }
  Outputs();
}

double GearboxIntegrator::PointAcceleration(int point) const noexcept {
  return shapes_all_.row(point).dot(state_.a.tail(nm_));
}

double GearboxIntegrator::Approach(int stage) const noexcept {
  return gearbox_->MeshVector(stage).dot(state_.u.head(nr_));
}

}  // namespace gearpath
