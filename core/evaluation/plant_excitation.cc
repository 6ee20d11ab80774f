#include "core/evaluation/plant_excitation.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/simulation/deterministic_rng.h"

namespace gearpath {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;
constexpr std::uint64_t kAmplitudeStream = 101;
constexpr std::uint64_t kToothStream = 102;

double UniformIn(DeterministicRng& rng, double lo, double hi) {
  return lo + (hi - lo) * rng.Uniform();
}

}  // namespace

std::string_view PlantFaultKindName(PlantFaultKind kind) noexcept {
  switch (kind) {
    case PlantFaultKind::kNone:
      return "none";
    case PlantFaultKind::kTePulse:
      return "te_pulse";
    case PlantFaultKind::kMeshAm:
      return "mesh_am";
    case PlantFaultKind::kWearDip:
      return "wear_dip";
    case PlantFaultKind::kCombined:
      return "combined";
  }
  return "unknown";
}

std::optional<PlantFaultKind> ParsePlantFaultKind(std::string_view name) noexcept {
  for (PlantFaultKind k : kAllPlantFaultKinds) {
    if (name == PlantFaultKindName(k)) return k;
  }
  return std::nullopt;
}

double TaperedWindow(double x, double length, double taper) noexcept {
  if (x < 0.0 || x >= length) return 0.0;
  const double ramp = taper * length;
  if (ramp <= 0.0) return 1.0;
  if (x < ramp) return 0.5 * (1.0 - std::cos(std::numbers::pi * x / ramp));
  if (x > length - ramp) return 0.5 * (1.0 - std::cos(std::numbers::pi * (length - x) / ramp));
  return 1.0;
}

Result<PlantExcitation> PlantExcitation::Create(const GearTrain& train,
                                                const PlantExcitationConfig& config) {
  Result<TrainKinematics> kin = train.Kinematics(1.0);
  if (!kin) return Error{"plant excitation: train: " + kin.error()};
  const PlantExcitationConfig& c = config;
  const PlantFaultSeverity& sv = c.severity;
  if (c.mesh_harmonics < 1) {
    return Error{
        fmt::format("plant excitation: mesh_harmonics must be >= 1, got {}", c.mesh_harmonics)};
  }
  if (!(c.mesh_fundamental_m > 0.0) || !std::isfinite(c.mesh_fundamental_m)) {
    return Error{fmt::format("plant excitation: mesh_fundamental_m must be finite and > 0, got {}",
                             c.mesh_fundamental_m)};
  }
  if (!(c.eccentricity_depth >= 0.0 && c.eccentricity_depth < 0.3)) {
    return Error{fmt::format("plant excitation: eccentricity_depth must be in [0, 0.3), got {}",
                             c.eccentricity_depth)};
  }
  if (!(sv.pulse_depth_m >= 0.0) || !(sv.dip_depth_m >= 0.0) ||
      !(sv.am_depth >= 0.0 && sv.am_depth <= 1.0)) {
    return Error{fmt::format(
        "plant excitation: severity depths must be >= 0 and am_depth in [0, 1], got pulse {} m, "
        "dip {} m, am {}",
        sv.pulse_depth_m, sv.dip_depth_m, sv.am_depth)};
  }
  if (!(sv.pulse_taper > 0.0 && sv.pulse_taper <= 0.5) ||
      !(sv.am_taper > 0.0 && sv.am_taper <= 0.5)) {
    return Error{fmt::format("plant excitation: tapers must be in (0, 0.5], got pulse {} am {}",
                             sv.pulse_taper, sv.am_taper)};
  }
  if (!(sv.pulse_length_periods > 0.0) || !(sv.am_length_periods > 0.0) ||
      !(sv.dip_length_lo > 0.0) || !(sv.dip_length_hi >= sv.dip_length_lo)) {
    return Error{
        "plant excitation: window lengths must be > 0 and dip_length_hi >= "
        "dip_length_lo"};
  }

  PlantExcitation e;
  e.config_ = c;
  for (const ShaftKinematics& s : kin->shafts) e.shaft_orders_.push_back(s.rotation_hz);
  DeterministicRng rng(c.seed, kAmplitudeStream);
  for (std::size_t s = 0; s < train.stages.size(); ++s) {
    const MeshKinematics& m = kin->meshes[s];
    const GearKinematics& gd = kin->gears[static_cast<std::size_t>(train.GearIndex(m.driver))];
    const GearKinematics& gn = kin->gears[static_cast<std::size_t>(train.GearIndex(m.driven))];
    Stage st;
    st.mesh_order = m.mesh_hz;
    const double a1 = c.mesh_fundamental_m * UniformIn(rng, 0.7, 1.3);
    const double rho = UniformIn(rng, 0.25, 0.45);
    double a = a1;
    for (int h = 0; h < c.mesh_harmonics; ++h) {
      st.amplitude.push_back(a);
      st.phase.push_back(kTwoPi * rng.Uniform());
      a *= rho;
    }
    st.order_driver = gd.characteristic_hz;
    st.order_driven = gn.characteristic_hz;
    st.mu_driver = c.eccentricity_depth * UniformIn(rng, 0.5, 1.5);
    st.mu_driven = c.eccentricity_depth * UniformIn(rng, 0.5, 1.5);
    st.psi_driver = kTwoPi * rng.Uniform();
    st.psi_driven = kTwoPi * rng.Uniform();
    e.stages_.push_back(std::move(st));
  }

  if (c.fault != PlantFaultKind::kNone) {
    const int g = train.GearIndex(c.faulty_gear);
    if (g < 0) {
      return Error{"plant excitation: faulty_gear '" + c.faulty_gear +
                   "' is not a gear of the train"};
    }
    const GearKinematics& gk = kin->gears[static_cast<std::size_t>(g)];
    DeterministicRng tooth(c.seed, kToothStream);
    e.fault_gear_ = g;
    e.fault_stage_ = gk.stage;
    e.fault_teeth_ = gk.teeth;
    e.fault_shaft_order_ = gk.characteristic_hz;
    e.fault_onset_revs_ = static_cast<double>(tooth.Below(static_cast<std::uint64_t>(gk.teeth))) /
                          static_cast<double>(gk.teeth);
    e.dip_length_ = UniformIn(tooth, sv.dip_length_lo, sv.dip_length_hi);
    const double longest =
        std::max({sv.pulse_length_periods, sv.am_length_periods, sv.dip_length_hi});
    e.window_periods_ = longest;
    if (longest >= static_cast<double>(gk.teeth)) {
      return Error{fmt::format(
          "plant excitation: faulty_gear '{}' has {} teeth, too few for a fault window of {} "
          "mesh periods",
          c.faulty_gear, gk.teeth, longest)};
    }
  }
  return e;
}

