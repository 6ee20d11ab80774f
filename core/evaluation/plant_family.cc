#include "core/evaluation/plant_family.h"

#include <fmt/format.h>

#include <cmath>
#include <numbers>
#include <string>

#include "core/evaluation/parametric_plate_plant.h"
#include "core/simulation/deterministic_rng.h"
#include "core/simulation/model_frf_set.h"

namespace gearpath {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;
constexpr std::uint64_t kPerturbStream = 301;
constexpr std::uint64_t kModalStream = 302;
constexpr double kFrfSampleRate = 8000.0;
constexpr Eigen::Index kFrfBlock = 8192;

double UniformIn(DeterministicRng& rng, double lo, double hi) {
  return lo + (hi - lo) * rng.Uniform();
}

std::vector<ChannelInfo> ChannelsFor(int seats, bool include_housing) {
  std::vector<ChannelInfo> channels;
  for (int s = 0; s < seats; ++s) {
    channels.push_back({"p" + std::to_string(s + 1), Axis::kX, "m/s^2", 0.0});
  }
  if (include_housing) channels.push_back({"m1", Axis::kX, "m/s^2", 0.0});
  return channels;
}

// Eq. 22 rows (seats), with the Eq. 24 row (m1) stacked under them when asked.
Result<FrfSet> NominalFrfSet(const LumpedGearboxModel& model, const GearTrain& train,
                             bool include_housing) {
  const Eigen::VectorXd grid = EvaluationFrfGrid();
  ModelFrfSetOptions options;
  options.decoupling = ModelFrfDecoupling::kVirtualEq22;
  options.description = "evaluation: nominal lumped model, Eq. 22";
  Result<FrfSet> pp = MakeModelFrfSet(model, train, grid, options);
  if (!pp || !include_housing) return pp;
  options.decoupling = ModelFrfDecoupling::kVirtualEq24;
  Result<FrfSet> mp = MakeModelFrfSet(model, train, grid, options);
  if (!mp) return mp;
  FrfSet set = std::move(pp).value();
  set.description = "evaluation: nominal lumped model, Eq. 22 (p) + Eq. 24 (m1)";
  set.decoupling = "eq22+eq24";
  set.channels.push_back(mp->channels.front());
  for (std::size_t k = 0; k < set.decoupled.at.size(); ++k) {
    Eigen::MatrixXcd& h = set.decoupled.at[k];
    const Eigen::MatrixXcd& m = mp->decoupled.at[k];
    Eigen::MatrixXcd stacked(h.rows() + m.rows(), h.cols());
    stacked << h, m;
    h = std::move(stacked);
  }
  return set;
}

Result<Plant> MakeLumpedPlant(const PlantSpec& spec, const GearTrain& train) {
  const GearboxParameters nominal = NominalParameters(train);
  Result<LumpedGearboxModel> nominal_model = LumpedGearboxModel::Create(nominal);
  if (!nominal_model) return Error{"plant: nominal model: " + nominal_model.error()};
  const bool torsional = spec.family == PlantFamily::kLumpedTorsional;
  Result<LumpedGearboxModel> plant_model =
      LumpedGearboxModel::Create(PerturbedParameters(nominal, torsional, spec.seed));
  if (!plant_model) return Error{"plant: perturbed model: " + plant_model.error()};
  const bool housing = spec.channels == ChannelSet::kSeatsAndHousing;
  Result<FrfSet> frf = NominalFrfSet(*nominal_model, train, housing);
  if (!frf) return Error{"plant: " + frf.error()};
  Plant plant;
  plant.spec = spec;
  plant.train = train;
  plant.channels = ChannelsFor(nominal_model->rotor_count(), housing);
  plant.model_frf = std::move(frf).value();
  plant.dynamics = std::make_shared<LumpedPlantDynamics>(std::move(plant_model).value(), housing);
  return plant;
}

Result<Plant> MakeModalPlant(const PlantSpec& spec, const GearTrain& train) {
  const bool housing = spec.channels == ChannelSet::kSeatsAndHousing;
  auto dynamics = std::make_shared<ModalHousingDynamics>(
      ModalHousingDynamics::Random(train, housing, spec.seed));
  const int seats = static_cast<int>(train.bearings.size());
  Plant plant;
  plant.spec = spec;
  plant.train = train;
  plant.channels = ChannelsFor(seats, housing);
  FrfSet& set = plant.model_frf;
  set.description = "evaluation: modal housing model (shifted modes)";
  set.quantity = FrfQuantity::kAccelerance;
  set.unit = "m/s^2/N";
  set.decoupling = "model";
  for (int b = 0; b < seats; ++b) {
    const BearingSpec& bearing = train.bearings[static_cast<std::size_t>(b)];
    set.paths.push_back({bearing.name + "x", bearing.name + ", " + bearing.shaft + " shaft", "x",
                         train.GearsNearBearing(b)});
  }
  for (const ChannelInfo& c : plant.channels) set.channels.push_back({c.sensor, "x"});
  set.decoupled.frequency_hz = EvaluationFrfGrid();
  for (Eigen::Index k = 0; k < set.decoupled.frequency_hz.size(); ++k) {
    set.decoupled.at.push_back(
        dynamics->Accelerance(dynamics->model_modes(), set.decoupled.frequency_hz[k]));
  }
  plant.dynamics = std::move(dynamics);
  return plant;
}

Result<Plant> MakeParametricPlatePlant(const PlantSpec& spec, const GearTrain& train) {
  const bool housing = spec.channels == ChannelSet::kSeatsAndHousing;
  Result<ParametricPlatePlant> truth = DrawParametricPlatePlant(train, housing, spec.seed);
  if (!truth) return Error{truth.error()};
  Plant plant;
  plant.spec = spec;
  plant.train = train;
  plant.channels = ChannelsFor(static_cast<int>(train.bearings.size()), housing);
  plant.model_frf = ParametricPlateFrfSet(*truth, train, plant.channels, EvaluationFrfGrid());
  plant.parametric = std::make_shared<const ParametricPlatePlant>(std::move(truth).value());
  return plant;
}

}  // namespace

