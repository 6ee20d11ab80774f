// Maximumly Weighted Iteration (MWI) for one frequency bin, seed Sect. 2.3, Eqs. 40-43.
//
// Solve x = H F (x: m responses, F: n path forces, H complex m x n; H^H replaces the seed's H^T).
// With A = H^H H and W = diag(1 / ||row_i(A)||_2) (Eq. 40), MWI iterates
//   (A W + alpha I) f_{k+1} = H^H x + alpha f_k,  f_0 = 0,  k = 0 .. K-1,   F = W f_K.
//
// Closed form (why the per-bin operator needs one SVD and never H^H H). Put D = W^{1/2},
// B = H D and z_k = D f_k. Multiplying the iteration on the left by D:
//   D A W f = D H^H H D D f = B^H B z,   D H^H x = B^H x,   D alpha f = alpha z,
// so (B^H B + alpha I) z_{k+1} = B^H x + alpha z_k: K steps of stationary iterated Tikhonov
// on B, started at 0. With B = U S V^H (thin) write z = V c + (part outside range(V)). The
// outside part obeys alpha z'_{k+1} = alpha z'_k and stays 0. Component i of c obeys
//   (sigma_i^2 + alpha) c_{k+1} = sigma_i beta_i + alpha c_k,   beta_i = u_i^H x,
// whose fixed point is beta_i / sigma_i; the distance to it shrinks by r_i = alpha /
// (sigma_i^2 + alpha) per step, so from c_0 = 0: c_K = (1 - r_i^K) beta_i / sigma_i.
// Hence F = W f_K = D z_K = D V diag(phi_i / sigma_i) U^H x, phi_i = 1 - (alpha/(sigma_i^2+alpha))^K.
// Components with sigma_i = 0 stay 0 (the iteration never excites them). As K -> infinity
// phi -> 1: F -> D B^+ x, the least-squares solution of minimum D^{-1}-weighted norm (the
// plain least-squares solution when H has full column rank). The tests check this identity
// against the literal iteration.
//
// Assumes no column of H is zero (else a row of A is zero and W is undefined).
#pragma once

#include <Eigen/Dense>

#include "core/common/result.h"

namespace gearpath {

// W of Eq. 40 as a vector: w_i = 1 / ||row_i(H^H H)||_2. Formed from A = H^H H on purpose (it
// is the definition); only the weights, never a solve, depend on A.
Result<Eigen::VectorXd> MwiWeights(const Eigen::MatrixXcd& h);

// The literal iteration (reference implementation for tests): forms A = H^H H and solves
// (A W + alpha I) f_{k+1} = H^H x + alpha f_k K times. Squares the condition number of H.
Result<Eigen::VectorXcd> SolveMwiByIteration(const Eigen::MatrixXcd& h, const Eigen::VectorXcd& x,
                                              double alpha, int iterations);

// The same forces from one SVD of H W^{1/2} (see above).
Result<Eigen::VectorXcd> SolveMwi(const Eigen::MatrixXcd& h, const Eigen::VectorXcd& x,
                                  double alpha, int iterations);

}  // namespace gearpath
