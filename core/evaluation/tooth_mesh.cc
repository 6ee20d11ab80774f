#include "core/evaluation/tooth_mesh.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace gearpath {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kTwoPi = 2.0 * std::numbers::pi;
constexpr int kShapeSamples = 20000;  // mean / max of the stiffness over a mesh period

double Ramp(double x, double r) noexcept {
  if (x >= r) return 1.0;
  if (x <= 0.0) return 0.0;
  return 0.5 * (1.0 - std::cos(kPi * x / r));
}

// a mod n in [0, n) for any sign of a.
std::int64_t Mod(std::int64_t a, std::int64_t n) noexcept {
  const std::int64_t r = a % n;
  return r < 0 ? r + n : r;
}

}  // namespace

ShaftPhase MakeShaftPhase(double revs, double rate_hz) noexcept {
  ShaftPhase s;
  s.revs = revs;
  s.rate_hz = rate_hz;
  const double f = revs - std::floor(revs);
  s.cos = std::cos(kTwoPi * f);
  s.sin = std::sin(kTwoPi * f);
  return s;
}

Result<ToothMesh> ToothMesh::Create(const ToothMeshParameters& parameters) {
  const ToothMeshParameters& p = parameters;
  if (p.z_driver < 2 || p.z_driven < 2) {
    return Error{fmt::format("tooth mesh: z_driver and z_driven must be >= 2, got {} and {}",
                             p.z_driver, p.z_driven)};
  }
  if (!(p.contact_ratio > 1.0 && p.contact_ratio < 2.0)) {
    return Error{
        fmt::format("tooth mesh: contact_ratio must be in (1, 2), got {}", p.contact_ratio)};
  }
  if (!(p.ramp_periods > 0.0 && p.ramp_periods < 0.5 * p.contact_ratio)) {
    return Error{fmt::format("tooth mesh: ramp_periods must be in (0, contact_ratio / 2), got {}",
                             p.ramp_periods)};
  }
  if (!(p.crown >= 0.0 && p.crown < 1.0)) {
    return Error{fmt::format("tooth mesh: crown must be in [0, 1), got {}", p.crown)};
  }
  if (!(p.pair_stiffness_n_per_m > 0.0) || !(p.base_pitch_m > 0.0) ||
      !std::isfinite(p.pair_stiffness_n_per_m) || !std::isfinite(p.base_pitch_m)) {
    return Error{fmt::format(
        "tooth mesh: pair_stiffness_n_per_m and base_pitch_m must be finite and > 0, got {} "
        "and {}",
        p.pair_stiffness_n_per_m, p.base_pitch_m)};
  }
  if (p.profile_amplitude_m.size() != p.profile_phase.size()) {
    return Error{fmt::format(
        "tooth mesh: profile_amplitude_m ({}) and profile_phase ({}) must have the same length",
        p.profile_amplitude_m.size(), p.profile_phase.size())};
  }
  ToothMesh mesh;
  mesh.p_ = p;
  mesh.trig_ = {std::cos(p.driver.runout_phase), std::sin(p.driver.runout_phase),
                std::cos(p.driven.runout_phase), std::sin(p.driven.runout_phase),
                std::cos(p.driver.wobble_phase),  std::sin(p.driver.wobble_phase),
                std::cos(p.driven.wobble_phase),  std::sin(p.driven.wobble_phase)};
  for (double phi : p.profile_phase) {
    mesh.cos_phase_.push_back(std::cos(phi));
    mesh.sin_phase_.push_back(std::sin(phi));
  }
  double sum = 0.0, top = 0.0;
  for (int i = 0; i < kShapeSamples; ++i) {
    const double u = (static_cast<double>(i) + 0.5) / kShapeSamples;
    const double k = mesh.PairShape(u) + mesh.PairShape(u + 1.0);
    sum += k;
    top = std::max(top, k);
  }
  mesh.mean_stiffness_ = p.pair_stiffness_n_per_m * sum / kShapeSamples;
  mesh.max_stiffness_ = p.pair_stiffness_n_per_m * top;
  return mesh;
}

