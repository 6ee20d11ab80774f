#include "core/evaluation/linear_plant_stream.h"

#include <cmath>

namespace gearpath {

double MaxRmsChange(PlantSimulator& sim, std::int64_t first_sample) {
  Eigen::MatrixXd healthy, faulty;
  sim.NoiseFree(first_sample, false, healthy);
  sim.NoiseFree(first_sample, true, faulty);
  double best = 0.0;
  for (Eigen::Index c = 0; c < healthy.cols(); ++c) {
    const double h = healthy.col(c).norm();
    if (h <= 0.0) continue;
    const double change = faulty.col(c).norm() / h - 1.0;
    if (std::abs(change) > std::abs(best)) best = change;
  }
  return best;
}

double SeverityScaleForRmsChange(PlantSimulator& sim, std::int64_t first_sample, double target) {
  Eigen::MatrixXd healthy, faulty;
  sim.NoiseFree(first_sample, false, healthy);
  sim.NoiseFree(first_sample, true, faulty);
  double best = 0.0;
  for (Eigen::Index c = 0; c < healthy.cols(); ++c) {
    const Eigen::VectorXd g = faulty.col(c) - healthy.col(c);
    const double a = g.squaredNorm();
    const double b = 2.0 * healthy.col(c).dot(g);
    const double hh = healthy.col(c).squaredNorm();
    if (a <= 0.0 || hh <= 0.0) continue;
    for (double level : {1.0 + target, 1.0 - target}) {
      const double cc = hh * (1.0 - level * level);
      const double disc = b * b - 4.0 * a * cc;
      if (disc < 0.0) continue;
      for (double root : {(-b + std::sqrt(disc)) / (2.0 * a), (-b - std::sqrt(disc)) / (2.0 * a)}) {
        if (root > 0.0 && (best == 0.0 || root < best)) best = root;
      }
    }
  }
  return best;
}

SeverityFit LinearPlantStream::NormaliseSeverity(double target) {
  SeverityFit fit;
  if (sim_.excitation().fault_stage() < 0 || !(target > 0.0)) return fit;
  const std::int64_t first =
      static_cast<std::int64_t>(sim_.blocks_written()) * sim_.config().block_length;
  const double scale = SeverityScaleForRmsChange(sim_, first, target);
  if (scale > 0.0) {
    sim_.ScaleFaultSeverity(scale);
    fit.scale = scale;
  }
  fit.rms_change = MaxRmsChange(sim_, first);
  fit.evaluations = 2;
  return fit;
}

}  // namespace gearpath