void PlantExcitation::ScaleSeverity(double factor) noexcept {
  if (!(factor >= 0.0) || !std::isfinite(factor)) return;
  PlantFaultSeverity& sv = config_.severity;
  sv.pulse_depth_m = std::min(sv.pulse_depth_m * factor, sv.max_pulse_depth_m);
  sv.dip_depth_m = std::min(sv.dip_depth_m * factor, sv.max_dip_depth_m);
  sv.am_depth = std::min(sv.am_depth * factor, sv.max_am_depth);
}

double PlantExcitation::MeshContent(const Stage& st, double input_revs) const noexcept {
  double mesh = 0.0;
  const double cycles = st.mesh_order * input_revs;
  // The cycle count grows large over a long run: reduce it before multiplying by 2 pi h.
  const double frac = cycles - std::floor(cycles);
  for (std::size_t h = 0; h < st.amplitude.size(); ++h) {
    mesh += st.amplitude[h] * std::cos(kTwoPi * static_cast<double>(h + 1) * frac + st.phase[h]);
  }
  const double rd = st.order_driver * input_revs;
  const double rn = st.order_driven * input_revs;
  const double modulation =
      1.0 + st.mu_driver * std::cos(kTwoPi * (rd - std::floor(rd)) + st.psi_driver) +
      st.mu_driven * std::cos(kTwoPi * (rn - std::floor(rn)) + st.psi_driven);
  return modulation * mesh;
}

double PlantExcitation::FaultX(double input_revs) const noexcept {
  double u = fault_shaft_order_ * input_revs - fault_onset_revs_;
  u -= std::floor(u);
  return u * static_cast<double>(fault_teeth_);  // mesh periods since the damaged tooth engaged
}

void PlantExcitation::FaultAt(double x, double& gain, double& pulse) const noexcept {
  const PlantFaultSeverity& sv = config_.severity;
  gain = 1.0;
  pulse = 0.0;
  switch (config_.fault) {
    case PlantFaultKind::kNone:
      break;
    case PlantFaultKind::kTePulse:
      pulse = sv.pulse_depth_m * TaperedWindow(x, sv.pulse_length_periods, sv.pulse_taper);
      break;
    case PlantFaultKind::kMeshAm:
      gain = 1.0 - sv.am_depth * TaperedWindow(x, sv.am_length_periods, sv.am_taper);
      break;
    case PlantFaultKind::kWearDip:
      if (x < dip_length_) {
        pulse = sv.dip_depth_m * 0.5 * (1.0 - std::cos(kTwoPi * x / dip_length_));
      }
      break;
    case PlantFaultKind::kCombined:
      pulse = sv.pulse_depth_m * TaperedWindow(x, sv.pulse_length_periods, sv.pulse_taper);
      gain = 1.0 - sv.am_depth * TaperedWindow(x, sv.am_length_periods, sv.am_taper);
      break;
  }
}

double PlantExcitation::Te(int stage, double input_revs, bool fault_on) const noexcept {
  if (stage < 0 || stage >= stage_count()) return 0.0;
  const double healthy = MeshContent(stages_[static_cast<std::size_t>(stage)], input_revs);
  if (!fault_on || stage != fault_stage_) return healthy;
  double gain = 1.0, pulse = 0.0;
  FaultAt(FaultX(input_revs), gain, pulse);
  return gain * healthy + pulse;
}

double PlantExcitation::FaultDeviation(int stage, double input_revs) const noexcept {
  if (stage != fault_stage_ || fault_stage_ < 0) return 0.0;
  const double x = FaultX(input_revs);
  if (x >= window_periods_) return 0.0;
  double gain = 1.0, pulse = 0.0;
  FaultAt(x, gain, pulse);
  if (gain == 1.0) return pulse;
  const double healthy = MeshContent(stages_[static_cast<std::size_t>(stage)], input_revs);
  return (gain - 1.0) * healthy + pulse;
}

double PlantExcitation::HealthyBandwidthOrder() const noexcept {
  double top = 0.0;
  for (const Stage& st : stages_) {
    top = std::max(top, static_cast<double>(st.amplitude.size()) * st.mesh_order +
                            std::max(st.order_driver, st.order_driven));
  }
  return top;
}

}  // namespace gearpath