Status ToothMesh::CheckFault(const ToothFault& fault) const {
  if (fault.kind == PlantFaultKind::kNone) return Status::Ok();
  const int z = fault.on_driver ? p_.z_driver : p_.z_driven;
  const PlantFaultSeverity& sv = fault.severity;
  if (fault.tooth < 0 || fault.tooth >= z) {
    return Error{fmt::format("tooth fault: tooth {} is not a tooth of a {}-tooth gear",
                             fault.tooth, z)};
  }
  if (!(sv.pulse_depth_m >= 0.0) || !(sv.dip_depth_m >= 0.0) ||
      !(sv.am_depth >= 0.0 && sv.am_depth < 1.0)) {
    return Error{fmt::format(
        "tooth fault: depths must be >= 0 and am_depth (crack) in [0, 1), got pulse {} m, dip {} "
        "m, crack {}",
        sv.pulse_depth_m, sv.dip_depth_m, sv.am_depth)};
  }
  if (!(sv.pulse_length_periods > 0.0) || !(sv.pulse_taper > 0.0 && sv.pulse_taper <= 0.5) ||
      !(fault.spall_start >= 0.0) ||
      fault.spall_start + sv.pulse_length_periods > p_.contact_ratio + 1e-12) {
    return Error{fmt::format(
        "tooth fault: the spall [{}, {}) must lie on the contact path [0, {}) with a taper in "
        "(0, 0.5]",
        fault.spall_start, fault.spall_start + sv.pulse_length_periods, p_.contact_ratio)};
  }
  if (!(fault.wear_length > 0.0 && fault.wear_length < static_cast<double>(z))) {
    return Error{fmt::format("tooth fault: wear_length must be in (0, {}) mesh periods, got {}", z,
                             fault.wear_length)};
  }
  return Status::Ok();
}

double ToothMesh::PairShape(double u) const noexcept {
  const double eps = p_.contact_ratio;
  if (u < 0.0 || u >= eps) return 0.0;
  const double c = 2.0 * u / eps - 1.0;
  return Ramp(u, p_.ramp_periods) * Ramp(eps - u, p_.ramp_periods) * (1.0 - p_.crown * c * c);
}

double ToothMesh::MeshCycles(const ShaftPhase& driver, const ShaftPhase& driven) const noexcept {
  const double run = p_.driver.runout_m * (driver.sin * trig_[0] + driver.cos * trig_[1]) +
                     p_.driven.runout_m * (driven.sin * trig_[2] + driven.cos * trig_[3]);
  return static_cast<double>(p_.z_driver) * driver.revs + p_.mesh_phase + run / p_.base_pitch_m;
}

