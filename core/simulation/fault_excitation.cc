#include "core/simulation/fault_excitation.h"

#include <cmath>
#include <numbers>
#include <string>

#include "core/simulation/deterministic_rng.h"

namespace gearpath {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

// Independent random streams derived from the one seed.
constexpr std::uint64_t kPhaseStream = 1;
constexpr std::uint64_t kToothStream = 2;

// Tapered box on [0, length): cosine ramps of taper * length at both ends, 1 in between.
double TaperedBox(double u, double length, double taper) noexcept {
  if (u < 0.0 || u >= length) return 0.0;
  const double ramp = taper * length;
  if (u < ramp) return 0.5 * (1.0 - std::cos(std::numbers::pi * u / ramp));
  if (u > length - ramp) return 0.5 * (1.0 - std::cos(std::numbers::pi * (length - u) / ramp));
  return 1.0;
}

}  // namespace

const char* FaultTypeName(FaultType type) noexcept {
  switch (type) {
    case FaultType::kNone:
      return "none";
    case FaultType::kChippedTooth:
      return "chipped";
    case FaultType::kLocalizedWear:
      return "wear";
    case FaultType::kToothFracture:
      return "fracture";
  }
  return "unknown";
}

std::optional<FaultType> ParseFaultType(std::string_view name) noexcept {
  for (FaultType t : {FaultType::kNone, FaultType::kChippedTooth, FaultType::kLocalizedWear,
                      FaultType::kToothFracture}) {
    if (name == FaultTypeName(t)) return t;
  }
  return std::nullopt;
}

FaultShape FaultShapeOf(FaultType type) noexcept {
  switch (type) {
    case FaultType::kNone:
      return {0.0, 0.0, 0.5};
    case FaultType::kChippedTooth:
      return {0.5, 0.5, 0.35};
    case FaultType::kLocalizedWear:
      return {0.25, 1.0, 0.5};
    case FaultType::kToothFracture:
      return {1.0, 1.0, 0.2};
  }
  return {0.0, 0.0, 0.5};
}

