// GearboxIntegrator against independent truth:
//  - with constant mesh stiffness and sinusoidal profile errors, the simulated steady state
//    equals the frequency-domain solution of the same linear system, assembled here from the
//    physical description (docs: parametric_gearbox.h) and solved densely: exactly at the
//    trapezoidal rule's warped frequency (2 / h) tan(w h / 2), and within the warp at w;
//  - one gear pair alone with constant stiffness is the closed-form single-DOF mesh oscillator;
//  - undamped and unforced, the energy 1/2 v'Mv + 1/2 u'Ku is conserved (average acceleration);
//  - damped, unforced, with the time-varying mesh stiffness, any state decays.
#include "core/evaluation/gearbox_integrator.h"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <numbers>

#include "core/evaluation/parametric_plant_simulator.h"
#include "core/evaluation/parametric_plate_plant.h"

namespace gearpath {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;
using Cd = std::complex<double>;

// A family plant with every mesh error and eccentricity removed; stage 0 then carries the given
// profile harmonics, stage 1 its own.
ParametricGearboxParameters Quiet(std::uint64_t seed, std::vector<double> a0,
                                  std::vector<double> a1) {
  Result<ParametricPlatePlant> plant = DrawParametricPlatePlant(GearTrain::Table1(), true, seed);
  EXPECT_TRUE(plant.ok()) << plant.error();
  ParametricGearboxParameters p = plant->truth->parameters();
  for (std::size_t s = 0; s < p.stages.size(); ++s) {
    ToothMeshParameters& m = p.stages[s].mesh;
    m.driver = m.driven = GearEccentricity{};
    m.profile_amplitude_m = s == 0 ? a0 : a1;
    m.profile_phase.assign(m.profile_amplitude_m.size(), 0.0);
    for (std::size_t h = 0; h < m.profile_phase.size(); ++h) {
      m.profile_phase[h] = 0.7 * static_cast<double>(h) - 0.3 * static_cast<double>(s);
    }
  }
  return p;
}

// The linear system written out from the physics: M, C, K over [phi, x, q] with mesh
// stiffness k_s (mean), mesh damping c_s, bearings between x_i and the plate at point i.
struct Linear {
  Eigen::MatrixXd m, c, k;
};
Linear Assemble(const ParametricGearbox& g) {
  const ParametricGearboxParameters& p = g.parameters();
  const int shafts = static_cast<int>(p.shafts.size());
  const PlateHousing& plate = p.plate;
  const int n = 2 * shafts + plate.mode_count();
  Linear l{Eigen::MatrixXd::Zero(n, n), Eigen::MatrixXd::Zero(n, n), Eigen::MatrixXd::Zero(n, n)};
  for (int i = 0; i < shafts; ++i) {
    l.m(i, i) = p.shafts[i].inertia_kg_m2;
    l.m(shafts + i, shafts + i) = p.shafts[i].mass_kg;
  }
  l.k(0, 0) += p.motor_stiffness_nm_per_rad;
  l.c(0, 0) += p.motor_damping_nms_per_rad;
  l.c(shafts - 1, shafts - 1) += p.load_damping_nms_per_rad;
  for (std::size_t s = 0; s < p.stages.size(); ++s) {
    const MeshStage& st = p.stages[s];
    Eigen::VectorXd v = Eigen::VectorXd::Zero(n);
    const double sigma = p.shafts[st.driver_shaft].rotation_sign;
    v[st.driver_shaft] = sigma * st.driver_base_radius_m;
    v[st.driven_shaft] = sigma * st.driven_base_radius_m;
    v[shafts + st.driver_shaft] += 1.0;
    v[shafts + st.driven_shaft] -= 1.0;
    l.k += g.meshes()[s].mean_stiffness() * v * v.transpose();
    l.c += st.damping_ns_per_m * v * v.transpose();
  }
  for (int r = 0; r < plate.mode_count(); ++r) {
    const double w = kTwoPi * plate.modes()[r].frequency_hz;
    l.m(2 * shafts + r, 2 * shafts + r) = 1.0;
    l.k(2 * shafts + r, 2 * shafts + r) += w * w;
    l.c(2 * shafts + r, 2 * shafts + r) += 2.0 * plate.modes()[r].damping_ratio * w;
  }
  for (int i = 0; i < shafts; ++i) {
    Eigen::VectorXd b = Eigen::VectorXd::Zero(n);
    b[shafts + i] = 1.0;
    for (int r = 0; r < plate.mode_count(); ++r) {
      const PlatePoint& q = plate.points()[i];
      b[2 * shafts + r] = -plate.Shape(r, q.x_m, q.y_m);
    }
    l.k += p.shafts[i].bearing_stiffness_n_per_m * b * b.transpose();
    l.c += p.shafts[i].bearing_damping_ns_per_m * b * b.transpose();
  }
  return l;
}

// Plate acceleration at point `point` for a profile error E (complex amplitude, m) on stage s
// at w; the system is evaluated at ws (w or the warped frequency), the error's rate at w.
Cd FrequencyDomain(const ParametricGearbox& g, const Linear& l, int stage, Cd e, double w,
                   double ws, int point) {
  const int shafts = g.shaft_count();
  const int n = static_cast<int>(l.m.rows());
  const ParametricGearboxParameters& p = g.parameters();
  const MeshStage& st = p.stages[stage];
  Eigen::VectorXcd f = Eigen::VectorXcd::Zero(n);
  const double sigma = p.shafts[st.driver_shaft].rotation_sign;
  f[st.driver_shaft] = sigma * st.driver_base_radius_m;
  f[st.driven_shaft] = sigma * st.driven_base_radius_m;
  f[shafts + st.driver_shaft] += 1.0;
  f[shafts + st.driven_shaft] -= 1.0;
  f *= (g.meshes()[stage].mean_stiffness() + Cd(0.0, w) * st.damping_ns_per_m) * e;
  const Eigen::MatrixXcd z = l.k.cast<Cd>() - ws * ws * l.m.cast<Cd>() + Cd(0.0, ws) * l.c.cast<Cd>();
  const Eigen::VectorXcd u = z.partialPivLu().solve(f);
  Cd acc = 0.0;
  const PlatePoint& q = p.plate.points()[point];
  for (int r = 0; r < p.plate.mode_count(); ++r) acc += p.plate.Shape(r, q.x_m, q.y_m) * u[2 * shafts + r];
  return -ws * ws * acc;
}

// One-sided complex amplitude of x at f (direct DFT).
Cd Bin(const Eigen::VectorXd& x, double f, double fs) {
  Cd acc = 0.0;
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    acc += x[i] * std::polar(1.0, -kTwoPi * f * static_cast<double>(i) / fs);
  }
  return acc * 2.0 / static_cast<double>(x.size());
}

