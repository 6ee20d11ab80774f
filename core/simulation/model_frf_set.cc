#include "core/simulation/model_frf_set.h"

#include <cmath>
#include <string>
#include <utility>

#include "core/frf/virtual_decoupling.h"
#include "core/simulation/gearbox_simulator.h"

namespace gearpath {

Result<FrfSet> MakeModelFrfSet(const LumpedGearboxModel& model, const GearTrain& train,
                               const Eigen::VectorXd& frequency_hz,
                               const ModelFrfSetOptions& options) {
  if (Status st = CheckTrainMatchesModel(model, train); !st) {
    return Error{"model FRF set: " + st.error()};
  }
  if (frequency_hz.size() == 0) return Error{"model FRF set: frequency grid is empty"};
  for (Eigen::Index k = 0; k < frequency_hz.size(); ++k) {
    const double f = frequency_hz(k);
    if (!std::isfinite(f) || f <= 0.0 || (k > 0 && f <= frequency_hz(k - 1))) {
      return Error{"model FRF set: frequency_hz[" + std::to_string(k) + "] = " + std::to_string(f) +
                   " Hz: the grid must be finite, > 0 and strictly increasing"};
    }
  }
  const int seats = model.rotor_count();

  FrfSet set;
  set.description = options.description;
  set.quantity = FrfQuantity::kAccelerance;
  set.unit = "m/s^2/N";
  for (int b = 0; b < seats; ++b) {
    const BearingSpec& bearing = train.bearings[static_cast<std::size_t>(b)];
    set.paths.push_back({bearing.name + "x", bearing.name + ", " + bearing.shaft + " shaft", "x",
                         train.GearsNearBearing(b)});
  }
  const bool at_seats = options.decoupling == ModelFrfDecoupling::kVirtualEq22 ||
                        options.decoupling == ModelFrfDecoupling::kPhysicalPp;
  if (at_seats) {
    for (int s = 0; s < seats; ++s) set.channels.push_back({"p" + std::to_string(s + 1), "x"});
  } else {
    set.channels.push_back({"m1", "x"});
  }

  const bool virtual_decoupling = options.decoupling == ModelFrfDecoupling::kVirtualEq22 ||
                                  options.decoupling == ModelFrfDecoupling::kVirtualEq24;
  std::optional<CoupledBlocks> blocks;
  if (virtual_decoupling || options.include_coupled) {
    Result<CoupledBlocks> b = model.CoupledBlocksOnGrid(frequency_hz, options.include_ap);
    if (!b.ok()) return Error{"model FRF set: " + b.error()};
    blocks = std::move(b).value();
  }
  switch (options.decoupling) {
    case ModelFrfDecoupling::kVirtualEq22:
    case ModelFrfDecoupling::kVirtualEq24: {
      Result<VirtualDecouplingResult> d = options.decoupling == ModelFrfDecoupling::kVirtualEq22
                                              ? DecoupleAtInterface(*blocks)
                                              : DecoupleAtMeasurementPoints(*blocks);
      if (!d.ok()) return Error{"model FRF set: " + d.error()};
      set.decoupled = std::move(d->decoupled);
      set.decoupling = options.decoupling == ModelFrfDecoupling::kVirtualEq22 ? "eq22" : "eq24";
      break;
    }
    case ModelFrfDecoupling::kPhysicalPp:
    case ModelFrfDecoupling::kPhysicalMp: {
      Result<FrfMatrix> h = options.decoupling == ModelFrfDecoupling::kPhysicalPp
                                ? model.PhysicalDecoupledPp(frequency_hz)
                                : model.PhysicalDecoupledMp(frequency_hz);
      if (!h.ok()) return Error{"model FRF set: " + h.error()};
      set.decoupled = std::move(h).value();
      set.decoupling = "physical";
      break;
    }
  }

  if (options.include_coupled) {
    CoupledSet coupled;
    for (int r = 0; r < seats; ++r) {
      const std::string i = std::to_string(r + 1);
      coupled.active.push_back(
          {"a" + i + "x", "rotor " + train.shafts[static_cast<std::size_t>(r)].name, "x"});
      coupled.passive.push_back({"p" + i + "x", "p" + i, "x"});
    }
    if (blocks->has_measurement_points()) coupled.measurement.push_back({"m1x", "m1", "x"});
    coupled.blocks = std::move(*blocks);
    set.coupled = std::move(coupled);
  }
  return set;
}

Result<FrfSet> MakeTable1FrfSet() {
  Result<LumpedGearboxModel> model = LumpedGearboxModel::Create(Table1Parameters());
  if (!model) return Error{"Table-1 lumped model: " + model.error()};
  constexpr double kSampleRate = 8000.0;
  constexpr Eigen::Index kBlock = 8192;
  Eigen::VectorXd f(kBlock / 2);
  for (Eigen::Index k = 0; k < f.size(); ++k) {
    f[k] = static_cast<double>(k + 1) * kSampleRate / static_cast<double>(kBlock);
  }
  ModelFrfSetOptions options;
  options.decoupling = ModelFrfDecoupling::kVirtualEq22;
  options.description = "builtin:table1 - seed Table-1 lumped gearbox, virtual decoupling Eq. 22";
  return MakeModelFrfSet(*model, GearTrain::Table1(), f, options);
}

}  // namespace gearpath
