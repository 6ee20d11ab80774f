// MakeModelFrfSet: the FrfSet (core/frf/frf_set.h) a vibration engineer would have produced
// for a gearbox described by the lumped model, so the simulated machine can be diagnosed with
// the same daemon, tools and file format as a measured one.
//
// Variants (ModelFrfDecoupling):
//   kVirtualEq22  H_d,pp from the coupled FRFs by virtual decoupling, seed Eq. 22
//                 (core/frf/virtual_decoupling.h); channels = the bearing seats "p1".."pN+1".
//   kVirtualEq24  H_d,mp by Eq. 24; channel = the central housing mass "m1".
//   kPhysicalPp   the housing-alone FRF at the seats (the seed's physical decoupling, Eq. 7).
//   kPhysicalMp   the housing-alone FRF from the seats to "m1".
// Paths (columns) = one bearing force per seat, in the gear train's bearing order: name
// "<bearing>x" (e.g. "B1x"), bearing "<bearing>, <shaft> shaft", direction "x" (the model's
// line of action), gears = the gears on the supported shaft (Table 1: B1 -> {G1},
// B2 -> {G2, G3}, B3 -> {G4}). Channel names match GearboxSimulator's ("p1".., "m1", axis x).
// With include_coupled the set also carries the coupled blocks (a = rotor translations "a1x"..,
// p = seats "p1x".., m = housing "m1x") so that `gearpath decouple` can redo Eq. 22/24.
// Quantity: accelerance in the model's convention (core/model/lumped_gearbox_model.h).
// The train must describe the model (CheckTrainMatchesModel). Configuration-time code.
#pragma once

#include <Eigen/Dense>
#include <string>

#include "core/common/result.h"
#include "core/frf/frf_set.h"
#include "core/model/gear_train.h"
#include "core/model/lumped_gearbox_model.h"

namespace gearpath {

enum class ModelFrfDecoupling { kVirtualEq22, kVirtualEq24, kPhysicalPp, kPhysicalMp };

struct ModelFrfSetOptions {
  ModelFrfDecoupling decoupling = ModelFrfDecoupling::kVirtualEq22;
  bool include_coupled = false;  // also store the coupled blocks (a, p, m roles)
  bool include_ap = true;        // false: store no H_ap (readers apply reciprocity)
  std::string description = "lumped gearbox model";
};

// frequency_hz: finite, > 0 (the accelerance vanishes at 0 Hz, where decoupling is
// singular), strictly increasing.
Result<FrfSet> MakeModelFrfSet(const LumpedGearboxModel& model, const GearTrain& train,
                               const Eigen::VectorXd& frequency_hz,
                               const ModelFrfSetOptions& options = {});

// The seed's Table-1 gearbox as gearpath ships it (the daemon's `builtin:table1`): the Table-1
// lumped model decoupled at the bearing seats by Eq. 22, channels p1..p3, paths B1x..B3x, on
// the bins 1..4096 of an 8192-sample block at 8 kHz (0.977 Hz .. 4 kHz), so the default block
// maps onto it exactly. No DC bin: decoupling is singular there.
Result<FrfSet> MakeTable1FrfSet();

}  // namespace gearpath
