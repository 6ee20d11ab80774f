// Per-block cost of bearing-force identification (IdentificationOperator), by rule: the
// precomputed operator (noise_floor: one mat-vec per bin) against per-block GCV. And the
// cost of building the operator (IdentificationOperator::Create) by thread count.
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

// The per-bin SVDs of an 8001-bin 12 x 12 set, MWI K = 50 (the reference workload's operator
// alone, without the rest of BlockProcessor::Prepare). threads 0 = one per hardware thread.
void BM_CreateOperator(benchmark::State& state) {
  const FrfMatrix frf = RandomFrf(12, 12, 8001);
  IdentificationOptions options;
  options.iterations = 50;
  const auto threads = static_cast<unsigned>(state.range(0));
  for (auto _ : state) {
    Result<IdentificationOperator> op = IdentificationOperator::Create(frf, options, threads);
    benchmark::DoNotOptimize(op.ok());
  }
  state.SetItemsProcessed(state.iterations() * frf.bins());
}
BENCHMARK(BM_CreateOperator)->ArgName("threads")->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace gearpath
