// PlantSimulator: blocks of housing accelerations (AccelBlock) of an evaluation plant, built
// from the plant's own TE -> response transfer (PlantDynamics) and mesh excitation
// (PlantExcitation), with measurement noise and optional unmodelled sources.
//
// Synthesis of one block of B samples starting at stream sample n0:
//  1. A segment of S = segment_factor x B samples ending with the block, [n0 + B - S, n0 + B),
//     is synthesised directly at its own times (no periodic chunk, so any speed works): the
//     input-shaft angle theta(t) is integrated analytically from the speed profile, and every
//     stage's TE is evaluated at theta(t_i).
//  2. TE -> real FFT -> times the plant's transfer T_cs(f_k), f_k = k fs / S -> inverse FFT
//     (S points). The healthy TE is band-limited (H mesh harmonics; Create() checks that it
//     stays under fs / 2) and sampled at fs. The fault's deviation from it is sampled
//     te_oversampling (4) times faster and only its bins up to fs / 2 are kept: an ideal
//     anti-aliasing filter (a sharp pulse has content far above fs / 2, which sampling at fs
//     would fold onto frequencies that are no harmonic of the faulty shaft). The DC and Nyquist
//     bins are dropped (a constant TE is a static preload an accelerometer does not see). The FFT
//     makes the convolution circular: the wrap-around transient sits at the start of the segment,
//     and only the last B samples are kept; this is exact as long as the plant's impulse response
//     dies out within S - B samples (modes above ~50 Hz with >= 1 % damping do, at S - B = 1 s).
//  3. Noise, unmodelled sources (pump tones, bursts) and the speed drift: MeasurementDisturbances
//     (measurement_disturbances.h), shared with the time-domain ParametricPlantSimulator. The
//     reference RMS of the noise and the sources is the noise-free HEALTHY first block's.
// Deterministic: same dynamics, excitation and config -> bit-identical blocks.
// Channels are named by the plant (e.g. "p1".."p3", "m1", axis x, as GearboxSimulator does).
#pragma once

#include <Eigen/Dense>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/common/accel_block.h"
#include "core/common/frf_matrix.h"
#include "core/common/result.h"
#include "core/dsp/fft_plan.h"
#include "core/evaluation/measurement_disturbances.h"
#include "core/evaluation/plant_excitation.h"
#include "core/evaluation/simulated_block_header.h"

namespace gearpath {

// The plant's linear transfer from each stage's TE (m) to each measured channel (m/s^2).
class PlantDynamics {
 public:
  virtual ~PlantDynamics() = default;
  virtual int channel_count() const = 0;
  virtual int stage_count() const = 0;
  // channels x stages per bin; frequency_hz >= 0, strictly increasing.
  virtual Result<FrfMatrix> TeTransfer(const Eigen::VectorXd& frequency_hz) const = 0;
};

struct PlantSimulatorConfig {
  std::string machine_id = "plant";
  double sample_rate_hz = 8000.0;
  std::uint32_t block_length = 8192;
  std::uint32_t segment_factor = 2;   // S = factor x block_length, >= 2
  std::uint32_t te_oversampling = 4;  // TE sampled at this multiple of fs, >= 1
  double input_speed_hz = 10.0;       // mean input-shaft speed, reported by every block
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
};

class PlantSimulator {
 public:
  // Validates the config (messages name the field) and computes the transfer on the segment's
  // grid and the reference RMS.
  static Result<PlantSimulator> Create(std::shared_ptr<const PlantDynamics> dynamics,
                                       std::vector<ChannelInfo> channels,
                                       PlantExcitation excitation,
                                       const PlantSimulatorConfig& config);

  const PlantSimulatorConfig& config() const noexcept { return config_; }
  const PlantExcitation& excitation() const noexcept { return excitation_; }
  void ScaleFaultSeverity(double factor) noexcept { excitation_.ScaleSeverity(factor); }
  const std::vector<ChannelInfo>& channels() const noexcept { return channels_; }
  const Eigen::VectorXd& reference_rms() const noexcept { return reference_rms_; }

  // Input-shaft angle (revolutions) at stream sample position `sample` (may be negative).
  double InputRevs(double sample) const noexcept;

  // Noise-free plant response (rows = block_length samples, one column per channel) of the
  // block starting at stream sample `first_sample`; no noise, no unmodelled sources.
  void NoiseFree(std::int64_t first_sample, bool fault_on, Eigen::MatrixXd& out);

  // Writes the next block (noise and unmodelled sources included) and advances the stream.
  void NextBlock(bool fault_on, AccelBlock& block);
  std::uint64_t blocks_written() const noexcept { return blocks_; }

 private:
  explicit PlantSimulator(PlantExcitation excitation) : excitation_(std::move(excitation)) {}

  PlantSimulatorConfig config_;
  PlantExcitation excitation_;
  std::shared_ptr<const PlantDynamics> dynamics_;
  std::vector<ChannelInfo> channels_;
  std::size_t segment_ = 0;
  FrfMatrix transfer_;  // channels x stages on the segment grid
  std::unique_ptr<FftPlan> forward_, forward_fault_, backward_;
  Eigen::MatrixXcd te_spectrum_;  // bins x stages
  Eigen::VectorXd reference_rms_;
  MeasurementDisturbances disturbances_;  // noise and unmodelled sources, fixed per run
  SimulatedBlockHeader header_;  // what every block says about its machine and clock
  SpeedProfile speed_;
  std::uint64_t blocks_ = 0;
  Eigen::MatrixXd scratch_;
};

}  // namespace gearpath
