// Speed of the simulator (construction = one period's FFT synthesis; one block) and of the
// per-block path contributions (seed Eq. 45) at the seed's experimental size (12 channels x
// 12 paths) on an 8192-sample block's bins.
#include <benchmark/benchmark.h>

#include <complex>
#include <random>
#include <vector>

#include "core/diagnosis/path_contributions.h"
#include "core/simulation/gearbox_simulator.h"

namespace gearpath {
namespace {

const LumpedGearboxModel& Table1Model() {
  static const LumpedGearboxModel model = LumpedGearboxModel::Create(Table1Parameters()).value();
  return model;
}

SimulatorConfig Config() {
  SimulatorConfig c;
  c.fault = {FaultType::kToothFracture, "G2", 1.0};
  c.noise_relative = 0.05;
  return c;
}

void BM_SimulatorCreate(benchmark::State& state) {
  for (auto _ : state) {
    Result<GearboxSimulator> sim =
        GearboxSimulator::Create(Table1Model(), GearTrain::Table1(), Config());
    benchmark::DoNotOptimize(sim.ok());
  }
}
BENCHMARK(BM_SimulatorCreate)->Unit(benchmark::kMillisecond);

void BM_SimulatorNextBlock(benchmark::State& state) {
  GearboxSimulator sim =
      GearboxSimulator::Create(Table1Model(), GearTrain::Table1(), Config()).value();
  AccelBlock block;
  for (auto _ : state) {
    sim.NextBlock(block);
    benchmark::DoNotOptimize(block.samples.data());
  }
  state.SetItemsProcessed(state.iterations() * 8192 * 4);
}
BENCHMARK(BM_SimulatorNextBlock)->Unit(benchmark::kMicrosecond);

void BM_PathContributions12x12(benchmark::State& state) {
  const Eigen::Index channels = 12, paths = 12, bins = 4097;
  std::mt19937 rng(1);
  std::normal_distribution<double> n;
  std::vector<Eigen::MatrixXcd> h(static_cast<std::size_t>(bins),
                                  Eigen::MatrixXcd(channels, paths));
  for (auto& hk : h) {
    for (Eigen::Index i = 0; i < hk.size(); ++i) hk.data()[i] = {n(rng), n(rng)};
  }
  Eigen::MatrixXcd forces(paths, bins);
  for (Eigen::Index i = 0; i < forces.size(); ++i) forces.data()[i] = {n(rng), n(rng)};
  PathContributions pc = PathContributions::Create(channels, paths, bins).value();
  PathEnergy energy = pc.MakeEnergy();
  for (auto _ : state) {
    benchmark::DoNotOptimize(pc.Compute(h, forces));
    benchmark::DoNotOptimize(pc.Energy(0, bins, -1, energy));
  }
}
BENCHMARK(BM_PathContributions12x12)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace gearpath
