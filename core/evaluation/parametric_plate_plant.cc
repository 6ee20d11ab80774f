#include "core/evaluation/parametric_plate_plant.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/model/lumped_gearbox_model.h"
#include "core/simulation/deterministic_rng.h"

namespace gearpath {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kTwoPi = 2.0 * std::numbers::pi;
constexpr std::uint64_t kPlantStream = 303;
constexpr std::uint64_t kFaultStream = 304;
constexpr double kShaftRadiusM = 0.024;
constexpr double kTruthCutoffHz = 5000.0;
constexpr double kSingleToothStiffness = 14e9;  // c', N/m per m of face width (ISO 6336-1)
constexpr int kProfileHarmonics = 4;

double UniformIn(DeterministicRng& rng, double lo, double hi) {
  return lo + (hi - lo) * rng.Uniform();
}
double LogUniformIn(DeterministicRng& rng, double lo, double hi) {
  return lo * std::pow(hi / lo, rng.Uniform());
}

struct Disc {
  double mass = 0.0;
  double inertia = 0.0;
};
Disc GearDisc(const GearboxParameters& g, int teeth) {
  const double r = 0.5 * g.module_m * teeth;
  Disc d;
  d.mass = g.density_kg_per_m3 * kPi * r * r * g.face_width_m;
  d.inertia = 0.5 * d.mass * r * r;
  return d;
}

GearEccentricity DrawEccentricity(DeterministicRng& rng) {
  GearEccentricity e;
  e.runout_m = UniformIn(rng, 2e-6, 8e-6);
  e.runout_phase = kTwoPi * rng.Uniform();
  e.wobble = UniformIn(rng, 0.01, 0.03);
  e.wobble_phase = kTwoPi * rng.Uniform();
  return e;
}

}  // namespace