struct Deviation {
  double exact = 0.0;      // against the solution at the warped frequency, relative
  double amplitude = 0.0;  // against the continuous solution: relative amplitude error
  double phase_deg = 0.0;  // and phase error
};

Deviation SteadyStateDeviation(const ParametricGearboxParameters& p, std::uint32_t oversampling) {
  Result<ParametricGearbox> g = ParametricGearbox::Create(p);
  EXPECT_TRUE(g.ok()) << g.error();
  auto gearbox = std::make_shared<const ParametricGearbox>(std::move(g).value());
  ParametricSimulatorConfig c;
  c.block_length = 8000;  // 1 Hz bins: every line at 10 Hz input falls on a bin
  c.input_speed_hz = 10.0;
  c.noise_relative = 0.0;
  c.run_in_s = 1.0;
  c.oversampling = oversampling;
  c.constant_stiffness = true;
  Result<ParametricPlantSimulator> sim = ParametricPlantSimulator::Create(
      gearbox, {0, 1, 2, 3}, {{"p1"}, {"p2"}, {"p3"}, {"m1"}}, ToothFault{}, c);
  EXPECT_TRUE(sim.ok()) << sim.error();
  Eigen::MatrixXd block;
  sim->NoiseFreeNext(false, block);  // block 0: t = 0 .. 1 s
  const Linear lin = Assemble(*gearbox);
  const double h = sim->step_s();
  Deviation d;
  for (int stage = 0; stage < 2; ++stage) {
    const ToothMeshParameters& m = p.stages[stage].mesh;
    const double mesh_hz =
        m.z_driver * p.shafts[p.stages[stage].driver_shaft].revs_per_input_rev * 10.0;
    for (std::size_t harmonic = 0; harmonic < m.profile_amplitude_m.size(); ++harmonic) {
      if (m.profile_amplitude_m[harmonic] == 0.0) continue;
      const double f = mesh_hz * static_cast<double>(harmonic + 1);
      // e = A cos(2 pi h (f_mesh t + m_0) + phi_h): complex amplitude at t = 0.
      const Cd e = std::polar(m.profile_amplitude_m[harmonic],
                              kTwoPi * static_cast<double>(harmonic + 1) * m.mesh_phase +
                                  m.profile_phase[harmonic]);
      const double w = kTwoPi * f;
      const double warped = 2.0 / h * std::tan(0.5 * w * h);
      for (int ch = 0; ch < 4; ++ch) {
        const Cd td = Bin(block.col(ch), f, 8000.0);
        const Cd exact = FrequencyDomain(*gearbox, lin, stage, e, w, warped, ch);
        const Cd cont = FrequencyDomain(*gearbox, lin, stage, e, w, w, ch);
        d.exact = std::max(d.exact, std::abs(td - exact) / std::abs(exact));
        d.amplitude = std::max(d.amplitude, std::abs(std::abs(td) / std::abs(cont) - 1.0));
        d.phase_deg =
            std::max(d.phase_deg, std::abs(std::arg(td / cont)) * 180.0 / std::numbers::pi);
        // Every line is a real response, not round-off.
        EXPECT_GT(std::abs(td), 1e-3 * block.col(ch).norm() / std::sqrt(8000.0)) << f << " " << ch;
      }
    }
  }
  return d;
}

