// FrfMatrix: a frequency response function matrix sampled on a frequency axis.
//
// at[k] is the complex (outputs x inputs) matrix at frequency_hz[k]. The quantity (receptance,
// mobility, accelerance) is a property of whoever produced it; gearpath works in accelerance
// (m/s^2/N) throughout, as the seed does (Eq. 6: H = w^2 (-w^2 M + jwC + K)^-1).
#pragma once

#include <Eigen/Dense>
#include <complex>
#include <vector>

namespace gearpath {

using Complex = std::complex<double>;

struct FrfMatrix {
  Eigen::VectorXd frequency_hz;         // strictly increasing, Hz
  std::vector<Eigen::MatrixXcd> at;     // one (outputs x inputs) matrix per frequency

  Eigen::Index bins() const { return frequency_hz.size(); }
  Eigen::Index outputs() const { return at.empty() ? 0 : at.front().rows(); }
  Eigen::Index inputs() const { return at.empty() ? 0 : at.front().cols(); }
};

}  // namespace gearpath