Result<ParametricPlatePlant> DrawParametricPlatePlant(const GearTrain& train, bool include_m1,
                                                      std::uint64_t seed) {
  Result<TrainKinematics> kin = train.Kinematics(1.0);
  if (!kin) return Error{"parametric plate: train: " + kin.error()};
  const int shafts = static_cast<int>(train.shafts.size());
  if (static_cast<int>(train.bearings.size()) != shafts) {
    return Error{"parametric plate: the train needs exactly one bearing per shaft"};
  }
  ParametricPlatePlant plant;
  std::vector<int> rotor_of_shaft(static_cast<std::size_t>(shafts), -1);
  for (int b = 0; b < shafts; ++b) {
    const int shaft = train.ShaftIndex(train.bearings[static_cast<std::size_t>(b)].shaft);
    if (shaft < 0 || rotor_of_shaft[static_cast<std::size_t>(shaft)] >= 0) {
      return Error{"parametric plate: the train needs exactly one bearing per shaft"};
    }
    rotor_of_shaft[static_cast<std::size_t>(shaft)] = b;
    plant.shaft_of_rotor.push_back(shaft);
  }
  if (plant.shaft_of_rotor.front() != 0 || plant.shaft_of_rotor.back() != shafts - 1) {
    return Error{"parametric plate: bearing 1 must carry the input shaft, the last the output"};
  }
  const GearboxParameters geometry = Table1Parameters();
  DeterministicRng rng(seed, kPlantStream);
  ParametricGearboxParameters p;

  // Rotors: rotation signs by propagation along the stages.
  std::vector<int> sign(static_cast<std::size_t>(shafts), 0);
  sign[0] = 1;
  for (int pass = 0; pass < shafts; ++pass) {
    for (const StageSpec& st : train.stages) {
      const int a = train.ShaftOfGear(st.driver), b = train.ShaftOfGear(st.driven);
      if (sign[static_cast<std::size_t>(a)] != 0) sign[static_cast<std::size_t>(b)] = -sign[static_cast<std::size_t>(a)];
    }
  }
  for (int r = 0; r < shafts; ++r) {
    const int shaft = plant.shaft_of_rotor[static_cast<std::size_t>(r)];
    ShaftRotor rot;
    const double shaft_mass = UniformIn(rng, 1.5, 3.0);
    rot.mass_kg = shaft_mass;
    rot.inertia_kg_m2 = 0.5 * shaft_mass * kShaftRadiusM * kShaftRadiusM;
    for (const std::string& gname : train.shafts[static_cast<std::size_t>(shaft)].gears) {
      const Disc d = GearDisc(geometry, train.gears[static_cast<std::size_t>(train.GearIndex(gname))].teeth);
      rot.mass_kg += d.mass;
      rot.inertia_kg_m2 += d.inertia;
    }
    rot.bearing_stiffness_n_per_m = LogUniformIn(rng, 1e8, 4e8);
    rot.bearing_damping_ns_per_m = UniformIn(rng, 500.0, 2000.0);
    rot.revs_per_input_rev = kin->shafts[static_cast<std::size_t>(shaft)].rotation_hz;
    rot.rotation_sign = sign[static_cast<std::size_t>(shaft)];
    if (rot.rotation_sign == 0) return Error{"parametric plate: a shaft is not driven"};
    p.shafts.push_back(rot);
  }
  p.motor_stiffness_nm_per_rad = LogUniformIn(rng, 1e4, 4e4);
  p.motor_damping_nms_per_rad = UniformIn(rng, 0.5, 2.0);
  p.load_torque_nm = UniformIn(rng, 40.0, 90.0);
  p.load_damping_nms_per_rad = UniformIn(rng, 0.05, 0.25);

  // Meshes.
  const double alpha = geometry.pressure_angle_deg * kPi / 180.0;
  for (const StageSpec& st : train.stages) {
    const int za = train.gears[static_cast<std::size_t>(train.GearIndex(st.driver))].teeth;
    const int zb = train.gears[static_cast<std::size_t>(train.GearIndex(st.driven))].teeth;
    MeshStage ms;
    ms.driver_shaft = rotor_of_shaft[static_cast<std::size_t>(train.ShaftOfGear(st.driver))];
    ms.driven_shaft = rotor_of_shaft[static_cast<std::size_t>(train.ShaftOfGear(st.driven))];
    ms.driver_base_radius_m = 0.5 * geometry.module_m * za * std::cos(alpha);
    ms.driven_base_radius_m = 0.5 * geometry.module_m * zb * std::cos(alpha);
    ToothMeshParameters& m = ms.mesh;
    m.z_driver = za;
    m.z_driven = zb;
    m.contact_ratio = std::clamp(StandardContactRatio(za, zb, geometry.pressure_angle_deg,
                                                      geometry.addendum_coefficient) *
                                     UniformIn(rng, 0.92, 1.02),
                                 1.4, 1.8);
    m.ramp_periods = UniformIn(rng, 0.06, 0.12);
    m.crown = UniformIn(rng, 0.15, 0.3);
    m.base_pitch_m = kPi * geometry.module_m * std::cos(alpha);
    const double mean_target = kSingleToothStiffness * (0.75 * m.contact_ratio + 0.25) *
                               geometry.face_width_m * UniformIn(rng, 0.85, 1.15);
    m.pair_stiffness_n_per_m = 1.0;
    Result<ToothMesh> unit = ToothMesh::Create(m);
    if (!unit) return Error{"parametric plate: " + unit.error()};
    m.pair_stiffness_n_per_m = mean_target / unit->mean_stiffness();
    double amplitude = 0.5e-6 * UniformIn(rng, 0.6, 1.4);
    const double decay = UniformIn(rng, 0.3, 0.5);
    for (int h = 0; h < kProfileHarmonics; ++h) {
      m.profile_amplitude_m.push_back(amplitude);
      m.profile_phase.push_back(kTwoPi * rng.Uniform());
      amplitude *= decay;
    }
    m.driver = DrawEccentricity(rng);
    m.driven = DrawEccentricity(rng);
    m.mesh_phase = rng.Uniform();
    m.driver_tooth_offset = static_cast<int>(rng.Below(static_cast<std::uint64_t>(za)));
    m.driven_tooth_offset = static_cast<int>(rng.Below(static_cast<std::uint64_t>(zb)));
    const ShaftRotor& ra = p.shafts[static_cast<std::size_t>(ms.driver_shaft)];
    const ShaftRotor& rb = p.shafts[static_cast<std::size_t>(ms.driven_shaft)];
    const double ma = ra.inertia_kg_m2 / (ms.driver_base_radius_m * ms.driver_base_radius_m);
    const double mb = rb.inertia_kg_m2 / (ms.driven_base_radius_m * ms.driven_base_radius_m);
    ms.damping_ns_per_m = 2.0 * UniformIn(rng, 0.03, 0.08) * std::sqrt(mean_target * ma * mb / (ma + mb));
    p.stages.push_back(std::move(ms));
  }

  // Plate (truth) and its points.
  PlateGeometry plate;
  plate.length_m = UniformIn(rng, 0.5, 0.7);
  plate.width_m = plate.length_m * UniformIn(rng, 0.6, 0.85);
  plate.thickness_m = UniformIn(rng, 0.012, 0.020);
  std::vector<PlateMode> modes = EnumeratePlateModes(plate, kTruthCutoffHz);
  for (PlateMode& m : modes) m.damping_ratio = UniformIn(rng, 0.01, 0.03);
  std::vector<PlatePoint> points;
  for (int i = 0; i < shafts; ++i) {
    const double spread = 0.2 + 0.6 * static_cast<double>(i) / static_cast<double>(shafts - 1);
    points.push_back({plate.length_m * (spread + UniformIn(rng, -0.05, 0.05)),
                      plate.width_m * UniformIn(rng, 0.35, 0.65)});
  }
  {
    const double x = plate.length_m * UniformIn(rng, 0.15, 0.85);
    const double y = rng.Uniform() < 0.5 ? UniformIn(rng, 0.1, 0.2) : UniformIn(rng, 0.8, 0.9);
    points.push_back({x, plate.width_m * y});
  }
  Result<PlateHousing> truth_plate = PlateHousing::Create(plate, modes, points);
  if (!truth_plate) return Error{"parametric plate: " + truth_plate.error()};
  p.plate = std::move(truth_plate).value();

  // The daemon's model of the plate.
  PlateGeometry model = plate;
  model.thickness_m *= UniformIn(rng, 0.97, 1.03);
  model.youngs_modulus_pa *= UniformIn(rng, 0.95, 1.05);
  plant.model_cutoff_hz = UniformIn(rng, 2200.0, 2800.0);
  std::vector<PlateMode> model_modes = EnumeratePlateModes(model, plant.model_cutoff_hz);
  for (PlateMode& m : model_modes) {
    const auto it = std::find_if(modes.begin(), modes.end(), [&m](const PlateMode& t) {
      return t.m == m.m && t.n == m.n;
    });
    if (it == modes.end()) return Error{"parametric plate: a model mode has no true mode"};
    m.damping_ratio = it->damping_ratio * UniformIn(rng, 0.7, 1.3);
  }
  Result<PlateHousing> model_plate = PlateHousing::Create(model, model_modes, points);
  if (!model_plate) return Error{"parametric plate: model: " + model_plate.error()};
  plant.model_plate = std::move(model_plate).value();

  Result<ParametricGearbox> gearbox = ParametricGearbox::Create(std::move(p));
  if (!gearbox) return Error{"parametric plate: " + gearbox.error()};
  plant.truth = std::make_shared<const ParametricGearbox>(std::move(gearbox).value());
  for (int i = 0; i < shafts; ++i) plant.channel_points.push_back(i);
  if (include_m1) plant.channel_points.push_back(shafts);
  return plant;
}

