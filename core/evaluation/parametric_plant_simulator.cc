#include "core/evaluation/parametric_plant_simulator.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace gearpath {
namespace {

constexpr double kSeverityTolerance = 0.01;  // relative to the target RMS change
constexpr int kMaxSeverityEvaluations = 8;
constexpr std::size_t kMaxChannels = 16;
constexpr int kMaxShafts = 8;

bool ActivePulse(PlantFaultKind k) {
  return k == PlantFaultKind::kTePulse || k == PlantFaultKind::kCombined;
}
bool ActiveCrack(PlantFaultKind k) {
  return k == PlantFaultKind::kMeshAm || k == PlantFaultKind::kCombined;
}
bool ActiveWear(PlantFaultKind k) { return k == PlantFaultKind::kWearDip; }

// Signed RMS change of the channel whose RMS changes most.
double MaxChange(const Eigen::VectorXd& healthy_rms, const Eigen::MatrixXd& faulty) {
  double best = 0.0;
  for (Eigen::Index c = 0; c < faulty.cols(); ++c) {
    if (!(healthy_rms[c] > 0.0)) continue;
    const double rms = std::sqrt(faulty.col(c).squaredNorm() / static_cast<double>(faulty.rows()));
    const double change = rms / healthy_rms[c] - 1.0;
    if (std::abs(change) > std::abs(best)) best = change;
  }
  return best;
}

Eigen::VectorXd Rms(const Eigen::MatrixXd& x) {
  Eigen::VectorXd r(x.cols());
  for (Eigen::Index c = 0; c < x.cols(); ++c) {
    r[c] = std::sqrt(x.col(c).squaredNorm() / static_cast<double>(x.rows()));
  }
  return r;
}

}  // namespace

