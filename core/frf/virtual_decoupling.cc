#include "core/frf/virtual_decoupling.h"

#include <fmt/format.h>

#include <Eigen/SVD>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace gearpath {
namespace {

enum class Target { kInterface, kMeasurementPoints };

const char* EquationName(Target target) {
  return target == Target::kInterface ? "virtual decoupling (Eq. 22)"
                                      : "virtual decoupling (Eq. 24)";
}

// Checks one block list: one matrix per bin, all of the given shape, all finite.
Status CheckBlock(const std::vector<Eigen::MatrixXcd>& block, const char* name, Eigen::Index bins,
                  Eigen::Index rows, Eigen::Index cols) {
  if (static_cast<Eigen::Index>(block.size()) != bins) {
    return Error{
        fmt::format("block H_{} has {} bins, the frequency axis has {}", name, block.size(), bins)};
  }
  for (std::size_t k = 0; k < block.size(); ++k) {
    if (block[k].rows() != rows || block[k].cols() != cols) {
      return Error{fmt::format("block H_{} at bin {} is {} x {}, expected {} x {}", name, k,
                               block[k].rows(), block[k].cols(), rows, cols)};
    }
    if (!block[k].allFinite()) {
      return Error{fmt::format("block H_{} at bin {} has a non-finite entry", name, k)};
    }
  }
  return Status::Ok();
}

Status CheckBlocks(const CoupledBlocks& b, Target target) {
  const Eigen::Index bins = b.bins();
  if (bins == 0) return Error{"the coupled blocks have no frequency bins"};
  for (Eigen::Index k = 0; k < bins; ++k) {
    if (!std::isfinite(b.frequency_hz[k]) ||
        (k > 0 && !(b.frequency_hz[k] > b.frequency_hz[k - 1]))) {
      return Error{
          fmt::format("frequency axis: bin {} ({} Hz) is not finite or not above the "
                      "previous bin",
                      k, b.frequency_hz[k])};
    }
  }
  if (b.aa.empty()) return Error{"block H_aa is missing"};
  if (b.pa.empty()) return Error{"block H_pa is missing"};
  if (b.pp.empty()) return Error{"block H_pp is missing"};
  const Eigen::Index na = b.aa.front().rows();
  const Eigen::Index np = b.pa.front().rows();
  if (na == 0) return Error{"block H_aa is empty (no active interface DOF)"};
  if (np != na) {
    return Error{fmt::format(
        "H_pa is {} x {}: the passive interface has {} DOFs and the active interface {}; virtual "
        "decoupling needs one p DOF per a DOF (each bearing link joins one a to one p)",
        np, b.pa.front().cols(), np, na)};
  }
  if (Status s = CheckBlock(b.aa, "aa", bins, na, na); !s) return s;
  if (Status s = CheckBlock(b.pa, "pa", bins, np, na); !s) return s;
  if (Status s = CheckBlock(b.pp, "pp", bins, np, np); !s) return s;
  if (b.has_ap()) {
    if (Status s = CheckBlock(b.ap, "ap", bins, na, np); !s) return s;
  }
  if (target == Target::kMeasurementPoints) {
    if (b.ma.empty()) return Error{"block H_ma is missing (Eq. 24 needs the measurement points)"};
    if (b.mp.empty()) return Error{"block H_mp is missing (Eq. 24 needs the measurement points)"};
    const Eigen::Index nm = b.ma.front().rows();
    if (nm == 0) return Error{"block H_ma has no rows (no measurement point)"};
    if (Status s = CheckBlock(b.ma, "ma", bins, nm, na); !s) return s;
    if (Status s = CheckBlock(b.mp, "mp", bins, nm, np); !s) return s;
  }
  return Status::Ok();
}

Result<VirtualDecouplingResult> Decouple(const CoupledBlocks& b, Target target,
                                         const VirtualDecouplingOptions& options) {
  if (Status s = CheckBlocks(b, target); !s) {
    return Error{fmt::format("{}: {}", EquationName(target), s.error())};
  }
  const Eigen::Index bins = b.bins();
  const Eigen::Index n = b.aa.front().rows();
  VirtualDecouplingResult result;
  DecouplingConditionReport& report = result.report;
  report.limit = options.max_condition_number > 0.0
                     ? options.max_condition_number
                     : 1.0 / (static_cast<double>(n) * std::numeric_limits<double>::epsilon());
  report.condition_number.resize(bins);
  result.decoupled.frequency_hz = b.frequency_hz;
  result.decoupled.at.reserve(bins);

  for (Eigen::Index k = 0; k < bins; ++k) {
    const Eigen::MatrixXcd d = b.pa[k] - b.aa[k];
    const Eigen::MatrixXcd rhs = b.has_ap() ? Eigen::MatrixXcd(b.pp[k] - b.ap[k])
                                            : Eigen::MatrixXcd(b.pp[k] - b.pa[k].transpose());
    const Eigen::JacobiSVD<Eigen::MatrixXcd> svd(d, Eigen::ComputeFullU | Eigen::ComputeFullV);
    const Eigen::VectorXd& sigma = svd.singularValues();
    const double cond =
        sigma[n - 1] > 0.0 ? sigma[0] / sigma[n - 1] : std::numeric_limits<double>::infinity();
    report.condition_number[k] = cond;
    if (k == 0 || cond > report.worst_condition_number) {
      report.worst_condition_number = cond;
      report.worst_frequency_hz = b.frequency_hz[k];
      report.worst_bin = k;
    }
    if (!(cond <= report.limit)) {
      return Error{fmt::format(
          "{}: (H_pa - H_aa) is {} at {:.6g} Hz (bin {}): 2-norm condition number {:.3g} exceeds "
          "the limit {:.3g}",
          EquationName(target), std::isfinite(cond) ? "numerically singular" : "singular",
          b.frequency_hz[k], k, cond, report.limit)};
    }
    // X = (H_pa - H_aa)^-1 (H_pp - H_ap); both equations subtract (rows) * X.
    const Eigen::MatrixXcd x = svd.solve(rhs);
    if (target == Target::kInterface) {
      result.decoupled.at.push_back(b.pp[k] - b.pa[k] * x);
    } else {
      result.decoupled.at.push_back(b.mp[k] - b.ma[k] * x);
    }
  }
  return result;
}

}  // namespace

Result<VirtualDecouplingResult> DecoupleAtInterface(const CoupledBlocks& blocks,
                                                    const VirtualDecouplingOptions& options) {
  return Decouple(blocks, Target::kInterface, options);
}

Result<VirtualDecouplingResult> DecoupleAtMeasurementPoints(
    const CoupledBlocks& blocks, const VirtualDecouplingOptions& options) {
  return Decouple(blocks, Target::kMeasurementPoints, options);
}

}  // namespace gearpath