FrfSet ParametricPlateFrfSet(const ParametricPlatePlant& plant, const GearTrain& train,
                             const std::vector<ChannelInfo>& channels,
                             const Eigen::VectorXd& grid_hz) {
  FrfSet set;
  set.description = fmt::format(
      "evaluation: plate housing model (modes up to {:.0f} Hz, thickness and modulus off by a "
      "few percent, damping off by up to 30 %)",
      plant.model_cutoff_hz);
  set.quantity = FrfQuantity::kAccelerance;
  set.unit = "m/s^2/N";
  set.decoupling = "model";
  std::vector<int> seats;
  for (std::size_t r = 0; r < plant.shaft_of_rotor.size(); ++r) {
    const BearingSpec& bearing = train.bearings[r];
    set.paths.push_back({bearing.name + "x", bearing.name + ", " + bearing.shaft + " shaft", "x",
                         train.GearsNearBearing(static_cast<int>(r))});
    seats.push_back(static_cast<int>(r));
  }
  for (const ChannelInfo& c : channels) set.channels.push_back({c.sensor, "x"});
  set.decoupled.frequency_hz = grid_hz;
  set.decoupled.at.reserve(static_cast<std::size_t>(grid_hz.size()));
  for (Eigen::Index k = 0; k < grid_hz.size(); ++k) {
    set.decoupled.at.push_back(
        plant.model_plate.Accelerance(grid_hz[k], plant.channel_points, seats));
  }
  return set;
}

Result<ToothFault> DrawToothFault(const ParametricPlatePlant& plant, const GearTrain& train,
                                  PlantFaultKind kind, const std::string& gear,
                                  std::uint64_t seed) {
  ToothFault fault;
  fault.kind = kind;
  PlantFaultSeverity& sv = fault.severity;
  sv.pulse_depth_m = 1.0e-6;
  sv.pulse_taper = 0.08;
  sv.am_depth = 0.15;
  sv.dip_depth_m = 1.0e-6;
  sv.max_pulse_depth_m = 10.0e-6;
  sv.max_am_depth = 0.6;
  sv.max_dip_depth_m = 5.0e-6;
  if (kind == PlantFaultKind::kNone) return fault;
  const int g = train.GearIndex(gear);
  if (g < 0) return Error{"parametric plate: faulty gear '" + gear + "' is not a gear of the train"};
  int stage = -1;
  for (std::size_t s = 0; s < train.stages.size(); ++s) {
    if (train.stages[s].driver == gear || train.stages[s].driven == gear) stage = static_cast<int>(s);
  }
  if (stage < 0) return Error{"parametric plate: gear '" + gear + "' meshes in no stage"};
  fault.stage = stage;
  fault.on_driver = train.stages[static_cast<std::size_t>(stage)].driver == gear;
  const ToothMesh& mesh = plant.truth->meshes()[static_cast<std::size_t>(stage)];
  const int z = fault.on_driver ? mesh.parameters().z_driver : mesh.parameters().z_driven;
  DeterministicRng rng(seed, kFaultStream);
  fault.tooth = static_cast<int>(rng.Below(static_cast<std::uint64_t>(z)));
  sv.pulse_length_periods = UniformIn(rng, 0.4, 0.8);
  fault.spall_start =
      UniformIn(rng, 0.0, mesh.parameters().contact_ratio - sv.pulse_length_periods);
  fault.wear_length = UniformIn(rng, 2.0, 3.0);
  sv.dip_length_lo = sv.dip_length_hi = fault.wear_length;
  if (Status st = mesh.CheckFault(fault); !st) return Error{"parametric plate: " + st.error()};
  return fault;
}

}  // namespace gearpath
