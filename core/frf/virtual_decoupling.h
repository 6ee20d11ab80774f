// Virtual decoupling: the housing's own FRFs computed from FRFs of the assembled gearbox
// (in-situ decoupling, seed Eqs. 22 and 24, after the seed's Ref. [29]).
//
//   Eq. 22 (responses at the housing interface p):
//     H_d,pp = H_pp - H_pa (H_pa - H_aa)^-1 (H_pp - H_ap)
//   Eq. 24 (responses at housing measurement points m):
//     H_d,mp = H_mp - H_ma (H_aa - H_pa)^-1 (H_ap - H_pp) = H_mp - H_ma (H_pa - H_aa)^-1 (H_pp -
//     H_ap)
//
// Why it is exact: if the rotor side (a) and the housing (p, m) are joined only through links
// between a and p (any link dynamic stiffness L', e.g. bearings k + j w c), the housing rows of
// Z H = I give H_{B,a} = -H_d,Bp L' (H_pa - H_aa) and H_{B,p} = H_d,Bp (I - L' (H_pp - H_ap))
// for B = p or m; eliminating the unknown H_d,Bp L' gives both equations. They hold for
// receptance or accelerance alike (every term scales by the same w^2), need no model of the
// links, and need |a| = |p| with (H_pa - H_aa) invertible.
//
// Assumptions / conventions: H_xy = response at x to a force at y. When `ap` is not given,
// H_ap = H_pa^T (plain transpose: reciprocity of a passive linear structure, not a conjugate).
// The solve uses an SVD of (H_pa - H_aa) per bin (no explicit inverse); its singular values give
// the 2-norm condition number reported per bin. A bin whose condition number exceeds the limit
// (default 1 / (n eps), n = |a|: beyond it the solve has no correct digit) is an error naming
// the frequency. Configuration-time code: allocates, returns Result.
#pragma once

#include <Eigen/Dense>

#include "core/common/frf_matrix.h"
#include "core/common/result.h"
#include "core/frf/coupled_blocks.h"

namespace gearpath {

struct VirtualDecouplingOptions {
  // Largest accepted 2-norm condition number of (H_pa - H_aa); <= 0 means 1 / (n eps).
  double max_condition_number = 0.0;
};

struct DecouplingConditionReport {
  Eigen::VectorXd condition_number;  // per bin, of (H_pa - H_aa)
  double worst_condition_number = 0.0;
  double worst_frequency_hz = 0.0;
  Eigen::Index worst_bin = 0;
  double limit = 0.0;  // the threshold that was applied
};

struct VirtualDecouplingResult {
  FrfMatrix decoupled;  // on the blocks' frequency grid
  DecouplingConditionReport report;
};

// Eq. 22: H_d,pp (p x p per bin).
Result<VirtualDecouplingResult> DecoupleAtInterface(const CoupledBlocks& blocks,
                                                    const VirtualDecouplingOptions& options = {});
// Eq. 24: H_d,mp (m x p per bin); needs the ma and mp blocks.
Result<VirtualDecouplingResult> DecoupleAtMeasurementPoints(
    const CoupledBlocks& blocks, const VirtualDecouplingOptions& options = {});

}  // namespace gearpath
