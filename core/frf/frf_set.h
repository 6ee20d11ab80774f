// FrfSet: everything gearpath knows about one gearbox housing's FRFs, as loaded from disk.
//
// The decoupled FRF matrix (response channels x transfer paths) is what the daemon inverts
// block by block. A set may also (or only) carry the coupled measurement it was derived from,
// with the role of every DOF, so that `gearpath decouple` can redo Eq. 22/24.
// On-disk format: docs/frf_format.md (JSON manifest + NumPy .npy arrays).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/common/frf_matrix.h"
#include "core/frf/coupled_blocks.h"

namespace gearpath {

inline constexpr int kFrfFormatVersion = 1;

enum class FrfQuantity { kAccelerance, kMobility, kReceptance };

// One transfer path = one bearing force component the daemon identifies.
struct TransferPath {
  std::string name;                // e.g. "B1x"
  std::string bearing;             // bearing location, e.g. "input shaft, drive end"
  std::string direction;           // "x", "y" or "z"
  std::vector<std::string> gears;  // the gear(s) nearest to this bearing, e.g. {"G1"}
};

// One response channel = one accelerometer axis on the housing.
struct ResponseChannel {
  std::string sensor;  // sensor id, e.g. "A1"
  std::string axis;    // "x", "y" or "z"
};

// A DOF of the coupled measurement (a, p or m role is given by which list it sits in).
struct CoupledDof {
  std::string name;       // e.g. "p1x"
  std::string node;       // measurement node / sensor id
  std::string direction;  // "x", "y" or "z"
};

struct CoupledSet {
  std::vector<CoupledDof> active;       // a
  std::vector<CoupledDof> passive;      // p
  std::vector<CoupledDof> measurement;  // m (may be empty)
  CoupledBlocks blocks;
};

struct FrfSet {
  int format_version = kFrfFormatVersion;
  std::string description;
  FrfQuantity quantity = FrfQuantity::kAccelerance;
  std::string unit = "m/s^2/N";
  // Which equation produced `decoupled`: "eq22" (responses at p), "eq24" (responses at m),
  // "physical" (housing measured alone), or "model".
  std::string decoupling;
  std::vector<TransferPath> paths;          // columns of `decoupled`
  std::vector<ResponseChannel> channels;    // rows of `decoupled`
  FrfMatrix decoupled;                      // may be empty when only `coupled` is present
  std::optional<CoupledSet> coupled;
};

}  // namespace gearpath