Result<ParametricPlantSimulator> ParametricPlantSimulator::Create(
    std::shared_ptr<const ParametricGearbox> gearbox, std::vector<int> channel_points,
    std::vector<ChannelInfo> channels, ToothFault fault, const ParametricSimulatorConfig& config) {
  const ParametricSimulatorConfig& c = config;
  if (gearbox == nullptr) return Error{"parametric simulator: gearbox is null"};
  if (!(c.sample_rate_hz > 0.0) || !std::isfinite(c.sample_rate_hz)) {
    return Error{fmt::format(
        "parametric simulator: sample_rate_hz must be finite and > 0, got {}", c.sample_rate_hz)};
  }
  if (!(c.input_speed_hz > 0.0) || !std::isfinite(c.input_speed_hz)) {
    return Error{fmt::format(
        "parametric simulator: input_speed_hz must be finite and > 0, got {}", c.input_speed_hz)};
  }
  if (c.block_length < 16) {
    return Error{
        fmt::format("parametric simulator: block_length must be >= 16, got {}", c.block_length)};
  }
  if (c.oversampling < 8 || c.oversampling > 64 || (c.oversampling & (c.oversampling - 1)) != 0) {
    return Error{fmt::format(
        "parametric simulator: oversampling must be a power of two in [8, 64], got {}",
        c.oversampling)};
  }
  if (!(c.run_in_s >= 0.0 && c.run_in_s <= 10.0)) {
    return Error{fmt::format("parametric simulator: run_in_s must be in [0, 10], got {}",
                             c.run_in_s)};
  }
  if (!(c.noise_relative >= 0.0) || !std::isfinite(c.noise_relative)) {
    return Error{fmt::format(
        "parametric simulator: noise_relative must be finite and >= 0, got {}", c.noise_relative)};
  }
  if (!(c.drift_relative >= 0.0 && c.drift_relative < 0.1)) {
    return Error{fmt::format("parametric simulator: drift_relative must be in [0, 0.1), got {}",
                             c.drift_relative)};
  }
  if (!(c.tone_level >= 0.0) || !(c.burst_level >= 0.0) || !(c.burst_rate_hz >= 0.0)) {
    return Error{"parametric simulator: tone_level, burst_level and burst_rate_hz must be >= 0"};
  }
  if (channel_points.empty() || channel_points.size() != channels.size() ||
      channels.size() > kMaxChannels) {
    return Error{fmt::format(
        "parametric simulator: {} channels named for {} channel points (need one each, 1..{})",
        channels.size(), channel_points.size(), kMaxChannels)};
  }
  if (gearbox->shaft_count() > kMaxShafts) {
    return Error{fmt::format("parametric simulator: at most {} shafts, got {}", kMaxShafts,
                             gearbox->shaft_count())};
  }
  for (int p : channel_points) {
    if (p < 0 || p >= gearbox->plate().point_count()) {
      return Error{fmt::format("parametric simulator: channel point {} is not a plate point", p)};
    }
  }
  if (fault.kind != PlantFaultKind::kNone) {
    if (fault.stage < 0 || fault.stage >= gearbox->stage_count()) {
      return Error{fmt::format("parametric simulator: fault stage {} is not a stage",
                               fault.stage)};
    }
    if (Status st = gearbox->meshes()[static_cast<std::size_t>(fault.stage)].CheckFault(fault);
        !st) {
      return Error{"parametric simulator: " + st.error()};
    }
  }
  // The highest mesh frequency the speed can reach must stay well under fs / 2.
  const double top_speed = c.input_speed_hz * (1.0 + (c.speed_drift ? c.drift_relative : 0.0));
  for (const MeshStage& st : gearbox->parameters().stages) {
    const double mesh_hz = st.mesh.z_driver *
                           gearbox->parameters().shafts[static_cast<std::size_t>(st.driver_shaft)]
                               .revs_per_input_rev *
                           top_speed;
    if (mesh_hz >= 0.25 * c.sample_rate_hz) {
      return Error{fmt::format(
          "parametric simulator: a mesh frequency of {:.0f} Hz at input_speed_hz {} is over "
          "sample_rate_hz / 4 ({}): too few mesh harmonics below fs / 2",
          mesh_hz, c.input_speed_hz, 0.25 * c.sample_rate_hz)};
    }
  }

  ParametricPlantSimulator sim;
  sim.config_ = c;
  sim.header_ = {c.machine_id, c.sample_rate_hz, c.input_speed_hz, c.start_time_ns,
                 c.first_sequence};
  sim.gearbox_ = std::move(gearbox);
  sim.channel_points_ = std::move(channel_points);
  sim.channels_ = std::move(channels);
  sim.fault_ = fault;
  sim.default_severity_ = fault.severity;
  const auto nc = static_cast<Eigen::Index>(sim.channels_.size());
  sim.disturbances_ = MeasurementDisturbances(DisturbanceConfigOf(c), nc);
  sim.speed_.mean_hz = c.input_speed_hz;
  sim.speed_.drift_relative = c.speed_drift ? c.drift_relative : 0.0;
  sim.speed_.period_s = static_cast<double>(c.block_length) / c.sample_rate_hz;
  sim.speed_.phase = sim.disturbances_.drift_phase();

  const double step_rate = c.sample_rate_hz * c.oversampling;
  sim.step_s_ = 1.0 / step_rate;
  const auto run_in_outputs = static_cast<std::int64_t>(std::ceil(c.run_in_s * c.sample_rate_hz));
  sim.run_in_steps_ = run_in_outputs * c.oversampling;
  Result<AntiAliasDecimator> decimator = AntiAliasDecimator::Create(
      step_rate, c.sample_rate_hz, c.pass_fraction * c.sample_rate_hz, c.attenuation_db,
      static_cast<int>(nc));
  if (!decimator) return Error{"parametric simulator: " + decimator.error()};
  sim.run_.decimator = std::move(decimator).value();
  sim.run_.integrator = GearboxIntegrator(*sim.gearbox_, sim.step_s_, sim.channel_points_);

  // Static equilibrium at the first step (time -run_in), then the run-in.
  std::vector<MeshSample> mesh;
  Eigen::VectorXd force;
  sim.Evaluate(0, false, mesh, force);
  sim.run_.integrator.SetStatic(mesh, force);
  for (int s = 0; s < sim.gearbox_->stage_count(); ++s) {
    // F = k (delta - e) at rest: the elastic load of the mesh (the approach delta also holds
    // the static transmission error e, runout included).
    const MeshSample& m = mesh[static_cast<std::size_t>(s)];
    sim.static_mesh_force_.push_back(m.TotalStiffness() * sim.run_.integrator.Approach(s) -
                                     m.ErrorForce());
  }
  {
    // Push the initial state (at rest: zero acceleration) as the first decimator input.
    std::vector<double> y(static_cast<std::size_t>(nc));
    if (sim.run_.decimator.Push(sim.run_.integrator.outputs().data(), y.data())) {
      ++sim.run_.outputs;
    }
  }
  sim.Advance(sim.run_, false, run_in_outputs - sim.run_.outputs, nullptr);

  // The first block, healthy: the reference RMS of the noise and the sources.
  Pending first;
  first.fault_on = false;
  first.scale = sim.scale_;
  first.after = sim.run_;
  sim.Advance(first.after, false, c.block_length, &first.block);
  sim.reference_rms_ = Rms(first.block);
  sim.pending_ = std::move(first);
  return sim;
}