// Lines at 280 .. 1120 Hz (stage 0, mesh harmonics 1-4) and 238 .. 714 Hz (stage 1) on every
// channel, constant mesh stiffness, no eccentricity.
TEST(GearboxIntegrator, ConstantStiffnessSteadyStateMatchesTheFrequencyDomainSolution) {
  const ParametricGearboxParameters p =
      Quiet(5, {1e-6, 0.5e-6, 0.25e-6, 0.1e-6}, {0.8e-6, 0.3e-6, 0.2e-6, 0.0});
  const Deviation d8 = SteadyStateDeviation(p, 8);
  const Deviation d16 = SteadyStateDeviation(p, 16);
  std::printf("constant stiffness vs frequency domain, 8x: exact (warped) %.2e, continuous: "
              "amplitude %.3f %%, phase %.3f deg; 16x: %.2e, %.3f %%, %.3f deg\n",
              d8.exact, 100.0 * d8.amplitude, d8.phase_deg, d16.exact, 100.0 * d16.amplitude,
              d16.phase_deg);
  // The integrator is exactly the trapezoidal rule (the anti-alias FIR's pass-band ripple is
  // ~1e-5): amplitude and phase at the warped frequency.
  EXPECT_LT(d8.exact, 1e-4);
  EXPECT_LT(d16.exact, 1e-4);
  // Against the continuous system at w, the warp ((w h)^2 / 12: 0.1 % in frequency at 1.1 kHz)
  // near lightly damped modes: within 2 % and 2 deg at 8x, falling as h^2.
  EXPECT_LT(d8.amplitude, 0.02);
  EXPECT_LT(d8.phase_deg, 2.0);
  EXPECT_LT(d16.amplitude, 0.35 * d8.amplitude);
  EXPECT_LT(d16.phase_deg, 0.35 * d8.phase_deg);
}

