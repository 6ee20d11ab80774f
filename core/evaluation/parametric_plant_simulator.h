// ParametricPlantSimulator: the time-domain PlantStream of the parametric_plate family.
//
// One continuous simulation per scenario:
//  1. The ParametricGearbox is integrated (GearboxIntegrator, Newmark average acceleration) at
//     oversampling x fs (8 x 8 kHz = 64 kHz). At every step t: the input angle from the speed
//     profile (SpeedProfile: f_0, or f_0 with the slow drift, which thereby drives the motor
//     angle), each shaft's angle, each mesh's stiffness and errors (ToothMesh; the tooth fault
//     while fault_on), the load and inertial forcing.
//  2. The plate's normal accelerations at the channel points go through an AntiAliasDecimator
//     (Kaiser FIR cascade, pass 0.45 fs, 100 dB stop above fs / 2, zero phase) down to fs.
//  3. The simulation starts run_in_s before t = 0 from the static equilibrium (consistent, at
//     rest) and the outputs before t = 0 are dropped, so blocks begin in steady state. The state
//     (integrator and decimator) carries from block to block: the stream is continuous; a
//     fault switched on at a block boundary starts there.
//  4. Noise and unmodelled sources: MeasurementDisturbances, exactly as PlantSimulator (the
//     reference RMS is the noise-free healthy first block's).
// Severity (NormaliseSeverity): the response is not linear in the depths (the crack is a
// parametric fault, its effect grows about as d^2..d^3; contact loss saturates a deep spall), so
// the common depth factor s is found by secant steps on log |r(s)| against log s, r(s) = the
// signed raw RMS change of the most affected channel on the next block (noise-free, from the
// current state, faulty vs healthy): a power law is solved in one step, the first step assumes
// r proportional to s, steps stay inside the bracket once found; until |r| is within 1 % of the
// target, s reaches the factor at which every depth is capped, or 8 evaluations. (A spall
// deeper than the pair's approach unloads that pair: its effect saturates, and the secant then
// walks to the cap.)
// Deterministic: same plant, fault and config -> bit-identical blocks.
#pragma once

#include <Eigen/Dense>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/evaluation/anti_alias_decimator.h"
#include "core/evaluation/gearbox_integrator.h"
#include "core/evaluation/measurement_disturbances.h"
#include "core/evaluation/plant_stream.h"
#include "core/evaluation/simulated_block_header.h"

namespace gearpath {

struct ParametricSimulatorConfig {
  std::string machine_id = "plant";
  double sample_rate_hz = 8000.0;
  std::uint32_t block_length = 8192;
  std::uint32_t oversampling = 8;  // integration steps per output sample: 2^K, >= 8
  double run_in_s = 0.5;
  double pass_fraction = 0.45;     // anti-alias pass band edge, x fs
  double attenuation_db = 100.0;   // anti-alias stop band
  double input_speed_hz = 10.0;    // mean input-shaft speed, reported by every block
  double noise_relative = 0.05;
  bool tones = false;
  bool bursts = false;
  bool speed_drift = false;
  double drift_relative = 0.003;
  double tone_level = 0.25;
  double burst_level = 2.0;
  double burst_rate_hz = 1.5;
  std::uint64_t seed = 1;  // noise, unmodelled sources
  std::int64_t start_time_ns = 0;
  std::uint64_t first_sequence = 0;
  bool constant_stiffness = false;  // tests: every mesh at its mean stiffness (LTI limit)
};

class ParametricPlantSimulator final : public PlantStream {
 public:
  // Validates the config (messages name the field), the channel points and the fault, sets the
  // static equilibrium, runs the run-in and the first (healthy) block for the reference RMS.
  static Result<ParametricPlantSimulator> Create(std::shared_ptr<const ParametricGearbox> gearbox,
                                                 std::vector<int> channel_points,
                                                 std::vector<ChannelInfo> channels,
                                                 ToothFault fault,
                                                 const ParametricSimulatorConfig& config);

  SeverityFit NormaliseSeverity(double target) override;
  PlantFaultSeverity severity() const override { return fault_.severity; }
  void NextBlock(bool fault_on, AccelBlock& block) override;

  // The next block, noise-free, without advancing the stream (rows = samples).
  void NoiseFreeNext(bool fault_on, Eigen::MatrixXd& out) const;
  // Depths = defaults x factor, each clamped to its cap.
  void ScaleFaultSeverity(double factor) noexcept;
  // The factor at which every depth of the fault's kind is at its cap (0 for no fault).
  double CapFactor() const noexcept;

  const ParametricSimulatorConfig& config() const noexcept { return config_; }
  const ToothFault& fault() const noexcept { return fault_; }
  const ParametricGearbox& gearbox() const noexcept { return *gearbox_; }
  const Eigen::VectorXd& reference_rms() const noexcept { return reference_rms_; }
  const SpeedProfile& speed() const noexcept { return speed_; }
  std::uint64_t blocks_written() const noexcept { return blocks_; }
  double step_s() const noexcept { return step_s_; }
  // Elastic mesh force of each stage at rest, at the start (N; positive = loaded flanks
  // compressed).
  const std::vector<double>& static_mesh_force() const noexcept { return static_mesh_force_; }

 private:
  struct Run {
    GearboxIntegrator integrator;
    AntiAliasDecimator decimator;
    std::int64_t step = 0;     // integration steps taken
    std::int64_t outputs = 0;  // decimator outputs produced (run-in included)
  };
  ParametricPlantSimulator() = default;
  // Integrates until `count` more outputs exist; writes them to out (count x channels) unless
  // out is null. fault_on applies the tooth fault.
  void Advance(Run& run, bool fault_on, std::int64_t count, Eigen::MatrixXd* out) const;
  void Evaluate(std::int64_t step, bool fault_on, std::vector<MeshSample>& mesh,
                Eigen::VectorXd& force) const;

  ParametricSimulatorConfig config_;
  std::shared_ptr<const ParametricGearbox> gearbox_;
  std::vector<int> channel_points_;
  std::vector<ChannelInfo> channels_;
  ToothFault fault_;
  PlantFaultSeverity default_severity_;
  double scale_ = 1.0;
  SpeedProfile speed_;
  MeasurementDisturbances disturbances_;
  SimulatedBlockHeader header_;  // what every block says about its machine and clock
  double step_s_ = 0.0;
  std::int64_t run_in_steps_ = 0;
  Run run_;
  std::vector<double> static_mesh_force_;
  Eigen::VectorXd reference_rms_;
  std::uint64_t blocks_ = 0;
  // A block already simulated ahead (by Create or NormaliseSeverity) and the run after it.
  struct Pending {
    bool fault_on = false;
    double scale = 1.0;
    Eigen::MatrixXd block;
    Run after;
  };
  std::optional<Pending> pending_;
  Eigen::MatrixXd scratch_;
};

}  // namespace gearpath
