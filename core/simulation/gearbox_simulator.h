// GearboxSimulator: a stream of housing-acceleration blocks (AccelBlock) of a gearbox running
// at constant speed, healthy or with one localized gear fault, with the true bearing forces.
//
// Method. The lumped model (core/model/lumped_gearbox_model.h, seed Eqs. 1-7) is linear and
// time invariant (time-averaged mesh stiffness, as the seed's Eq. 6), so the response is the
// transmission-error (TE) spectrum times the model's TE -> response transfer, bin by bin:
//  1. Every shaft returns to its starting angle after the least common period of the train
//     (GearTrain::InputRevolutionsPerCommonPeriod; 10 input revolutions = 1 s for Table 1 at
//     600 r/min), and so does the TE (core/simulation/fault_excitation.h). The simulator uses a
//     chunk of exactly one common period, N samples. When the period is not a whole number of
//     samples, the input speed is snapped to the nearest speed for which it is (relative
//     change <= 1 / (2 N), e.g. 2.5e-5 for 10.1 Hz at 8 kHz); speed_hz() and the blocks report
//     the snapped speed.
//  2. TE of every stage sampled over the chunk -> real FFT -> times the model's transfer at
//     f_k = k fs / N -> inverse FFT: one period of the steady-state seat and housing
//     accelerations and bearing forces. Because everything is periodic over the chunk, the
//     circular convolution of the FFT is the exact steady state, and the chunk repeats
//     seamlessly: the stream is the chunk repeated forever (computed once, at Create()).
//     The 0 Hz bin is dropped (a constant TE only changes the static preload, which an
//     accelerometer does not see) and so is the Nyquist bin (a real sinusoid at exactly fs/2
//     has no well-defined phase); both carry nothing for the defaults.
//  3. Per block: the next samples of the periodic chunk plus white Gaussian measurement noise
//     (independent per channel and sample) of standard deviation noise_relative times the RMS
//     of that channel's noise-free signal, drawn from a seeded generator
//     (core/simulation/deterministic_rng.h): same config -> bit-identical blocks.
//
// Channels (Table 1 naming, one axis "x" = the line of action, as the lumped model):
//   "p1", "p2", "p3" ... : bearing seats s_0 ... s_N (the seed's x4, x5, x6; 'p' points),
//   "m1"                 : the central housing mass (the seed's x7; the 'm' point), unless
//                          include_housing_channel is false.
// Bearing forces: one per seat, force of bearing i on seat i (seed Eq. 44), N.
//
// Consistency: the gear train must describe the model: stage s drives from shaft s to shaft
// s + 1 with the model's tooth counts, and one bearing per shaft in shaft order (bearing i
// supports shaft i = model rotor i). CheckTrainMatchesModel() says which field disagrees.
#pragma once

#include <Eigen/Dense>
#include <cstdint>
#include <string>
#include <vector>

#include "core/common/accel_block.h"
#include "core/common/result.h"
#include "core/model/gear_train.h"
#include "core/model/lumped_gearbox_model.h"
#include "core/simulation/deterministic_rng.h"
#include "core/simulation/fault_excitation.h"

namespace gearpath {

struct SimulatorConfig {
  std::string machine_id = "sim";
  GearFault fault;                      // type kNone = healthy
  double input_speed_hz = 10.0;         // 600 r/min (seed Sec. 4)
  double sample_rate_hz = 8000.0;       // the seed's DH8303 setting
  std::uint32_t block_length = 8192;    // samples per channel and block, >= 1
  double noise_relative = 0.0;          // noise std / noise-free RMS per channel, >= 0
  std::uint64_t seed = 1;               // excitation phases, damaged tooth, noise
  bool report_speed = true;             // blocks carry speed_hz, SpeedSource::kAcquisition
  bool include_housing_channel = true;  // append "m1" (central housing mass)
  std::int64_t start_time_ns = 0;       // t0 of the first block, ns since the Unix epoch
  std::uint64_t first_sequence = 0;
  std::size_t max_period_samples = std::size_t{1} << 23;  // refuse longer common periods
  ExcitationParameters excitation;                        // its seed is overridden by `seed`
};

// Empty status when the train describes the model (see the file comment).
Status CheckTrainMatchesModel(const LumpedGearboxModel& model, const GearTrain& train);

class GearboxSimulator {
 public:
  // Validates the config (messages name the field), checks train vs model, and computes the
  // periodic chunk. Allocates; everything per block afterwards reuses the caller's buffers.
  static Result<GearboxSimulator> Create(const LumpedGearboxModel& model, const GearTrain& train,
                                         const SimulatorConfig& config);

  const SimulatorConfig& config() const noexcept { return config_; }
  const FaultExcitation& excitation() const noexcept { return excitation_; }
  double speed_hz() const noexcept { return speed_hz_; }  // snapped input speed
  const std::vector<ChannelInfo>& channels() const noexcept { return channels_; }
  Eigen::Index seat_count() const noexcept { return bearing_force_.cols(); }

  // One noise-free period (rows = samples, period_samples() of them). Accelerations: one
  // column per channel (channels() order); bearing forces: one column per seat; TE: one
  // column per stage, mean removed, m.
  std::size_t period_samples() const noexcept {
    return static_cast<std::size_t>(acceleration_.rows());
  }
  const Eigen::MatrixXd& periodic_acceleration() const noexcept { return acceleration_; }
  const Eigen::MatrixXd& periodic_bearing_force() const noexcept { return bearing_force_; }
  const Eigen::MatrixXd& periodic_transmission_error() const noexcept { return te_; }
  // Noise standard deviation per channel, m/s^2.
  const Eigen::VectorXd& noise_std() const noexcept { return noise_std_; }

  // Writes the next block into `block` (its vectors are resized only when their size differs,
  // so a reused block allocates nothing after the first call). If `bearing_forces` is not
  // null it receives the true bearing forces of the same samples, planar (seat-major,
  // seat_count() * block_length values), noise-free.
  void NextBlock(AccelBlock& block, std::vector<double>* bearing_forces = nullptr);

  // Index of the next sample in the stream (0 at Create()); Rewind() restarts the stream,
  // noise included, so a rewound simulator repeats its blocks exactly.
  std::uint64_t position() const noexcept { return position_; }
  void Rewind() noexcept;

 private:
  GearboxSimulator(FaultExcitation excitation) : excitation_(std::move(excitation)) {}

  SimulatorConfig config_;
  FaultExcitation excitation_;
  double speed_hz_ = 0.0;
  std::vector<ChannelInfo> channels_;
  Eigen::MatrixXd acceleration_;   // period x channels
  Eigen::MatrixXd bearing_force_;  // period x seats
  Eigen::MatrixXd te_;             // period x stages
  Eigen::VectorXd noise_std_;
  std::uint64_t position_ = 0;
  std::uint64_t blocks_ = 0;
  DeterministicRng noise_{0, 0};
};

}  // namespace gearpath
