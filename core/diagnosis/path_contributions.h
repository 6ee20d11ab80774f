// PathContributions: the contribution of every transfer path to every response channel, per
// frequency bin, and the per-path energy shares over a band (seed Eq. 45).
//
// With H_k the decoupled FRF matrix at bin k (channels x paths) and F_k the identified bearing
// forces (one per path), the response at channel c is the sum over paths of
//   C_{c,i}(k) = H_k(c, i) F_i(k),      X_c(k) = sum_i C_{c,i}(k) = (H_k F_k)_c.
// Energy of path i over bins [first, end) and the selected channels: E_i = sum |C_{c,i}(k)|^2.
// The shares s_i = E_i / sum_j E_j sum to 1 but do NOT partition the response energy
//   sum |X_c(k)|^2 = sum_i E_i + 2 Re sum_{i<j} sum C_{c,i} conj(C_{c,j}),
// because contributions of different paths interfere (they come from the same mesh forces, so
// they are coherent, and can cancel or add). We report both: `share` (incoherent, >= 0, sums to
// 1: which path carries the most energy on its own, the seed's dominant-path reading) and
// `projection_share` p_i = Re sum conj(X) C_i / sum |X|^2 (the part of the response energy
// along path i's contribution; sums to exactly 1 but may be negative when a path cancels
// others), plus the cross-term total response_energy - sum_i E_i so a caller can tell how far
// the incoherent reading is from a partition.
//
// Configure once per shape (channels, paths, bins) with Create(); Compute() and Energy() are
// noexcept and allocate nothing. Contributions are stored bins-contiguous per (path, channel),
// so the time signal of one path at one channel is one inverse FFT of a contiguous span.
#pragma once

#include <Eigen/Dense>
#include <complex>
#include <span>
#include <string_view>
#include <vector>

#include "core/common/result.h"

namespace gearpath {

enum class ContributionStatus { kOk, kShapeMismatch, kBadBinRange, kBadChannel };
std::string_view ToString(ContributionStatus status) noexcept;

// Per-path energies over a band (vectors sized paths(); see the file comment).
struct PathEnergy {
  Eigen::VectorXd energy;            // E_i = sum over bins and channels of |C_i|^2
  Eigen::VectorXd share;             // E_i / sum_j E_j (all 0 if the paths carry no energy)
  Eigen::VectorXd projection_share;  // Re <C_i, X> / <X, X> (all 0 if the response is 0)
  double response_energy = 0.0;      // sum |X|^2 over the same bins and channels
  double path_energy_sum = 0.0;      // sum_i E_i; response_energy - this = cross terms
  Eigen::Index dominant_path = -1;   // argmax of share; -1 when no path carries energy
};

class PathContributions {
 public:
  // Allocates the outputs for `channels` x `paths` x `bins` (each >= 1). The message names
  // the offending dimension.
  static Result<PathContributions> Create(Eigen::Index channels, Eigen::Index paths,
                                          Eigen::Index bins);

  Eigen::Index channels() const noexcept { return channels_; }
  Eigen::Index paths() const noexcept { return paths_; }
  Eigen::Index bins() const noexcept { return bins_; }

  // h: bins() matrices of channels() x paths() (e.g. FrfMatrix::at); forces: paths() x bins()
  // (one column per bin, as IdentificationOperator::IdentifyAll writes them).
  ContributionStatus Compute(std::span<const Eigen::MatrixXcd> h,
                             const Eigen::Ref<const Eigen::MatrixXcd>& forces) noexcept;

  // C_{channel, path}(k) for every bin k (bins() values). Empty span on a bad index.
  std::span<const std::complex<double>> Contribution(Eigen::Index path,
                                                     Eigen::Index channel) const noexcept;
  // X_channel(k) = sum over paths, for every bin. Empty span on a bad index.
  std::span<const std::complex<double>> Response(Eigen::Index channel) const noexcept;

  // Energies over bins [first_bin, end_bin) at one channel, or all channels when channel is
  // -1. `out` must have been made by MakeEnergy() (or have paths()-long vectors).
  ContributionStatus Energy(Eigen::Index first_bin, Eigen::Index end_bin, Eigen::Index channel,
                            PathEnergy& out) const noexcept;
  PathEnergy MakeEnergy() const;

 private:
  PathContributions() = default;
  Eigen::Index Column(Eigen::Index path, Eigen::Index channel) const noexcept {
    return path * channels_ + channel;
  }

  Eigen::Index channels_ = 0;
  Eigen::Index paths_ = 0;
  Eigen::Index bins_ = 0;
  Eigen::MatrixXcd contributions_;  // bins x (paths * channels), column path * channels + c
  Eigen::MatrixXcd response_;       // bins x channels
};

}  // namespace gearpath