std::string_view PlantFamilyName(PlantFamily family) noexcept {
  switch (family) {
    case PlantFamily::kLumpedPerturbed:
      return "lumped_perturbed";
    case PlantFamily::kLumpedTorsional:
      return "lumped_torsional";
    case PlantFamily::kModalHousing:
      return "modal_housing";
    case PlantFamily::kParametricPlate:
      return "parametric_plate";
  }
  return "unknown";
}

std::optional<PlantFamily> ParsePlantFamily(std::string_view name) noexcept {
  for (PlantFamily f : kAllPlantFamilies) {
    if (name == PlantFamilyName(f)) return f;
  }
  return std::nullopt;
}

std::string_view TrainVariantName(TrainVariant variant) noexcept {
  return variant == TrainVariant::kTable1 ? "table1" : "distinct";
}

std::string_view ChannelSetName(ChannelSet set) noexcept {
  return set == ChannelSet::kSeats ? "p" : "p+m";
}

GearTrain MakeTrain(TrainVariant variant) {
  GearTrain train = GearTrain::Table1();
  if (variant == TrainVariant::kDistinct) train.gears[3].teeth = 29;  // G4: 29 teeth
  return train;
}

Eigen::VectorXd EvaluationFrfGrid() {
  Eigen::VectorXd f(kFrfBlock / 2);
  for (Eigen::Index k = 0; k < f.size(); ++k) {
    f[k] = static_cast<double>(k + 1) * kFrfSampleRate / static_cast<double>(kFrfBlock);
  }
  return f;
}

