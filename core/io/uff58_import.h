// From UFF 58 records to gearpath data: coupled FRF blocks, and time histories for replay.
//
// ImportCoupledSet assembles the coupled blocks H_aa, H_pa, H_pp (required), H_ap (when
// measured; otherwise left empty and reciprocity H_ap = H_pa^T is applied by the decoupling,
// seed Eqs. 22/24) and H_ma, H_mp (when measurement DOFs are given) from FRF records
// (function type 4) sharing one abscissa. The caller says which DOF plays which role (seed
// Fig. 2: a = rotor-side interface, p = housing-side interface, m = other housing points).
//
// Sign convention: roles name DOFs by node and positive direction (1/2/3 = +X/+Y/+Z). A record
// measured along a negative direction (-1/-2/-3) is the same DOF with opposite sense, so its
// FRF is negated once per negative end (response and/or reference). Records whose two DOFs are
// not both assigned are ignored (files often hold other DOFs); a required pair with no FRF, a
// pair with two FRFs, and FRFs on different abscissae are errors that name the DOFs.
#pragma once

#include <Eigen/Dense>
#include <span>
#include <string>
#include <vector>

#include "core/common/result.h"
#include "core/frf/frf_set.h"
#include "core/io/uff58.h"

namespace gearpath {

enum class DofRole { kActive, kPassive, kMeasurement };

// One DOF of the coupled measurement, as the caller assigns it.
struct UffDofAssignment {
  std::string name;   // e.g. "p1x"; becomes CoupledDof::name
  int node = 0;       // UFF node number
  int direction = 1;  // 1, 2, 3 = +X, +Y, +Z
  DofRole role = DofRole::kPassive;
};

// Assembles the coupled set; DOFs keep the order in which `dofs` lists them within each role.
// Abscissae must agree to a relative 1e-9 (the ASCII header prints them with 6 digits).
Result<CoupledSet> ImportCoupledSet(std::span<const Uff58Record> records,
                                    std::span<const UffDofAssignment> dofs);

// Time responses (function type 1) as equal-length channels on one sample clock.
struct TimeHistories {
  struct Channel {
    int node = 0;
    int direction = 0;
    std::string label;  // ID line 1 of the record
    std::string unit;   // ordinate units label
  };
  double sample_rate_hz = 0.0;
  double start_time_s = 0.0;
  std::vector<Channel> channels;
  Eigen::MatrixXd samples;  // n_samples x n_channels
};

// Extracts every time-response record, in file order. All must be real, evenly sampled, with
// the same start, increment and length (relative 1e-9).
Result<TimeHistories> ExtractTimeHistories(std::span<const Uff58Record> records);

}  // namespace gearpath
