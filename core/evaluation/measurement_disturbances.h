// MeasurementDisturbances: what every evaluation plant adds on top of its own noise-free
// response, whatever its physics: measurement noise, the unmodelled sources (a pump / fan with
// its own tones, broadband bursts) and the slow speed drift of the input shaft. Shared by the
// frequency-domain PlantSimulator and the time-domain ParametricPlantSimulator so that both
// families see the same disturbances (docs/evaluation.md, "Synthesis").
//
//  - noise: white Gaussian, std = noise_relative x the channel's reference RMS (the RMS of the
//    noise-free HEALTHY first block, fixed for the whole run), drawn per block from
//    (seed, 2^20 + block index);
//  - tones: a pump / fan at its own rate f_p in [17, 31] Hz, not tied to any shaft, with 3
//    tones at f_p x {7 sqrt 2, 13 sqrt 3, 9 pi} (irrational multiples), amplitude tone_level x
//    reference RMS each, amplitude-modulated at f_p (depth 0.3);
//  - bursts: broadband decaying bursts (exp(-t / tau) sin(2 pi f t), f in [400, 3500] Hz, tau
//    in [2, 8] ms, peak burst_level x reference RMS) at Poisson times of rate burst_rate_hz,
//    drawn per block from (seed, 2^21 + block index);
//  - speed drift (SpeedProfile): speed(t) = f_0 (1 + drift sin(2 pi t / T_b + phase)), T_b the
//    block duration, so every block's mean speed is f_0 while the speed moves within it.
// The fixed sources (pump rate, tone phases and gains, burst gains, drift phase) are drawn once
// from (seed, stream 201), in this order.
#pragma once

#include <Eigen/Dense>
#include <cstdint>
#include <vector>

namespace gearpath {

// Input-shaft speed profile: f_0, or f_0 with the slow drift. Angle in revolutions since t = 0.
struct SpeedProfile {
  double mean_hz = 10.0;
  double drift_relative = 0.0;  // 0 = constant speed
  double period_s = 1.0;        // drift period (the block duration)
  double phase = 0.0;

  // Integral of the speed from 0 to t (revolutions); t may be negative.
  double Revs(double t) const noexcept;
  double Hz(double t) const noexcept;        // speed, rev/s
  double HzPerS(double t) const noexcept;    // its time derivative, rev/s^2
};

struct DisturbanceConfig {
  double sample_rate_hz = 8000.0;
  double noise_relative = 0.05;
  bool tones = false;
  bool bursts = false;
  double tone_level = 0.25;
  double burst_level = 2.0;
  double burst_rate_hz = 1.5;
  std::uint64_t seed = 1;
};

// The disturbance settings of a simulator configuration that names them as DisturbanceConfig
// does (PlantSimulatorConfig, ParametricPlantSimulatorConfig).
template <typename SimulatorConfig>
DisturbanceConfig DisturbanceConfigOf(const SimulatorConfig& c) {
  DisturbanceConfig dc;
  dc.sample_rate_hz = c.sample_rate_hz;
  dc.noise_relative = c.noise_relative;
  dc.tones = c.tones;
  dc.bursts = c.bursts;
  dc.tone_level = c.tone_level;
  dc.burst_level = c.burst_level;
  dc.burst_rate_hz = c.burst_rate_hz;
  dc.seed = c.seed;
  return dc;
}

class MeasurementDisturbances {
 public:
  MeasurementDisturbances() = default;
  MeasurementDisturbances(const DisturbanceConfig& config, Eigen::Index channels);

  // Phase of the speed drift (drawn with the sources, used or not).
  double drift_phase() const noexcept { return drift_phase_; }

  // Adds the enabled tones and bursts to the noise-free block starting at stream sample
  // first_sample (rows = samples, one column per channel); block_index seeds the bursts.
  void AddUnmodelled(std::int64_t first_sample, std::uint64_t block_index,
                     const Eigen::VectorXd& reference_rms, Eigen::MatrixXd& signal) const;

  // Writes signal + noise as float samples, channel-major (samples[ch * rows + i]).
  void WriteWithNoise(std::uint64_t block_index, const Eigen::VectorXd& reference_rms,
                      const Eigen::MatrixXd& signal, std::vector<float>& samples) const;

 private:
  DisturbanceConfig config_;
  double pump_hz_ = 0.0;
  std::vector<double> tone_hz_, tone_phase_;
  Eigen::MatrixXd tone_gain_;   // channels x tones
  Eigen::VectorXd burst_gain_;  // per channel
  double drift_phase_ = 0.0;
};

}  // namespace gearpath
