// DeterministicRng: a seeded random source whose output is fixed by the C++ standard.
//
// std::mt19937_64's sequence is specified bit for bit by the standard, but the standard
// distributions (uniform_real_distribution, normal_distribution) are not: libstdc++ and libc++
// give different numbers for the same engine state. Simulated signals must be reproducible
// from their seed on any toolchain, so the conversions are written out here: uniform doubles
// from the top 53 bits, Gaussians by the Box-Muller transform. Sub-seeds for independent
// streams (phases, noise) come from SplitMix64 (Steele, Lea & Flood, OOPSLA 2014).
#pragma once

#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>

namespace gearpath {

// SplitMix64 finaliser: a well-mixed 64-bit value from (seed, stream).
constexpr std::uint64_t SplitMix64(std::uint64_t x) noexcept {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

class DeterministicRng {
 public:
  DeterministicRng(std::uint64_t seed, std::uint64_t stream) noexcept
      : engine_(SplitMix64(seed ^ SplitMix64(stream))) {}

  // Uniform in [0, 1).
  double Uniform() noexcept { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }

  // Standard normal (mean 0, variance 1), Box-Muller; the second variate is kept for the
  // next call.
  double Gaussian() noexcept {
    if (has_spare_) {
      has_spare_ = false;
      return spare_;
    }
    const double u1 = 1.0 - Uniform();  // (0, 1]: log is finite
    const double u2 = Uniform();
    const double r = std::sqrt(-2.0 * std::log(u1));
    spare_ = r * std::sin(2.0 * std::numbers::pi * u2);
    has_spare_ = true;
    return r * std::cos(2.0 * std::numbers::pi * u2);
  }

  // Uniform integer in [0, n), n >= 1 (modulo bias < n / 2^64, irrelevant here).
  std::uint64_t Below(std::uint64_t n) noexcept { return engine_() % n; }

 private:
  std::mt19937_64 engine_;
  double spare_ = 0.0;
  bool has_spare_ = false;
};

}  // namespace gearpath