void ParametricPlantSimulator::Evaluate(std::int64_t step, bool fault_on,
                                        std::vector<MeshSample>& mesh,
                                        Eigen::VectorXd& force) const {
  const double t = static_cast<double>(step - run_in_steps_) * step_s_;
  const double revs = speed_.Revs(t);
  const double hz = speed_.Hz(t);
  const ParametricGearboxParameters& p = gearbox_->parameters();
  const int stages = gearbox_->stage_count();
  mesh.resize(static_cast<std::size_t>(stages));
  const ToothFault* fault = fault_on && fault_.kind != PlantFaultKind::kNone ? &fault_ : nullptr;
  ShaftPhase phases[kMaxShafts];
  const int shafts = gearbox_->shaft_count();
  for (int i = 0; i < shafts; ++i) {
    const double rho = p.shafts[static_cast<std::size_t>(i)].revs_per_input_rev;
    phases[i] = MakeShaftPhase(rho * revs, rho * hz);
  }
  for (int s = 0; s < stages; ++s) {
    const MeshStage& st = p.stages[static_cast<std::size_t>(s)];
    gearbox_->meshes()[static_cast<std::size_t>(s)].Evaluate(
        phases[st.driver_shaft], phases[st.driven_shaft],
        fault != nullptr && fault->stage == s ? fault : nullptr, config_.constant_stiffness,
        mesh[static_cast<std::size_t>(s)]);
  }
  gearbox_->NominalForce(hz, speed_.HzPerS(t), force);
}

void ParametricPlantSimulator::Advance(Run& run, bool fault_on, std::int64_t count,
                                       Eigen::MatrixXd* out) const {
  const auto nc = static_cast<Eigen::Index>(channels_.size());
  if (out != nullptr) out->resize(count, nc);
  std::vector<MeshSample> mesh;
  Eigen::VectorXd force;
  double y[kMaxChannels];
  std::int64_t produced = 0;
  while (produced < count) {
    ++run.step;
    Evaluate(run.step, fault_on, mesh, force);
    run.integrator.Step(mesh, force);
    if (!run.decimator.Push(run.integrator.outputs().data(), y)) continue;
    ++run.outputs;
    if (out != nullptr) {
      for (Eigen::Index ch = 0; ch < nc; ++ch) (*out)(produced, ch) = y[ch];
    }
    ++produced;
  }
}

void ParametricPlantSimulator::NoiseFreeNext(bool fault_on, Eigen::MatrixXd& out) const {
  if (pending_ && pending_->fault_on == fault_on && (!fault_on || pending_->scale == scale_)) {
    out = pending_->block;
    return;
  }
  Run copy = run_;
  Advance(copy, fault_on, config_.block_length, &out);
}

void ParametricPlantSimulator::ScaleFaultSeverity(double factor) noexcept {
  if (!(factor >= 0.0) || !std::isfinite(factor)) return;
  scale_ = factor;
  const PlantFaultSeverity& d = default_severity_;
  PlantFaultSeverity& sv = fault_.severity;
  sv.pulse_depth_m = std::min(d.pulse_depth_m * factor, d.max_pulse_depth_m);
  sv.am_depth = std::min(d.am_depth * factor, d.max_am_depth);
  sv.dip_depth_m = std::min(d.dip_depth_m * factor, d.max_dip_depth_m);
}

