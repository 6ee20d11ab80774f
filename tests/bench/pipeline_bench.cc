// Speed of one block through BlockProcessor::Process (validation to verdict) on the simulated
// Table-1 gearbox: 3 channels, 3 paths, 8192 samples at 8 kHz, FRFs on every bin. Run:
//   ./build-<you>/tests/bench/bench_pipeline
#include <benchmark/benchmark.h>

#include "core/diagnosis/train_layout.h"
#include "core/model/gear_train.h"
#include "core/model/lumped_gearbox_model.h"
#include "core/pipeline/block_processor.h"
#include "core/simulation/gearbox_simulator.h"
#include "core/simulation/model_frf_set.h"

namespace gearpath {
namespace {

void BM_ProcessBlock(benchmark::State& state) {
  const auto n = static_cast<std::uint32_t>(state.range(0));
  const auto criterion = static_cast<AnalysisOptions::DominantCriterion>(state.range(1));
  constexpr double kFs = 8000.0;
  auto model = LumpedGearboxModel::Create(Table1Parameters());
  const GearTrain train = GearTrain::Table1();
  Eigen::VectorXd f(n / 2);
  for (Eigen::Index k = 0; k < f.size(); ++k) f[k] = static_cast<double>(k + 1) * kFs / n;
  auto set = MakeModelFrfSet(model.value(), train, f);
  MachineSetup setup;
  setup.machine_id = "sim";
  setup.frf_set = set.value();
  setup.train = TrainLayoutFromGearTrain(train).value();
  setup.options.sample_rate_hz = kFs;
  setup.options.nominal_speed_hz = 10.0;
  setup.options.criterion = criterion;
  auto processor = BlockProcessor::Create(setup);
  if (!processor.ok()) {
    state.SkipWithError(processor.error().c_str());
    return;
  }
  SimulatorConfig c;
  c.machine_id = "sim";
  c.fault.type = FaultType::kChippedTooth;
  c.fault.gear = "G2";
  c.block_length = n;
  c.noise_relative = 0.05;
  c.include_housing_channel = false;
  auto sim = GearboxSimulator::Create(model.value(), train, c);
  AccelBlock block;
  BlockResult result;
  sim->NextBlock(block);
  (void)processor->Process(block.view(), result);  // configures the shape
  std::uint64_t seq = block.sequence;
  for (auto _ : state) {
    block.sequence = ++seq;
    const ProcessOutcome o = processor->Process(block.view(), result);
    benchmark::DoNotOptimize(o.reason);
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["block_s"] = static_cast<double>(n) / kFs;
}

BENCHMARK(BM_ProcessBlock)
    ->Args({8192, 0})
    ->Args({16384, 0})
    ->Args({8192, 2})
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace gearpath
