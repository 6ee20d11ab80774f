#include "core/diagnosis/path_contributions.h"

#include <string>

namespace gearpath {

std::string_view ToString(ContributionStatus status) noexcept {
  switch (status) {
    case ContributionStatus::kOk:
      return "ok";
    case ContributionStatus::kShapeMismatch:
      return "FRF or force shape differs from the configured channels x paths x bins";
    case ContributionStatus::kBadBinRange:
      return "bin range is empty or outside the configured bins";
    case ContributionStatus::kBadChannel:
      return "channel index is outside the configured channels";
  }
  return "unknown";
}

Result<PathContributions> PathContributions::Create(Eigen::Index channels, Eigen::Index paths,
                                                    Eigen::Index bins) {
  const auto check = [](const char* what, Eigen::Index n) -> std::string {
    return n >= 1 ? std::string()
                  : std::string("path contributions: ") + what + " must be >= 1, got " +
                        std::to_string(n);
  };
  for (const std::string& why :
       {check("channels", channels), check("paths", paths), check("bins", bins)}) {
    if (!why.empty()) return Error{why};
  }
  PathContributions c;
  c.channels_ = channels;
  c.paths_ = paths;
  c.bins_ = bins;
  c.contributions_ = Eigen::MatrixXcd::Zero(bins, paths * channels);
  c.response_ = Eigen::MatrixXcd::Zero(bins, channels);
  return c;
}

ContributionStatus PathContributions::Compute(
    std::span<const Eigen::MatrixXcd> h,
    const Eigen::Ref<const Eigen::MatrixXcd>& forces) noexcept {
  if (static_cast<Eigen::Index>(h.size()) != bins_ || forces.rows() != paths_ ||
      forces.cols() != bins_) {
    return ContributionStatus::kShapeMismatch;
  }
  for (const Eigen::MatrixXcd& hk : h) {
    if (hk.rows() != channels_ || hk.cols() != paths_) return ContributionStatus::kShapeMismatch;
  }
  // Bin-major: each H_k is read once, contiguously (the FRF matrices are separate
  // allocations, so a path-major order strides across all of them; it measured slower).
  for (Eigen::Index k = 0; k < bins_; ++k) {
    const Eigen::MatrixXcd& hk = h[static_cast<std::size_t>(k)];
    for (Eigen::Index c = 0; c < channels_; ++c) {
      std::complex<double> sum = 0.0;
      for (Eigen::Index i = 0; i < paths_; ++i) {
        const std::complex<double> contribution = hk(c, i) * forces(i, k);
        contributions_(k, Column(i, c)) = contribution;
        sum += contribution;
      }
      response_(k, c) = sum;
    }
  }
  return ContributionStatus::kOk;
}

std::span<const std::complex<double>> PathContributions::Contribution(
    Eigen::Index path, Eigen::Index channel) const noexcept {
  if (path < 0 || path >= paths_ || channel < 0 || channel >= channels_) return {};
  return {contributions_.col(Column(path, channel)).data(), static_cast<std::size_t>(bins_)};
}

std::span<const std::complex<double>> PathContributions::Response(
    Eigen::Index channel) const noexcept {
  if (channel < 0 || channel >= channels_) return {};
  return {response_.col(channel).data(), static_cast<std::size_t>(bins_)};
}

PathEnergy PathContributions::MakeEnergy() const {
  PathEnergy e;
  e.energy = Eigen::VectorXd::Zero(paths_);
  e.share = Eigen::VectorXd::Zero(paths_);
  e.projection_share = Eigen::VectorXd::Zero(paths_);
  return e;
}

ContributionStatus PathContributions::Energy(Eigen::Index first_bin, Eigen::Index end_bin,
                                             Eigen::Index channel, PathEnergy& out) const noexcept {
  if (first_bin < 0 || end_bin > bins_ || first_bin >= end_bin) {
    return ContributionStatus::kBadBinRange;
  }
  if (channel < -1 || channel >= channels_) return ContributionStatus::kBadChannel;
  if (out.energy.size() != paths_ || out.share.size() != paths_ ||
      out.projection_share.size() != paths_) {
    return ContributionStatus::kShapeMismatch;
  }
  const Eigen::Index c0 = channel < 0 ? 0 : channel;
  const Eigen::Index c1 = channel < 0 ? channels_ : channel + 1;
  const Eigen::Index n = end_bin - first_bin;
  out.response_energy = 0.0;
  for (Eigen::Index c = c0; c < c1; ++c) {
    out.response_energy += response_.col(c).segment(first_bin, n).squaredNorm();
  }
  out.path_energy_sum = 0.0;
  for (Eigen::Index i = 0; i < paths_; ++i) {
    double energy = 0.0;
    double projection = 0.0;
    for (Eigen::Index c = c0; c < c1; ++c) {
      const auto ci = contributions_.col(Column(i, c)).segment(first_bin, n);
      const auto x = response_.col(c).segment(first_bin, n);
      energy += ci.squaredNorm();
      projection += x.dot(ci).real();  // Eigen's dot conjugates the first argument
    }
    out.energy(i) = energy;
    out.projection_share(i) = projection;
    out.path_energy_sum += energy;
  }
  out.dominant_path = -1;
  if (out.path_energy_sum > 0.0) {
    out.share = out.energy / out.path_energy_sum;
    out.share.maxCoeff(&out.dominant_path);
  } else {
    out.share.setZero();
  }
  if (out.response_energy > 0.0) {
    out.projection_share /= out.response_energy;
  } else {
    out.projection_share.setZero();
  }
  return ContributionStatus::kOk;
}

}  // namespace gearpath
