// The reference workload of the performance issue through BlockProcessor::Process (validation to
// verdict): 12 response channels x 12 transfer paths, 8 kHz, 2-s blocks (16 000 samples per
// channel), MWI K = 50, kurtogram depth 6, an FRF set of 8001 bins (0..4000 Hz every 0.5 Hz);
// variants with 18 channels and with 65 536-sample blocks; tracking 0 (defaults: localisation
// tracking), 1 (order tracking of every average), 2 (none); drift 1: the speed moves by
// +/- 0.3 % within the block, so the machine is tracked (counter `tracked` = 1). Also
// the cost of making the machine ready: Create + Prepare (per-bin operators, plans, buffers).
// Run: ./build/tests/bench/bench_reference
//
// The FRF set is synthetic (a few random housing modes per channel-path pair, well-posed), the
// block a Table-1 train's mesh tones with shaft-rate modulation plus 5 % noise: timing needs
// the shapes, the operators and realistic spectra, not a particular gearbox.
#include <benchmark/benchmark.h>

#include <cmath>
#include <complex>
#include <numbers>
#include <random>
#include <string>

#include "core/diagnosis/train_layout.h"
#include "core/pipeline/block_processor.h"

namespace gearpath {
namespace {

constexpr double kFs = 8000.0;
constexpr double kSpeedHz = 10.0;  // input shaft, 600 r/min

FrfSet ReferenceFrfSet(int channels, int paths) {
  FrfSet set;
  set.decoupling = "model";
  const char* gears[] = {"G1", "G2", "G3", "G4"};
  for (int p = 0; p < paths; ++p) {
    TransferPath tp;
    tp.name = "B" + std::to_string(p / 3 + 1) + "xyz"[p % 3];
    tp.direction = std::string(1, "xyz"[p % 3]);
    tp.bearing = "bearing " + std::to_string(p / 3 + 1);
    tp.gears = {gears[(p / 3) % 4]};
    set.paths.push_back(tp);
  }
  for (int c = 0; c < channels; ++c) {
    set.channels.push_back({"A" + std::to_string(c / 3 + 1), std::string(1, "xyz"[c % 3])});
  }
  constexpr Eigen::Index kBins = 8001;
  set.decoupled.frequency_hz = Eigen::VectorXd::LinSpaced(kBins, 0.0, 4000.0);
  // Per (channel, path): a sum of three modes with random frequency, damping and gain, plus a
  // direct term on the "own" path so the operator is well posed.
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> fr(300.0, 3500.0), zeta(0.01, 0.04), gain(-1.0, 1.0);
  struct Mode { double f, z, g; };
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

// drift: the speed moves by +/- 0.3 % within the block (a sine over the block), so the
// per-machine tracking decision tracks it and the tracked averages are paid for.
AccelBlock ReferenceBlock(const FrfSet& set, std::uint32_t n, bool drift) {
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
  std::mt19937_64 rng(7);
  std::normal_distribution<double> noise(0.0, 0.05);
  b.samples.resize(b.channels.size() * n);
  const double period = n / kFs;
  for (std::size_t c = 0; c < b.channels.size(); ++c) {
    for (std::uint32_t i = 0; i < n; ++i) {
      // Time at constant speed that gives the same shaft angle (integral of the speed ratio).
      const double t = i / kFs - (drift ? 0.003 * period / (2.0 * std::numbers::pi) *
                                              std::cos(2.0 * std::numbers::pi * i / kFs / period)
                                        : 0.0);
      // Mesh 1 at 280 Hz modulated at 7 Hz, mesh 2 at 238 Hz: Table 1 at 600 r/min.
      const double phase = static_cast<double>(c);
      const double v = (1.0 + 0.2 * std::cos(2.0 * std::numbers::pi * 7.0 * t)) *
                           std::cos(2.0 * std::numbers::pi * 280.0 * t + 0.3 * phase) +
                       0.6 * std::cos(2.0 * std::numbers::pi * 238.0 * t + 0.7 * phase);
      b.samples[c * n + i] = static_cast<float>(v + noise(rng));
    }
  }
  return b;
}

// tracking: 0 = the defaults (localisation tracking only), 1 = order tracking of every
// average, 2 = none.
MachineSetup ReferenceSetup(int channels, int tracking) {
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

// Args: channels, samples per channel, tracking (ReferenceSetup), drift (ReferenceBlock).
void BM_ReferenceBlock(benchmark::State& state) {
  const auto channels = static_cast<int>(state.range(0));
  const auto n = static_cast<std::uint32_t>(state.range(1));
  MachineSetup setup = ReferenceSetup(channels, static_cast<int>(state.range(2)));
  AccelBlock block = ReferenceBlock(setup.frf_set, n, state.range(3) != 0);
  auto processor = BlockProcessor::Create(std::move(setup));
  if (!processor.ok()) {
    state.SkipWithError(processor.error().c_str());
    return;
  }
  if (Status s = processor->Prepare(n); !s) {
    state.SkipWithError(s.error().c_str());
    return;
  }
  BlockResult result;
  std::uint64_t seq = 0;
  // Past the baseline, so every block is scored as in service.
  for (int i = 0; i < 21; ++i) {
    block.sequence = ++seq;
    (void)processor->Process(block.view(), result);
  }
  for (auto _ : state) {
    block.sequence = ++seq;
    const ProcessOutcome o = processor->Process(block.view(), result);
    benchmark::DoNotOptimize(o.reason);
  }
  state.counters["block_s"] = static_cast<double>(n) / kFs;
  // The machine's tracking decision (-1 undecided, 0 constant speed, 1 tracked).
  state.counters["tracked"] = processor->ExportLearnedState().order_tracking_mode;
}
BENCHMARK(BM_ReferenceBlock)
    ->ArgNames({"channels", "samples", "tracking", "drift"})
    ->Args({12, 16000, 0, 0})
    ->Args({12, 16000, 2, 0})
    ->Args({12, 16000, 0, 1})
    ->Args({12, 16000, 1, 1})
    ->Args({18, 16000, 0, 0})
    ->Args({12, 65536, 0, 0})
    ->Unit(benchmark::kMillisecond);

// Create + Prepare of the reference machine (the precompute before READY=1).
void BM_ReferencePrecompute(benchmark::State& state) {
  const MachineSetup setup = ReferenceSetup(12, 0);
  for (auto _ : state) {
    auto processor = BlockProcessor::Create(setup);
    if (!processor.ok()) {
      state.SkipWithError(processor.error().c_str());
      return;
    }
    if (Status s = processor->Prepare(16000); !s) {
      state.SkipWithError(s.error().c_str());
      return;
    }
    benchmark::DoNotOptimize(processor->configured_for(16000));
  }
}
BENCHMARK(BM_ReferencePrecompute)->Unit(benchmark::kMillisecond)->Iterations(3);

}  // namespace
}  // namespace gearpath
