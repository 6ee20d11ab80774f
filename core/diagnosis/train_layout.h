// TrainLayout: the topology of a parallel-axis gear train as the diagnosis needs it.
//
// Which gear sits on which shaft, which gears mesh, and the tooth counts: from these follow
// every shaft rate and mesh frequency for a given input-shaft speed (seed Table 6: a fault on a
// gear modulates the mesh at the rate of the shaft carrying the gear), and which gears the
// envelope cannot tell apart (same shaft rate AND same mesh, e.g. Table 1 gears 3 and 4).
// Assumes rigid shafts and no slip: rate(driven shaft) = rate(driver shaft) * z_driver / z_driven.
// core/model/gear_train.h computes the same kinematics for the simulator; this plain-data form
// keeps the daemon's configuration -> pipeline path independent of the model library.
#pragma once

#include <string>
#include <vector>

#include "core/common/result.h"

namespace gearpath {

struct TrainShaft {
  std::string name;  // e.g. "input", "intermediate", "output"
};

struct TrainGear {
  std::string name;  // e.g. "G1"; the names FrfSet paths use in TransferPath::gears
  int teeth = 0;
  int shaft = -1;  // index into TrainLayout::shafts
};

struct TrainMesh {
  int gear_a = -1;  // index into TrainLayout::gears (the driver, nearer the input)
  int gear_b = -1;  // index into TrainLayout::gears (the driven gear)
};

struct TrainLayout {
  std::vector<TrainShaft> shafts;
  std::vector<TrainGear> gears;
  std::vector<TrainMesh> meshes;
  int input_shaft = 0;  // the shaft whose speed the blocks / configuration give

  // Table 1 of the seed: G1 (28 teeth) on "input" meshes G2 (40) on "intermediate"; G3 (34) on
  // "intermediate" meshes G4 (34) on "output". At 10 Hz input: 7 Hz intermediate and output,
  // meshes at 280 Hz and 238 Hz.
  static TrainLayout Table1();
};

// Checks indices, tooth counts (> 0), unique gear names, that every gear is in at most one
// mesh pair per partner, and that every shaft is reachable from the input shaft through
// meshes; returns per-shaft rate ratios (shaft rate / input rate) on success. The message
// names the offending gear, shaft or mesh.
Result<std::vector<double>> ShaftRateRatios(const TrainLayout& layout);

struct GearTrain;  // core/model/gear_train.h

// The layout of a GearTrain (shafts in order, the input shaft first; stages as meshes, driver
// first). Fails with the GearTrain's own validation message.
Result<TrainLayout> TrainLayoutFromGearTrain(const GearTrain& train);

}  // namespace gearpath
