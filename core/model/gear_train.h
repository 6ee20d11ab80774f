// GearTrain: the kinematic description of a multistage parallel-axis gearbox.
//
// Shafts (the input shaft first), the gears on each shaft with their tooth counts, the gear
// stages (driver gear -> driven gear, one mesh per stage) and the bearings (each supports one
// shaft; the daemon maps them to FRF transfer paths). From the input-shaft speed it gives every
// shaft's rotation frequency, every mesh frequency, and for every gear its shaft, its stage and
// its characteristic (fault) frequency, which is its shaft's rotation frequency: a localized
// tooth fault engages once per revolution of the gear (the seed's Table 6 lists exactly these,
// f1 = input shaft, f2 = intermediate shaft, for its Table 1 train).
//
// Assumes rigid shafts and gears in permanent mesh (no clutches, no planetary stages, no idler
// gear meshing in two stages): every shaft's speed follows from the input speed through the
// tooth ratios, speed_driven = speed_driver * z_driver / z_driven. A plain struct so that the
// daemon's configuration parser can fill it; call Validate() before use.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/common/result.h"

namespace gearpath {

struct GearSpec {
  std::string name;  // e.g. "G1"
  int teeth = 0;     // >= 1
};

struct ShaftSpec {
  std::string name;                // e.g. "input", "intermediate", "output"
  std::vector<std::string> gears;  // names of the gears keyed to this shaft
};

// One gear pair in mesh: power flows from `driver` to `driven` (names of gears).
struct StageSpec {
  std::string driver;
  std::string driven;
};

struct BearingSpec {
  std::string name;   // e.g. "B1"
  std::string shaft;  // name of the shaft it supports
};

struct ShaftKinematics {
  std::string name;
  double rotation_hz = 0.0;
};

struct MeshKinematics {
  std::string driver;
  std::string driven;
  double mesh_hz = 0.0;        // = z_driver * f_driver_shaft = z_driven * f_driven_shaft
  double contact_ratio = 0.0;  // involute transverse contact ratio of the pair (standard gears)
};

struct GearKinematics {
  std::string name;
  int teeth = 0;
  int shaft = -1;                  // index into GearTrain::shafts
  int stage = -1;                  // index into GearTrain::stages (its mesh)
  double characteristic_hz = 0.0;  // fault frequency: its shaft's rotation frequency
};

struct TrainKinematics {
  double input_hz = 0.0;
  std::vector<ShaftKinematics> shafts;  // same order as GearTrain::shafts
  std::vector<MeshKinematics> meshes;   // same order as GearTrain::stages
  std::vector<GearKinematics> gears;    // same order as GearTrain::gears
};

struct GearTrain {
  std::vector<ShaftSpec> shafts;  // shafts[0] is the input shaft
  std::vector<GearSpec> gears;
  std::vector<StageSpec> stages;
  std::vector<BearingSpec> bearings;
  // Tooth geometry for the contact ratio (standard full-depth involute gears, no profile shift).
  double pressure_angle_deg = 20.0;
  double addendum_coefficient = 1.0;

  // Empty string when valid; otherwise the first problem found, naming the field, e.g.
  // "gears[2] (G3): teeth must be >= 1, got 0" or "bearings[1] (B2): unknown shaft 'shaft9'".
  bool IsValid(std::string* why) const;
  Status Validate() const;

  // Speeds for an input-shaft speed in Hz (> 0). Fails with the validation message if invalid.
  Result<TrainKinematics> Kinematics(double input_hz) const;

  // The smallest number of input-shaft revolutions after which every shaft is back at its
  // starting angle (the least common period of all shafts, in input revolutions): every shaft
  // speed is input * p/q with p/q a product of tooth ratios, so this is lcm(q) over the shafts.
  // For Table 1: 10 (7/10 on the intermediate and output shafts). Fails on an invalid train or
  // if the period exceeds 10^9 input revolutions (no practical common period).
  Result<std::int64_t> InputRevolutionsPerCommonPeriod() const;

  // Lookups on a valid train; -1 when the name is unknown.
  int GearIndex(const std::string& name) const;
  int ShaftIndex(const std::string& name) const;
  int ShaftOfGear(const std::string& name) const;
  // Names of the gears on the shaft a bearing supports (the gears nearest to that bearing).
  std::vector<std::string> GearsNearBearing(int bearing) const;

  // The seed's Table 1 gearbox: Z1 = 28 on the input shaft, Z2 = 40 and Z3 = 34 on the
  // intermediate shaft, Z4 = 34 on the output shaft; stages G1->G2 and G3->G4; one bearing
  // (seat) per shaft, B1 (input), B2 (intermediate), B3 (output), as in the lumped model.
  static GearTrain Table1();
};

// Transverse contact ratio of two standard external involute spur gears (module cancels):
// eps = (sqrt(ra1^2 - rb1^2) + sqrt(ra2^2 - rb2^2) - a sin(alpha)) / (pi cos(alpha)), in units
// of the module, with r = z/2, ra = r + ha*, rb = r cos(alpha), a = r1 + r2.
double StandardContactRatio(int z1, int z2, double pressure_angle_deg, double addendum_coefficient);

// Revolutions per minute to Hz and back.
constexpr double RpmToHz(double rpm) { return rpm / 60.0; }
constexpr double HzToRpm(double hz) { return hz * 60.0; }

}  // namespace gearpath
