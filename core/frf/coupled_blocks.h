// CoupledBlocks: FRFs of the assembled (coupled) gearbox, split by DOF role, per frequency.
//
// Roles, as in the seed's Fig. 2: `a` = interface DOFs on the rotor (active) side, `p` =
// interface DOFs on the housing (passive) side, `m` = other measurement points on the housing.
// H_xy is the response at x-DOFs to a unit force at y-DOFs (rows = responses, cols = forces).
// These are the inputs of virtual decoupling (seed Eqs. 22 and 24).
#pragma once

#include <Eigen/Dense>
#include <vector>

namespace gearpath {

struct CoupledBlocks {
  Eigen::VectorXd frequency_hz;           // strictly increasing, Hz
  std::vector<Eigen::MatrixXcd> aa;       // a x a, required
  std::vector<Eigen::MatrixXcd> pa;       // p x a, required
  std::vector<Eigen::MatrixXcd> pp;       // p x p, required
  std::vector<Eigen::MatrixXcd> ap;       // a x p, optional: empty means H_ap = H_pa^T (reciprocity)
  std::vector<Eigen::MatrixXcd> ma;       // m x a, optional (needed for Eq. 24 only)
  std::vector<Eigen::MatrixXcd> mp;       // m x p, optional (needed for Eq. 24 only)

  Eigen::Index bins() const { return frequency_hz.size(); }
  bool has_ap() const { return !ap.empty(); }
  bool has_measurement_points() const { return !ma.empty() && !mp.empty(); }
};

}  // namespace gearpath