// One gear pair, nothing else that moves: the classic single-degree-of-freedom mesh model
// (e.g. Ozguven and Houser, J. Sound Vib. 121, 1988) in the approach delta = rb_1 phi_1 +
// rb_2 phi_2: m_e delta'' + c delta' + k delta = k e + c e', m_e = 1 / (rb_1^2 / J_1 +
// rb_2^2 / J_2), whose steady state under e = E cos(w t) is delta = E (k + j c w) /
// (k - m_e w^2 + j c w): closed form, no matrix anywhere. The pair is isolated by making the
// lateral masses enormous (no lateral motion), the motor coupling negligible and the load
// free. The integrator (trapezoidal) must give that response at the warped frequency
// (2 / h) tan(w h / 2) to round-off, at w within the warp; below, at and above resonance.
TEST(GearboxIntegrator, SingleGearPairWithConstantStiffnessIsTheClosedFormOscillator) {
  const double j1 = 1.0e-3, j2 = 3.0e-3, rb1 = 0.04, rb2 = 0.06;
  const double k = 5.0e7, zeta = 0.05;
  const double me = 1.0 / (rb1 * rb1 / j1 + rb2 * rb2 / j2);
  const double c = 2.0 * zeta * std::sqrt(k * me);
  const double wn = std::sqrt(k / me);
  ParametricGearboxParameters p;
  p.shafts = {{j1, 1e12, 1e8, 0.0, 1.0, 1}, {j2, 1e12, 1e8, 0.0, rb1 / rb2, -1}};
  MeshStage stage;
  stage.driver_shaft = 0;
  stage.driven_shaft = 1;
  stage.driver_base_radius_m = rb1;
  stage.driven_base_radius_m = rb2;
  stage.damping_ns_per_m = c;
  stage.mesh.z_driver = 20;
  stage.mesh.z_driven = 30;
  p.stages = {stage};
  p.motor_stiffness_nm_per_rad = 1e-9;
  PlateGeometry plate;
  std::vector<PlateMode> modes = EnumeratePlateModes(plate, 1000.0);
  modes.resize(1);
  modes[0].damping_ratio = 0.02;
  p.plate = PlateHousing::Create(plate, modes, {{0.2, 0.2}, {0.4, 0.2}}).value();
  Result<ParametricGearbox> g = ParametricGearbox::Create(p);
  ASSERT_TRUE(g.ok()) << g.error();
  const double h = 1.0 / 64000.0;
  const double e_amp = 1e-6;
  for (double ratio : {0.5, 1.0, 1.5}) {
    const double w = ratio * wn;
    GearboxIntegrator integrator(*g, h);
    std::vector<MeshSample> mesh(1);
    mesh[0].pairs = 1;
    mesh[0].stiffness[0] = k;
    mesh[0].bilateral = true;
    const Eigen::VectorXd force = Eigen::VectorXd::Zero(g->rotor_dofs());
    // Transient: e^{-zeta wn t} < 1e-14 after 64000 steps (1 s); then fit A cos + B sin over
    // 6400 steps by least squares (exact for a sampled sinusoid).
    Eigen::Matrix2d normal = Eigen::Matrix2d::Zero();
    Eigen::Vector2d rhs = Eigen::Vector2d::Zero();
    for (int n = 1; n <= 70400; ++n) {
      const double t = n * h;
      mesh[0].gap[0] = e_amp * std::cos(w * t);
      mesh[0].error_rate = -e_amp * w * std::sin(w * t);
      integrator.Step(mesh, force);
      if (n > 64000) {
        const Eigen::Vector2d basis(std::cos(w * t), std::sin(w * t));
        normal += basis * basis.transpose();
        rhs += basis * integrator.Approach(0);
      }
    }
    const Eigen::Vector2d ab = normal.ldlt().solve(rhs);
    const Cd simulated(ab[0], -ab[1]);  // delta = Re(D e^{j w t})
    const double warped = 2.0 / h * std::tan(0.5 * w * h);
    const auto closed_form = [&](double ws) {
      return e_amp * Cd(k, c * w) / Cd(k - me * ws * ws, c * ws);
    };
    const Cd exact = closed_form(warped);
    const Cd continuous = closed_form(w);
    EXPECT_LT(std::abs(simulated - exact), 1e-6 * std::abs(exact)) << "w / wn " << ratio;
    // Against the continuous oscillator, the warp ((w h)^2 / 12: 0.3 % in frequency at f_n =
    // 1.9 kHz, 0.7 % at 2.8 kHz, where the response falls as w^-2, so ~2 % in amplitude).
    EXPECT_LT(std::abs(std::abs(simulated) / std::abs(continuous) - 1.0), 0.03) << ratio;
    std::printf("gear pair at %.2f w_n: |delta| %.4e m (closed form %.4e at w, %.4e warped), "
                "relative deviation from the warped one %.1e\n",
                ratio, std::abs(simulated), std::abs(continuous), std::abs(exact),
                std::abs(simulated - exact) / std::abs(exact));
  }
}

std::vector<MeshSample> MeanMesh(const ParametricGearbox& g, bool bilateral) {
  std::vector<MeshSample> mesh(static_cast<std::size_t>(g.stage_count()));
  for (int s = 0; s < g.stage_count(); ++s) {
    mesh[s].pairs = 1;
    mesh[s].stiffness[0] = g.meshes()[s].mean_stiffness();
    mesh[s].bilateral = bilateral;
  }
  return mesh;
}

double Energy(const ParametricGearbox& g, const IntegratorState& s,
              const std::vector<double>& k) {
  Eigen::MatrixXd m, c, kk;
  g.Assemble(k, m, c, kk);
  return 0.5 * s.v.dot(m * s.v) + 0.5 * s.u.dot(kk * s.u);
}

