// Synthetic signals shared by the core/dsp tests: sinusoids, noise, decaying-resonance
// impulse trains. Deterministic (fixed seeds) so a failure reproduces.
#pragma once

#include <cmath>
#include <cstddef>
#include <numbers>
#include <random>
#include <vector>

namespace gearpath::dsp_test {

inline constexpr double kTwoPi = 2.0 * std::numbers::pi;

// A cos(2 pi f n / fs + phi), n = 0..n-1.
inline std::vector<double> Cosine(std::size_t n, double fs, double f, double amplitude,
                                  double phase) {
  std::vector<double> x(n);
  for (std::size_t i = 0; i < n; ++i) {
    x[i] = amplitude * std::cos(kTwoPi * f * static_cast<double>(i) / fs + phase);
  }
  return x;
}

inline std::vector<double> WhiteNoise(std::size_t n, double sigma, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal(0.0, sigma);
  std::vector<double> x(n);
  for (double& v : x) v = normal(rng);
  return x;
}

// Adds a train of impulses at `rate_hz` (first at t0), each exciting a resonance at
// `resonance_hz` with damping ratio `zeta`: a e^{-zeta w t} sin(w_d t) per impulse.
inline void AddResonanceImpulses(std::vector<double>& x, double fs, double rate_hz, double t0,
                                 double resonance_hz, double zeta, double amplitude) {
  const double w = kTwoPi * resonance_hz;
  const double wd = w * std::sqrt(1.0 - zeta * zeta);
  const double duration = std::log(1e4) / (zeta * w);  // down to 1e-4
  for (double t_imp = t0; t_imp < static_cast<double>(x.size()) / fs; t_imp += 1.0 / rate_hz) {
    const auto first = static_cast<std::size_t>(std::ceil(t_imp * fs));
    for (std::size_t i = first; i < x.size(); ++i) {
      const double t = static_cast<double>(i) / fs - t_imp;
      if (t > duration) break;
      x[i] += amplitude * std::exp(-zeta * w * t) * std::sin(wd * t);
    }
  }
}

inline double Rms(const std::vector<double>& x) {
  double s = 0.0;
  for (double v : x) s += v * v;
  return std::sqrt(s / static_cast<double>(x.size()));
}

}  // namespace gearpath::dsp_test