double ParametricPlantSimulator::CapFactor() const noexcept {
  const PlantFaultSeverity& d = default_severity_;
  const PlantFaultKind k = fault_.kind;
  double cap = 0.0;
  if (ActivePulse(k) && d.pulse_depth_m > 0.0) cap = std::max(cap, d.max_pulse_depth_m / d.pulse_depth_m);
  if (ActiveCrack(k) && d.am_depth > 0.0) cap = std::max(cap, d.max_am_depth / d.am_depth);
  if (ActiveWear(k) && d.dip_depth_m > 0.0) cap = std::max(cap, d.max_dip_depth_m / d.dip_depth_m);
  return cap;
}

SeverityFit ParametricPlantSimulator::NormaliseSeverity(double target) {
  SeverityFit fit;
  if (fault_.kind == PlantFaultKind::kNone || !(target > 0.0)) return fit;
  Eigen::MatrixXd healthy;
  NoiseFreeNext(false, healthy);
  const Eigen::VectorXd healthy_rms = Rms(healthy);
  const double cap = CapFactor();
  Pending best;
  auto evaluate = [&](double s) {
    ScaleFaultSeverity(s);
    Pending p;
    p.fault_on = true;
    p.scale = s;
    p.after = run_;
    Advance(p.after, true, config_.block_length, &p.block);
    ++fit.evaluations;
    const double r = MaxChange(healthy_rms, p.block);
    best = std::move(p);
    return r;
  };
  // Secant on log |r| against log s (a power law r ~ s^p is solved in one step; the first
  // step assumes p = 1), kept inside the bracket once the target is bracketed.
  double s = std::min(1.0, cap);
  double r = evaluate(s);
  double s_prev = 0.0, r_prev = 0.0;
  double lo = 0.0, hi = 0.0;  // |r(lo)| < target < |r(hi)| (0 = not found yet)
  while (fit.evaluations < kMaxSeverityEvaluations &&
         std::abs(std::abs(r) - target) > kSeverityTolerance * target) {
    if (std::abs(r) < target) lo = std::max(lo, s);
    if (std::abs(r) > target && (hi == 0.0 || s < hi)) hi = s;
    if (std::abs(r) < target && s >= cap) break;  // every depth at its cap
    if (r == 0.0) break;                          // the fault changes nothing
    double power = 1.0;
    if (s_prev > 0.0 && r_prev != 0.0 && s_prev != s) {
      power = std::log(std::abs(r) / std::abs(r_prev)) / std::log(s / s_prev);
      if (!std::isfinite(power) || power < 0.3) power = 1.0;
      power = std::min(power, 8.0);
    }
    double next = s * std::pow(target / std::abs(r), 1.0 / power);
    next = std::clamp(next, 0.1 * s, 10.0 * s);
    if (lo > 0.0 && hi > 0.0 && !(next > lo && next < hi)) next = std::sqrt(lo * hi);
    next = std::min(next, cap);
    if (next == s) break;
    s_prev = s;
    r_prev = r;
    s = next;
    r = evaluate(s);
  }
  fit.scale = s;
  fit.rms_change = r;
  if (best.scale != scale_) ScaleFaultSeverity(best.scale);
  pending_ = std::move(best);
  return fit;
}

void ParametricPlantSimulator::NextBlock(bool fault_on, AccelBlock& block) {
  const std::uint32_t len = config_.block_length;
  if (pending_ && pending_->fault_on == fault_on && (!fault_on || pending_->scale == scale_)) {
    scratch_ = std::move(pending_->block);
    run_ = std::move(pending_->after);
  } else {
    Advance(run_, fault_on, len, &scratch_);
  }
  pending_.reset();
  const std::int64_t first = static_cast<std::int64_t>(blocks_) * len;
  disturbances_.AddUnmodelled(first, blocks_, reference_rms_, scratch_);
  header_.Stamp(blocks_, len, channels_, block);
  disturbances_.WriteWithNoise(blocks_, reference_rms_, scratch_, block.samples);
  ++blocks_;
}

}  // namespace gearpath
