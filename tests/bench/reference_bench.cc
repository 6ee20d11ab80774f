// The reference workload of the performance issue through BlockProcessor::Process (validation to
// verdict): 12 response channels x 12 transfer paths, 8 kHz, 2-s blocks (16 000 samples per
// channel), MWI K = 50, kurtogram depth 6, an FRF set of 8001 bins (0..4000 Hz every 0.5 Hz);
// variants with 18 channels and with 65 536-sample blocks; tracking 0 (defaults: localisation
// tracking), 1 (order tracking of every average), 2 (none); drift 1: the speed moves by
// +/- 0.3 % within the block, so the machine is tracked (counter `tracked` = 1). Also
// the cost of making the machine ready: Create + Prepare (per-bin operators, plans, buffers).
// Run: ./build/tests/bench/bench_reference
//
// The FRF set, the block and the set-up are tests/bench/reference_workload.h (shared with the
// recorded-figures regression test).
#include <benchmark/benchmark.h>

#include <string>

#include "core/pipeline/block_processor.h"
#include "tests/bench/reference_workload.h"

namespace gearpath {
namespace {

using reference::kFs;
using reference::ReferenceBlock;
using reference::ReferenceSetup;

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