Result<FaultExcitation> FaultExcitation::Create(const GearTrain& train, double input_hz,
                                                const GearFault& fault,
                                                const ExcitationParameters& parameters) {
  Result<TrainKinematics> kin = train.Kinematics(input_hz);
  if (!kin.ok()) return Error{"fault excitation: " + kin.error()};
  const Result<std::int64_t> revolutions = train.InputRevolutionsPerCommonPeriod();
  if (!revolutions.ok()) return Error{"fault excitation: " + revolutions.error()};
  const ExcitationParameters& p = parameters;
  for (std::size_t h = 0; h < p.mesh_harmonic_amplitude_m.size(); ++h) {
    const double a = p.mesh_harmonic_amplitude_m[h];
    if (!(a >= 0.0) || !std::isfinite(a)) {
      return Error{"fault excitation: mesh_harmonic_amplitude_m[" + std::to_string(h) +
                   "] must be finite and >= 0, got " + std::to_string(a)};
    }
  }
  if (!(p.shaft_modulation_depth >= 0.0 && p.shaft_modulation_depth < 0.5)) {
    return Error{"fault excitation: shaft_modulation_depth must be in [0, 0.5), got " +
                 std::to_string(p.shaft_modulation_depth)};
  }
  if (!(p.deflection_scale_m > 0.0) || !std::isfinite(p.deflection_scale_m)) {
    return Error{"fault excitation: deflection_scale_m must be finite and > 0, got " +
                 std::to_string(p.deflection_scale_m)};
  }
  if (p.shape &&
      !(p.shape->depth_factor >= 0.0 && p.shape->length_factor > 0.0 &&
        p.shape->length_factor <= 2.0 && p.shape->taper > 0.0 && p.shape->taper <= 0.5)) {
    return Error{
        "fault excitation: shape must have depth_factor >= 0, length_factor in (0, 2] "
        "and taper in (0, 0.5]"};
  }
  if (!(fault.severity >= 0.0) || !std::isfinite(fault.severity)) {
    return Error{"fault excitation: fault severity must be finite and >= 0, got " +
                 std::to_string(fault.severity)};
  }

  FaultExcitation e;
  e.kinematics_ = std::move(kin).value();
  e.fault_ = fault;
  e.parameters_ = parameters;
  e.common_period_s_ = static_cast<double>(*revolutions) / input_hz;

  DeterministicRng phases(p.seed, kPhaseStream);
  for (std::size_t s = 0; s < train.stages.size(); ++s) {
    const MeshKinematics& m = e.kinematics_.meshes[s];
    Stage st;
    st.mesh_hz = m.mesh_hz;
    const int gd = train.GearIndex(m.driver);
    const int gn = train.GearIndex(m.driven);
    st.driver_shaft_hz = e.kinematics_.gears[static_cast<std::size_t>(gd)].characteristic_hz;
    st.driven_shaft_hz = e.kinematics_.gears[static_cast<std::size_t>(gn)].characteristic_hz;
    for (std::size_t h = 0; h < p.mesh_harmonic_amplitude_m.size(); ++h) {
      st.harmonic_phase.push_back(kTwoPi * phases.Uniform());
    }
    st.driver_phase = kTwoPi * phases.Uniform();
    st.driven_phase = kTwoPi * phases.Uniform();
    e.stages_.push_back(std::move(st));
  }

  if (fault.type != FaultType::kNone) {
    const int g = train.GearIndex(fault.gear);
    if (g < 0) {
      return Error{"fault excitation: fault gear '" + fault.gear + "' is not a gear of the train"};
    }
    const GearKinematics& gk = e.kinematics_.gears[static_cast<std::size_t>(g)];
    const MeshKinematics& mesh = e.kinematics_.meshes[static_cast<std::size_t>(gk.stage)];
    const FaultShape shape = p.shape.value_or(FaultShapeOf(fault.type));
    const double mesh_period = 1.0 / mesh.mesh_hz;
    e.fault_period_s_ = 1.0 / gk.characteristic_hz;  // = teeth * mesh period
    e.fault_length_s_ = shape.length_factor * mesh.contact_ratio * mesh_period;
    if (e.fault_length_s_ >= e.fault_period_s_) {
      return Error{"fault excitation: gear '" + fault.gear + "' has too few teeth (" +
                   std::to_string(gk.teeth) +
                   ") for a once-per-revolution fault pulse shorter than a revolution"};
    }
    DeterministicRng tooth(p.seed, kToothStream);
    const auto damaged_tooth =
        static_cast<double>(tooth.Below(static_cast<std::uint64_t>(gk.teeth)));
    e.fault_onset_s_ = damaged_tooth * mesh_period;
    e.fault_depth_m_ = shape.depth_factor * p.deflection_scale_m * fault.severity;
    e.fault_taper_ = shape.taper;
    e.fault_stage_ = e.fault_depth_m_ > 0.0 ? gk.stage : -1;
    if (e.fault_stage_ < 0) {
      e.fault_period_s_ = e.fault_onset_s_ = e.fault_length_s_ = 0.0;
    }
  }
  return e;
}

double FaultExcitation::Healthy(int stage, double t_s) const noexcept {
  if (stage < 0 || stage >= stage_count()) return 0.0;
  const Stage& st = stages_[static_cast<std::size_t>(stage)];
  const std::vector<double>& amplitude = parameters_.mesh_harmonic_amplitude_m;
  double mesh = 0.0;
  for (std::size_t h = 0; h < amplitude.size(); ++h) {
    const double order = static_cast<double>(h + 1);
    mesh += amplitude[h] * std::cos(kTwoPi * order * st.mesh_hz * t_s + st.harmonic_phase[h]);
  }
  const double mu = parameters_.shaft_modulation_depth;
  const double modulation = 1.0 +
                            mu * std::cos(kTwoPi * st.driver_shaft_hz * t_s + st.driver_phase) +
                            mu * std::cos(kTwoPi * st.driven_shaft_hz * t_s + st.driven_phase);
  return modulation * mesh;
}

double FaultExcitation::Fault(int stage, double t_s) const noexcept {
  if (stage != fault_stage_ || fault_stage_ < 0) return 0.0;
  double u = t_s - fault_onset_s_;
  u -= std::floor(u / fault_period_s_) * fault_period_s_;  // into [0, period)
  return fault_depth_m_ * TaperedBox(u, fault_length_s_, fault_taper_);
}

void FaultExcitation::Sample(int stage, double t0_s, double sample_rate_hz,
                             std::span<double> out) const noexcept {
  for (std::size_t n = 0; n < out.size(); ++n) {
    out[n] = Total(stage, t0_s + static_cast<double>(n) / sample_rate_hz);
  }
}

}  // namespace gearpath