GearboxParameters NominalParameters(const GearTrain& train) {
  GearboxParameters p = Table1Parameters();
  p.stages.clear();
  for (const StageSpec& st : train.stages) {
    p.stages.push_back({train.gears[static_cast<std::size_t>(train.GearIndex(st.driver))].teeth,
                        train.gears[static_cast<std::size_t>(train.GearIndex(st.driven))].teeth,
                        std::nullopt});
  }
  const std::size_t rotors = p.stages.size() + 1;
  auto resize = [rotors](std::vector<double>& v) { v.resize(rotors, v.empty() ? 0.0 : v.back()); };
  resize(p.bearing_stiffness_n_per_m);
  resize(p.bearing_damping_ns_per_m);
  resize(p.seat_mass_kg);
  resize(p.seat_stiffness_n_per_m);
  resize(p.seat_damping_ns_per_m);
  return p;
}

GearboxParameters PerturbedParameters(const GearboxParameters& nominal, bool torsional,
                                      std::uint64_t seed) {
  DeterministicRng rng(seed, kPerturbStream);
  auto factor = [&rng] { return UniformIn(rng, 0.7, 1.3); };
  GearboxParameters p = nominal;
  // Mesh stiffnesses: the nominal (ISO 6336) value of each stage, scaled.
  Result<LumpedGearboxModel> model = LumpedGearboxModel::Create(nominal);
  for (std::size_t s = 0; s < p.stages.size(); ++s) {
    const double k = model ? model->meshes()[s].stiffness_n_per_m
                           : p.stages[s].mesh_stiffness_n_per_m.value_or(3e8);
    p.stages[s].mesh_stiffness_n_per_m = k * factor();
  }
  for (std::vector<double>* v :
       {&p.bearing_stiffness_n_per_m, &p.bearing_damping_ns_per_m, &p.seat_mass_kg,
        &p.seat_stiffness_n_per_m, &p.seat_damping_ns_per_m}) {
    for (double& x : *v) x *= factor();
  }
  p.housing_mass_kg *= factor();
  p.ground_stiffness_n_per_m *= factor();
  p.ground_damping_ns_per_m *= factor();
  p.density_kg_per_m3 *= factor();
  p.mesh_damping_ratio *= factor();
  if (torsional) {
    p.torsional_stiffness_nm_per_rad.assign(p.stages.size() + 1, 0.0);
    p.torsional_stiffness_nm_per_rad.front() = UniformIn(rng, 2e3, 2e4);
    p.torsional_stiffness_nm_per_rad.back() = UniformIn(rng, 2e3, 2e4);
    p.mesh_damping_ratio = UniformIn(rng, 0.05, 0.10);
  }
  return p;
}

Result<FrfMatrix> LumpedPlantDynamics::TeTransfer(const Eigen::VectorXd& frequency_hz) const {
  Result<TransmissionErrorTransfer> t = model_.TransmissionErrorTransferOnGrid(frequency_hz);
  if (!t) return Error{"lumped plant: " + t.error()};
  FrfMatrix out;
  out.frequency_hz = frequency_hz;
  out.at.reserve(static_cast<std::size_t>(frequency_hz.size()));
  for (std::size_t k = 0; k < t->seat_acceleration.at.size(); ++k) {
    if (!include_housing_) {
      out.at.push_back(t->seat_acceleration.at[k]);
      continue;
    }
    const Eigen::MatrixXcd& seat = t->seat_acceleration.at[k];
    Eigen::MatrixXcd h(seat.rows() + 1, seat.cols());
    h << seat, t->housing_acceleration.at[k];
    out.at.push_back(std::move(h));
  }
  return out;
}