void ToothMesh::Evaluate(const ShaftPhase& driver, const ShaftPhase& driven,
                         const ToothFault* fault, bool constant_stiffness,
                         MeshSample& out) const noexcept {
  const GearEccentricity& ed = p_.driver;
  const GearEccentricity& en = p_.driven;
  // Eccentricity: runout along the line of action (an additive TE and a shift of the contact
  // timing) and the wobble of the pair stiffness, once per revolution of each gear.
  const double cd = trig_[0], sd = trig_[1], cn = trig_[2], sn = trig_[3];
  const double run = ed.runout_m * (driver.sin * cd + driver.cos * sd) +
                     en.runout_m * (driven.sin * cn + driven.cos * sn);
  const double run_rate = ed.runout_m * kTwoPi * driver.rate_hz * (driver.cos * cd - driver.sin * sd) +
                          en.runout_m * kTwoPi * driven.rate_hz * (driven.cos * cn - driven.sin * sn);
  const double m = static_cast<double>(p_.z_driver) * driver.revs + p_.mesh_phase +
                   run / p_.base_pitch_m;
  const double m_rate =
      static_cast<double>(p_.z_driver) * driver.rate_hz + run_rate / p_.base_pitch_m;
  const double wobble =
      1.0 +
      ed.wobble * (driver.cos * trig_[4] - driver.sin * trig_[5]) +
      en.wobble * (driven.cos * trig_[6] - driven.sin * trig_[7]);

  // Healthy profile error: harmonics of the mesh position, by powers of e^{j 2 pi frac(m)}.
  const double j0 = std::floor(m);
  const double frac = m - j0;
  const double c1 = std::cos(kTwoPi * frac), s1 = std::sin(kTwoPi * frac);
  double ch = 1.0, sh = 0.0, e = run, de_dm = 0.0;
  for (std::size_t h = 0; h < p_.profile_amplitude_m.size(); ++h) {
    const double c = ch * c1 - sh * s1;
    sh = sh * c1 + ch * s1;
    ch = c;
    const double a = p_.profile_amplitude_m[h];
    const double cos_arg = ch * cos_phase_[h] - sh * sin_phase_[h];
    const double sin_arg = sh * cos_phase_[h] + ch * sin_phase_[h];
    e += a * cos_arg;
    de_dm -= a * kTwoPi * static_cast<double>(h + 1) * sin_arg;
  }
  double e_rate = de_dm * m_rate + run_rate;

  const bool faulty = fault != nullptr && fault->kind != PlantFaultKind::kNone;
  const PlantFaultKind kind = faulty ? fault->kind : PlantFaultKind::kNone;
  const int z = faulty ? (fault->on_driver ? p_.z_driver : p_.z_driven) : 1;
  const int offset = faulty ? (fault->on_driver ? p_.driver_tooth_offset : p_.driven_tooth_offset) : 0;
  const auto pair0 = static_cast<std::int64_t>(j0);

  out.error_rate = e_rate;
  out.bilateral = false;
  out.pairs = 0;
  if (constant_stiffness) {
    out.bilateral = true;
    out.pairs = 1;
    out.stiffness[0] = mean_stiffness_;
    out.gap[0] = e;
    out.stiffness[1] = 0.0;
    out.gap[1] = e;
    return;
  }
  for (int back = 0; back < 2; ++back) {
    const double u = frac + static_cast<double>(back);
    const double shape = PairShape(u);
    if (shape <= 0.0) continue;
    double k = p_.pair_stiffness_n_per_m * shape * wobble;
    double gap = e;
    if (faulty) {
      const PlantFaultSeverity& sv = fault->severity;
      // Teeth from the damaged one to this pair's tooth on the faulty gear, in (-z/2, z/2].
      std::int64_t teeth = Mod(pair0 - back + offset - fault->tooth, z);
      if (2 * teeth > z) teeth -= z;
      if (teeth == 0 && kind != PlantFaultKind::kWearDip) {
        if (kind != PlantFaultKind::kTePulse) k *= 1.0 - sv.am_depth;
        if (kind != PlantFaultKind::kMeshAm) {
          gap += sv.pulse_depth_m *
                 TaperedWindow(u - fault->spall_start, sv.pulse_length_periods, sv.pulse_taper);
        }
      }
      if (kind == PlantFaultKind::kWearDip &&
          2.0 * std::abs(static_cast<double>(teeth)) < fault->wear_length) {
        // Worn flank: smooth along the path (zero at engagement and release), the worn tooth
        // fully, its neighbours by a Hann weight over wear_length teeth.
        const double across = std::cos(kPi * static_cast<double>(teeth) / fault->wear_length);
        const double along = std::sin(kPi * u / p_.contact_ratio);
        gap += sv.dip_depth_m * across * across * along * along;
      }
    }
    out.stiffness[out.pairs] = k;
    out.gap[out.pairs] = gap;
    ++out.pairs;
  }
  for (int j = out.pairs; j < 2; ++j) {
    out.stiffness[j] = 0.0;
    out.gap[j] = e;
  }
}

}  // namespace gearpath
