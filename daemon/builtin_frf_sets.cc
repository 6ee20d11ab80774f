// The built-in FRF sets (`"frf_set": "builtin:<name>"`), computed at start-up.
//
// builtin:table1: the seed's Table-1 two-stage gearbox (core/model/lumped_gearbox_model.h,
// Table1Parameters; gear train GearTrain::Table1), decoupled at the bearing seats by Eq. 22
// (core/simulation/model_frf_set.h): response channels p1, p2, p3 (axis x, the model's line of
// action), paths B1x, B2x, B3x with their nearest gears. Frequency grid: the bins 1..4096 of an
// 8192-sample block at 8 kHz (0.977 Hz .. 4 kHz), so the default block maps onto it exactly;
// other block lengths are interpolated by the pipeline. No DC bin: decoupling is singular
// there (the accelerance vanishes).
#include <fmt/format.h>

#include "core/model/gear_train.h"
#include "core/model/lumped_gearbox_model.h"
#include "core/simulation/model_frf_set.h"
#include "daemon/machine_setup_builder.h"

namespace gearpath::daemon {

Result<FrfSet> BuiltinFrfSet(const std::string& name) {
  if (name != "table1") {
    return Error{fmt::format("unknown built-in FRF set \"{}\" (known: table1)", name)};
  }
  auto model = LumpedGearboxModel::Create(Table1Parameters());
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
  return MakeModelFrfSet(model.value(), GearTrain::Table1(), f, options);
}

}  // namespace gearpath::daemon