TEST(GearboxIntegrator, UndampedUnforcedEnergyIsConserved) {
  ParametricGearboxParameters p = Quiet(9, {}, {});
  p.motor_damping_nms_per_rad = 0.0;
  p.load_damping_nms_per_rad = 0.0;
  for (ShaftRotor& r : p.shafts) r.bearing_damping_ns_per_m = 0.0;
  for (MeshStage& s : p.stages) s.damping_ns_per_m = 0.0;
  std::vector<PlateMode> modes = p.plate.modes();
  for (PlateMode& m : modes) m.damping_ratio = 0.0;
  p.plate = PlateHousing::Create(p.plate.geometry(), modes, p.plate.points()).value();
  Result<ParametricGearbox> g = ParametricGearbox::Create(p);
  ASSERT_TRUE(g.ok()) << g.error();
  GearboxIntegrator integrator(*g, 1.0 / 64000.0);
  IntegratorState& s = integrator.mutable_state();
  // Some displacement of every DOF, at rest; a consistent acceleration M a = -K u.
  for (Eigen::Index i = 0; i < s.u.size(); ++i) s.u[i] = 1e-6 * std::sin(1.3 * static_cast<double>(i) + 0.2);
  const std::vector<double> k = {g->meshes()[0].mean_stiffness(), g->meshes()[1].mean_stiffness()};
  Eigen::MatrixXd m, c, kk;
  g->Assemble(k, m, c, kk);
  s.a = -m.diagonal().cwiseInverse().cwiseProduct(kk * s.u);
  const double e0 = Energy(*g, s, k);
  ASSERT_GT(e0, 0.0);
  const std::vector<MeshSample> mesh = MeanMesh(*g, true);
  const Eigen::VectorXd force = Eigen::VectorXd::Zero(g->rotor_dofs());
  double worst = 0.0;
  for (int n = 0; n < 32000; ++n) {
    integrator.Step(mesh, force);
    if (n % 1000 == 999) worst = std::max(worst, std::abs(Energy(*g, integrator.state(), k) / e0 - 1.0));
  }
  EXPECT_LT(worst, 1e-9);
  EXPECT_GT(integrator.state().v.norm(), 0.0);  // it did move
}

TEST(GearboxIntegrator, DampedUnforcedStateDecaysWithTheTimeVaryingStiffness) {
  ParametricGearboxParameters p = Quiet(13, {}, {});
  p.load_torque_nm = 0.0;
  p.load_damping_nms_per_rad = 0.0;  // the nominal motion then needs no torque
  Result<ParametricGearbox> g = ParametricGearbox::Create(p);
  ASSERT_TRUE(g.ok());
  for (double rpm : {200.0, 900.0}) {
    GearboxIntegrator integrator(*g, 1.0 / 64000.0);
    IntegratorState& s = integrator.mutable_state();
    for (Eigen::Index i = 0; i < s.u.size(); ++i) s.u[i] = 1e-6 * std::cos(0.7 * static_cast<double>(i));
    const std::vector<double> k = {g->meshes()[0].mean_stiffness(), g->meshes()[1].mean_stiffness()};
    Eigen::MatrixXd m, c, kk;
    g->Assemble(k, m, c, kk);
    s.a = -m.diagonal().cwiseInverse().cwiseProduct(kk * s.u);
    const double e0 = Energy(*g, s, k);
    std::vector<MeshSample> mesh(2);
    const Eigen::VectorXd force = Eigen::VectorXd::Zero(g->rotor_dofs());
    double largest = 0.0, last = 0.0;
    for (int n = 1; n <= 32000; ++n) {  // 0.5 s
      const double revs = rpm / 60.0 * n / 64000.0;
      for (int st = 0; st < 2; ++st) {
        const MeshStage& stage = p.stages[st];
        const double ra = p.shafts[stage.driver_shaft].revs_per_input_rev;
        const double rb = p.shafts[stage.driven_shaft].revs_per_input_rev;
        g->meshes()[st].Evaluate(MakeShaftPhase(ra * revs, ra * rpm / 60.0),
                                 MakeShaftPhase(rb * revs, rb * rpm / 60.0), nullptr, false,
                                 mesh[st]);
        mesh[st].bilateral = true;  // no preload here: keep the linear (two-sided) contact
      }
      integrator.Step(mesh, force);
      if (n % 500 == 0) {
        last = Energy(*g, integrator.state(), k);
        largest = std::max(largest, last);
      }
    }
    EXPECT_LT(largest, 2.0 * e0) << rpm;   // no parametric growth
    EXPECT_LT(last, 1e-6 * e0) << rpm;     // decayed
  }
}

}  // namespace
}  // namespace gearpath
