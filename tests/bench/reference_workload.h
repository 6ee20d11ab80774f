// The reference workload of the performance issue (issue 9), shared by its benchmark
// (reference_bench.cc) and by the recorded-figures regression test
// (tests/core/pipeline/recorded_figures_test.cc): 12 response channels x 12 transfer paths (or
// 18 x 12), 8 kHz, 16 000-sample blocks, MWI K = 50, kurtogram depth 6, an FRF set of 8001 bins
// (0..4000 Hz every 0.5 Hz).
//
// The FRF set is synthetic (a few random housing modes per channel-path pair, well-posed), the
// block a Table-1 train's mesh tones with shaft-rate modulation plus 5 % noise: timing needs
// the shapes, the operators and realistic spectra, not a particular gearbox. Everything is
// seeded (std::mt19937_64), so a given toolchain makes the same set and blocks every run.
#pragma once

#include <cmath>
#include <complex>
#include <cstdint>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "core/diagnosis/train_layout.h"
#include "core/pipeline/block_processor.h"

namespace gearpath::reference {

inline constexpr double kFs = 8000.0;
inline constexpr double kSpeedHz = 10.0;  // input shaft, 600 r/min

inline FrfSet ReferenceFrfSet(int channels, int paths) {
  FrfSet set;
  set.decoupling = "model";
  const char* gears[] = {"G1", "G2", "G3", "G4"};
  // Names appended piece by piece: GCC 12 at -O3 warns (-Wrestrict, a false positive) on
  // "literal" + std::string&&.
  auto numbered = [](const char* prefix, int number) {
    std::string s(prefix);
    s += std::to_string(number);
    return s;
  };
  for (int p = 0; p < paths; ++p) {
    TransferPath tp;
    tp.name = numbered("B", p / 3 + 1);
    tp.name += "xyz"[p % 3];
    tp.direction = std::string(1, "xyz"[p % 3]);
    tp.bearing = numbered("bearing ", p / 3 + 1);
    tp.gears = {gears[(p / 3) % 4]};
    set.paths.push_back(tp);
  }
  for (int c = 0; c < channels; ++c) {
    set.channels.push_back({numbered("A", c / 3 + 1), std::string(1, "xyz"[c % 3])});
  }
  constexpr Eigen::Index kBins = 8001;
  set.decoupled.frequency_hz = Eigen::VectorXd::LinSpaced(kBins, 0.0, 4000.0);
  // Per (channel, path): a sum of three modes with random frequency, damping and gain, plus a
  // direct term on the "own" path so the operator is well posed.
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> fr(300.0, 3500.0), zeta(0.01, 0.04), gain(-1.0, 1.0);
  struct Mode {
    double f, z, g;
  };
  std::vector<Mode> modes(static_cast<std::size_t>(channels * paths * 3));
  for (Mode& m : modes) m = {fr(rng), zeta(rng), gain(rng)};
  set.decoupled.at.assign(kBins, Eigen::MatrixXcd(channels, paths));
  for (Eigen::Index k = 0; k < kBins; ++k) {
    const double w = 2.0 * std::numbers::pi * set.decoupled.frequency_hz[k];
    Eigen::MatrixXcd& h = set.decoupled.at[static_cast<std::size_t>(k)];
    for (int c = 0; c < channels; ++c) {
      for (int p = 0; p < paths; ++p) {
        std::complex<double> v = (c % paths) == p ? 1e-3 : 0.0;
        for (int i = 0; i < 3; ++i) {
          const Mode& m = modes[static_cast<std::size_t>((c * paths + p) * 3 + i)];
          const double wn = 2.0 * std::numbers::pi * m.f;
          v += 1e-3 * m.g * w * w / std::complex<double>(wn * wn - w * w, 2.0 * m.z * wn * w);
        }
        h(c, p) = v;
      }
    }
  }
  return set;
}

// What a block carries besides the two modulated mesh tones and the noise.
struct BlockVariant {
  bool drift = false;            // the speed moves by +/- 0.3 % within the block (a sine)
  std::uint64_t noise_seed = 7;  // the 5 % Gaussian noise
  // A chipped-tooth-like fault on the input shaft: a decaying 1.9 kHz ring once per input-shaft
  // revolution (10 Hz) at this amplitude (0 = none), in every channel.
  double impulse_amplitude = 0.0;
};

// drift: the per-machine tracking decision tracks it and the tracked averages are paid for.
inline AccelBlock ReferenceBlock(const FrfSet& set, std::uint32_t n, const BlockVariant& v) {
  AccelBlock b;
  b.machine_id = "ref";
  b.sample_rate_hz = kFs;
  b.speed_hz = kSpeedHz;
  b.speed_source = SpeedSource::kAcquisition;
  b.samples_per_channel = n;
  for (const ResponseChannel& ch : set.channels) {
    ChannelInfo info;
    info.sensor = ch.sensor;
    info.axis = ch.axis == "x" ? Axis::kX : ch.axis == "y" ? Axis::kY : Axis::kZ;
    b.channels.push_back(info);
  }
  std::mt19937_64 rng(v.noise_seed);
  std::normal_distribution<double> noise(0.0, 0.05);
  b.samples.resize(b.channels.size() * n);
  const double period = n / kFs;
  for (std::size_t c = 0; c < b.channels.size(); ++c) {
    for (std::uint32_t i = 0; i < n; ++i) {
      // Time at constant speed that gives the same shaft angle (integral of the speed ratio).
      const double t = i / kFs - (v.drift ? 0.003 * period / (2.0 * std::numbers::pi) *
                                                std::cos(2.0 * std::numbers::pi * i / kFs / period)
                                          : 0.0);
      // Mesh 1 at 280 Hz modulated at 7 Hz, mesh 2 at 238 Hz: Table 1 at 600 r/min.
      const double phase = static_cast<double>(c);
      double x = (1.0 + 0.2 * std::cos(2.0 * std::numbers::pi * 7.0 * t)) *
                     std::cos(2.0 * std::numbers::pi * 280.0 * t + 0.3 * phase) +
                 0.6 * std::cos(2.0 * std::numbers::pi * 238.0 * t + 0.7 * phase);
      if (v.impulse_amplitude > 0.0) {
        const double since = std::fmod(t * kSpeedHz + 0.25, 1.0) / kSpeedHz;  // s since impact
        x += v.impulse_amplitude * std::exp(-since * 400.0) *
             std::sin(2.0 * std::numbers::pi * 1900.0 * since + phase);
      }
      b.samples[c * n + i] = static_cast<float>(x + noise(rng));
    }
  }
  return b;
}

inline AccelBlock ReferenceBlock(const FrfSet& set, std::uint32_t n, bool drift) {
  BlockVariant v;
  v.drift = drift;
  return ReferenceBlock(set, n, v);
}

// tracking: 0 = the defaults (localisation tracking only), 1 = order tracking of every
// average, 2 = none.
inline MachineSetup ReferenceSetup(int channels, int tracking) {
  MachineSetup setup;
  setup.machine_id = "ref";
  setup.frf_set = ReferenceFrfSet(channels, 12);
  setup.train = TrainLayout::Table1();
  setup.options.sample_rate_hz = kFs;
  setup.options.nominal_speed_hz = kSpeedHz;
  setup.options.identification.iterations = 50;
  setup.options.kurtogram_max_level = 6;
  setup.options.order_tracking = tracking == 1;
  setup.options.localisation_tracking = tracking == 0;
  setup.options.max_samples_per_channel = 1u << 17;
  return setup;
}

}  // namespace gearpath::reference