ModalHousingDynamics ModalHousingDynamics::Random(const GearTrain& train, bool include_housing,
                                                  std::uint64_t seed) {
  DeterministicRng rng(seed, kModalStream);
  ModalHousingDynamics d;
  d.seats_ = static_cast<int>(train.bearings.size());
  d.channels_ = d.seats_ + (include_housing ? 1 : 0);
  const int points = d.seats_ + 1;  // shapes always carry m1 so both channel sets share modes
  const int modes = 6 + static_cast<int>(rng.Below(7));  // 6..12
  for (int r = 0; r < modes; ++r) {
    HousingMode m;
    m.frequency_hz = 300.0 * std::pow(3500.0 / 300.0, rng.Uniform());
    m.damping_ratio = UniformIn(rng, 0.01, 0.04);
    const double modal_mass = UniformIn(rng, 5.0, 30.0);
    m.shape.resize(points);
    for (int p = 0; p < points; ++p) m.shape[p] = rng.Gaussian() / std::sqrt(modal_mass);
    d.modes_.push_back(m);
    HousingMode shifted = m;
    shifted.frequency_hz *= 1.0 + UniformIn(rng, -0.05, 0.05);
    shifted.damping_ratio *= 1.0 + UniformIn(rng, -0.3, 0.3);
    d.model_modes_.push_back(std::move(shifted));
  }
  Result<LumpedGearboxModel> nominal = LumpedGearboxModel::Create(NominalParameters(train));
  for (std::size_t s = 0; s < train.stages.size(); ++s) {
    MeshSource src;
    const double k = nominal ? nominal->meshes()[s].stiffness_n_per_m : 3.4e8;
    src.stiffness_n_per_m = k * UniformIn(rng, 0.8, 1.2);
    src.rotor_hz = UniformIn(rng, 1200.0, 3000.0);
    src.rotor_damping = 0.05;
    src.lever = UniformIn(rng, 0.35, 0.65);
    d.sources_.push_back(src);
  }
  return d;
}

Eigen::MatrixXcd ModalHousingDynamics::Accelerance(const std::vector<HousingMode>& modes,
                                                   double frequency_hz) const {
  const double w = kTwoPi * frequency_hz;
  Eigen::MatrixXcd h = Eigen::MatrixXcd::Zero(channels_, seats_);
  for (const HousingMode& m : modes) {
    const double wr = kTwoPi * m.frequency_hz;
    const Complex g = -w * w / Complex(wr * wr - w * w, 2.0 * m.damping_ratio * wr * w);
    for (int c = 0; c < channels_; ++c) {
      for (int b = 0; b < seats_; ++b) h(c, b) += g * m.shape[c] * m.shape[b];
    }
  }
  return h;
}

Eigen::MatrixXcd ModalHousingDynamics::ForceTransfer(double frequency_hz) const {
  Eigen::MatrixXcd g = Eigen::MatrixXcd::Zero(seats_, stage_count());
  for (int s = 0; s < stage_count(); ++s) {
    const MeshSource& src = sources_[static_cast<std::size_t>(s)];
    const double x = frequency_hz / src.rotor_hz;
    const Complex rotor = 1.0 / Complex(1.0 - x * x, 2.0 * src.rotor_damping * x);
    const Complex force = src.stiffness_n_per_m * rotor;
    g(s, s) += src.lever * force;
    if (s + 1 < seats_) g(s + 1, s) -= (1.0 - src.lever) * force;
  }
  return g;
}

Result<FrfMatrix> ModalHousingDynamics::TeTransfer(const Eigen::VectorXd& frequency_hz) const {
  FrfMatrix out;
  out.frequency_hz = frequency_hz;
  out.at.reserve(static_cast<std::size_t>(frequency_hz.size()));
  for (Eigen::Index k = 0; k < frequency_hz.size(); ++k) {
    const double f = frequency_hz[k];
    if (!std::isfinite(f) || f < 0.0 || (k > 0 && f <= frequency_hz[k - 1])) {
      return Error{fmt::format(
          "modal housing: frequency_hz[{}] = {} must be finite, >= 0 and increasing", k, f)};
    }
    out.at.push_back(Accelerance(modes_, f) * ForceTransfer(f));
  }
  return out;
}

Result<Plant> MakePlant(const PlantSpec& spec) {
  const GearTrain train = MakeTrain(spec.variant);
  if (spec.family == PlantFamily::kModalHousing) return MakeModalPlant(spec, train);
  if (spec.family == PlantFamily::kParametricPlate) return MakeParametricPlatePlant(spec, train);
  return MakeLumpedPlant(spec, train);
}

}  // namespace gearpath
