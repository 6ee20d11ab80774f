// One block through the core/dsp chain at a typical size: 8 channels x 16384 samples at 8 kHz
// (2.048 s), spectra of all channels, then on one (the dominant path's) time signal: fast
// kurtogram of depth 6, band-pass of its best band, squared envelope spectrum and the
// five-harmonic indicator. Run: ./build-<you>/tests/bench/bench_dsp
#include <benchmark/benchmark.h>

#include <cmath>
#include <complex>
#include <numbers>
#include <random>
#include <vector>

#include "core/dsp/band_pass.h"
#include "core/dsp/envelope_spectrum.h"
#include "core/dsp/harmonic_indicator.h"
#include "core/dsp/kurtogram.h"
#include "core/dsp/order_tracker.h"
#include "core/dsp/spectrum.h"

namespace gearpath {
namespace {

constexpr double kFs = 8000.0;
constexpr std::size_t kN = 16384;
constexpr std::size_t kChannels = 8;

// Noise, mesh tones and a 10 Hz train of 2500 Hz resonance ringings, like a faulty gear.
std::vector<double> Signal(std::size_t channels, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::vector<double> x(channels * kN);
  const double w = 2.0 * std::numbers::pi;
  for (std::size_t c = 0; c < channels; ++c) {
    for (std::size_t i = 0; i < kN; ++i) {
      const double t = static_cast<double>(i) / kFs;
      double v = normal(rng);
      for (int h = 1; h <= 6; ++h) v += 10.0 / h * std::cos(w * 280.0 * h * t + h * h);
      const double since = std::fmod(t, 0.1);
      v += 3.0 * std::exp(-0.02 * w * 2500.0 * since) * std::sin(w * 2500.0 * since);
      x[c * kN + i] = v;
    }
  }
  return x;
}

void BM_SpectrumEightChannels(benchmark::State& state) {
  auto spectrum = Spectrum::Create(kN, kChannels, kFs).value();
  const auto x = Signal(kChannels, 1);
  std::vector<std::complex<double>> s(spectrum.bin_count() * kChannels);
  for (auto _ : state) {
    benchmark::DoNotOptimize(spectrum.Process(x, s).ok());
    benchmark::ClobberMemory();
  }
}
BENCHMARK(BM_SpectrumEightChannels)->Unit(benchmark::kMicrosecond);

void BM_Kurtogram(benchmark::State& state) {
  KurtogramOptions options;
  options.depth = 6;
  options.whitening =
      state.range(0) != 0 ? KurtogramWhitening::kAutoregressive : KurtogramWhitening::kNone;
  auto kurtogram = Kurtogram::Create(kN, kFs, options).value();
  const auto x = Signal(1, 2);
  for (auto _ : state) benchmark::DoNotOptimize(kurtogram.Process(x).ok());
  state.SetLabel(state.range(0) != 0 ? "depth 6, AR(64) whitening" : "depth 6, no whitening");
}
BENCHMARK(BM_Kurtogram)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

void BM_BandPass(benchmark::State& state) {
  auto band_pass = BandPass::Create(kN, kFs, 50.0).value();
  const auto x = Signal(1, 3);
  std::vector<double> y(kN);
  for (auto _ : state) benchmark::DoNotOptimize(band_pass.Process(x, 2300.0, 2700.0, y).ok());
}
BENCHMARK(BM_BandPass)->Unit(benchmark::kMicrosecond);

void BM_EnvelopeSpectrum(benchmark::State& state) {
  auto ses = EnvelopeSpectrum::Create(kN, kFs).value();
  const auto x = Signal(1, 4);
  std::vector<double> out(ses.bin_count());
  for (auto _ : state) benchmark::DoNotOptimize(ses.Process(x, out).ok());
}
BENCHMARK(BM_EnvelopeSpectrum)->Unit(benchmark::kMicrosecond);

// The whole per-block chain: what one block costs the daemon in core/dsp.
void BM_OneBlockChain(benchmark::State& state) {
  auto spectrum = Spectrum::Create(kN, kChannels, kFs).value();
  KurtogramOptions options;
  options.depth = 6;
  options.min_bandwidth_hz = 100.0;  // 10 x a 10 Hz shaft rate
  auto kurtogram = Kurtogram::Create(kN, kFs, options).value();
  auto band_pass = BandPass::Create(kN, kFs, 50.0).value();
  auto ses = EnvelopeSpectrum::Create(kN, kFs).value();
  const auto x = Signal(kChannels, 5);
  std::vector<std::complex<double>> s(spectrum.bin_count() * kChannels);
  std::vector<double> filtered(kN);
  std::vector<double> envelope_spectrum(ses.bin_count());
  const std::span<const double> path(x.data(), kN);
  for (auto _ : state) {
    if (!spectrum.Process(x, s).ok()) state.SkipWithError("spectrum");
    auto band = kurtogram.Process(path);
    if (!band.ok()) state.SkipWithError("kurtogram");
    if (!band_pass.Process(path, band->low_hz, band->high_hz, filtered).ok()) {
      state.SkipWithError("band-pass");
    }
    if (!ses.Process(filtered, envelope_spectrum).ok()) state.SkipWithError("ses");
    auto result = ComputeHarmonicIndicator(envelope_spectrum, ses.bin_hz(), 10.0);
    if (!result.ok()) state.SkipWithError("indicator");
    benchmark::DoNotOptimize(result->sum);
  }
  state.counters["blocks_per_s"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_OneBlockChain)->Unit(benchmark::kMillisecond);

// One tacho-less order track of a reference-sized block (16 000 samples at 8 kHz): a 300 Hz
// mesh tone whose speed drifts by +/- 0.3 % within the block, 5 % noise, the band +/- 5.25 Hz
// (3/4 of a 7 Hz shaft), three iterations. A tracked machine runs one per carrier and block
// (up to nine), and a new machine's first block does too, for its tracking decision.
void BM_OrderTrack(benchmark::State& state) {
  constexpr std::size_t n = 16000;
  auto tracker = OrderTracker::Create(n, kFs).value();
  std::mt19937_64 rng(6);
  std::normal_distribution<double> normal(0.0, 0.05);
  std::vector<double> x(n);
  const double w = 2.0 * std::numbers::pi;
  for (std::size_t i = 0; i < n; ++i) {
    const double t = static_cast<double>(i) / kFs;
    const double angle = 300.0 * (t - 0.003 / (w * 0.5) * std::cos(w * 0.5 * t));
    x[i] = std::cos(w * angle) + normal(rng);
  }
  std::vector<double> warp(n);
  for (auto _ : state) {
    if (!tracker.TryTrack(x, 300.0, 5.25, warp)) state.SkipWithError("track");
    benchmark::DoNotOptimize(warp.data());
  }
}
BENCHMARK(BM_OrderTrack)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace gearpath
