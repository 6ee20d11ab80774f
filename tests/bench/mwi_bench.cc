// Per-block cost of bearing-force identification (IdentificationOperator), by rule: the
// precomputed operator (noise_floor: one mat-vec per bin) against per-block GCV.
#include <benchmark/benchmark.h>

#include <random>

#include "core/inverse/identification_operator.h"

namespace gearpath {
namespace {

FrfMatrix RandomFrf(Eigen::Index channels, Eigen::Index paths, int bins) {
  std::mt19937_64 engine(7);
  std::normal_distribution<double> normal;
  FrfMatrix frf;
  frf.frequency_hz = Eigen::VectorXd::LinSpaced(bins, 1.0, 4000.0);
  for (int k = 0; k < bins; ++k) {
    Eigen::MatrixXcd h(channels, paths);
    for (Eigen::Index j = 0; j < paths; ++j) {
      for (Eigen::Index i = 0; i < channels; ++i) h(i, j) = {normal(engine), normal(engine)};
    }
    frf.at.push_back(h);
  }
  return frf;
}

void IdentifyAllBins(benchmark::State& state, RegularisationRule rule) {
  const Eigen::Index channels = state.range(0);
  const Eigen::Index paths = state.range(1);
  constexpr int kBins = 2049;
  const FrfMatrix frf = RandomFrf(channels, paths, kBins);
  IdentificationOptions options;
  options.regularisation.rule = rule;
  IdentificationOperator op = IdentificationOperator::Create(frf, options).value();
  const Eigen::MatrixXcd x = Eigen::MatrixXcd::Random(channels, kBins);
  Eigen::MatrixXcd forces(paths, kBins);
  for (auto _ : state) {
    benchmark::DoNotOptimize(op.IdentifyAll(x, forces));
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * kBins);
}

void BM_NoiseFloorPrecomputed(benchmark::State& state) {
  IdentifyAllBins(state, RegularisationRule::kNoiseFloor);
}
void BM_GcvPerBlock(benchmark::State& state) { IdentifyAllBins(state, RegularisationRule::kGcv); }

BENCHMARK(BM_NoiseFloorPrecomputed)->Args({3, 3})->Args({4, 3})->Args({18, 12});
BENCHMARK(BM_GcvPerBlock)->Args({4, 3})->Args({18, 12});

}  // namespace
}  // namespace gearpath
