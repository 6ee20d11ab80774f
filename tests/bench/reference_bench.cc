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
#include <sys/resource.h>

#include <chrono>
#include <complex>
#include <ctime>
#include <string>
#include <vector>

#include "core/dsp/spectrum.h"
#include "core/inverse/identification_operator.h"
#include "core/pipeline/block_processor.h"
#include "core/pipeline/frf_grid_mapping.h"
#include "tests/bench/reference_workload.h"

namespace gearpath {
namespace {

using reference::kFs;
using reference::ReferenceBlock;
using reference::ReferenceSetup;

// Args: channels, samples per channel, tracking (ReferenceSetup), drift (ReferenceBlock).
// The reference machine of the benchmark's args (channels, samples, tracking, drift), built,
// prepared and past its baseline, so every further block is scored as in service. `block` is
// its block and `seq` the last sequence number used. An error is the benchmark's skip reason.
Result<BlockProcessor> WarmedUpMachine(const benchmark::State& state, AccelBlock& block,
                                       std::uint64_t& seq) {
  const auto channels = static_cast<int>(state.range(0));
  const auto n = static_cast<std::uint32_t>(state.range(1));
  MachineSetup setup = ReferenceSetup(channels, static_cast<int>(state.range(2)));
  block = ReferenceBlock(setup.frf_set, n, state.range(3) != 0);
  auto processor = BlockProcessor::Create(std::move(setup));
  if (!processor.ok()) return Error{processor.error()};
  if (Status s = processor->Prepare(n); !s) return Error{s.error()};
  BlockResult result;
  for (int i = 0; i < 21; ++i) {
    block.sequence = ++seq;
    (void)processor->Process(block.view(), result);
  }
  return processor;
}

void BM_ReferenceBlock(benchmark::State& state) {
  const auto n = static_cast<std::uint32_t>(state.range(1));
  AccelBlock block;
  std::uint64_t seq = 0;
  auto processor = WarmedUpMachine(state, block, seq);
  if (!processor.ok()) {
    state.SkipWithError(processor.error().c_str());
    return;
  }
  BlockResult result;
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

// The same blocks with the processor's per-stage timing on: one counter per part of Process()
// (validation, then every stage), in ms of wall clock per block (the mean over the timed
// blocks; with --benchmark_repetitions the aggregates are taken over the repetitions' means),
// their sum, and cpu_over_wall (multiply a stage's figure by it for its CPU time on a loaded
// machine). Since issue 9 the residual and the path energies are computed in the
// identification pass (path_energy keeps the shares and the criterion).
void BM_ReferenceStages(benchmark::State& state) {
  AccelBlock block;
  std::uint64_t seq = 0;
  auto processor = WarmedUpMachine(state, block, seq);
  if (!processor.ok()) {
    state.SkipWithError(processor.error().c_str());
    return;
  }
  BlockResult result;
  processor->set_stage_timing(true);
  processor->ResetStageTimes();
  const auto wall0 = std::chrono::steady_clock::now();
  const std::clock_t cpu0 = std::clock();
  for (auto _ : state) {
    block.sequence = ++seq;
    const ProcessOutcome o = processor->Process(block.view(), result);
    benchmark::DoNotOptimize(o.reason);
  }
  // The stage times are wall clock: on a loaded machine they include preemption. This ratio of
  // the loop's CPU time to its wall time scales them to CPU time (preemption falls on every
  // stage in proportion to its length).
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  const double cpu = static_cast<double>(std::clock() - cpu0) / CLOCKS_PER_SEC;
  state.counters["cpu_over_wall"] = wall > 0.0 ? cpu / wall : 0.0;
  double sum = 0.0;
  for (const StageTime& t : processor->stage_times()) {
    if (t.blocks == 0) continue;
    const double ms = 1e3 * t.total_s / static_cast<double>(t.blocks);
    state.counters[std::string(t.stage) + "_ms"] = ms;
    sum += ms;
  }
  state.counters["sum_ms"] = sum;
}
BENCHMARK(BM_ReferenceStages)
    ->ArgNames({"channels", "samples", "tracking", "drift"})
    ->Args({12, 16000, 0, 0})
    ->Args({18, 16000, 0, 0})
    ->Args({12, 65536, 0, 0})
    ->Unit(benchmark::kMillisecond);

// The per-bin identification operator alone on the reference block's spectra, every in-range
// bin through IdentificationOperator::Identify, without (figures:0) and with (figures:1) the
// per-bin figures; the difference is the cost of the residual ||x - H F|| (issue 9).
void BM_ReferenceIdentify(benchmark::State& state) {
  const bool figures = state.range(0) != 0;
  constexpr std::uint32_t kN = 16000;
  const MachineSetup setup = ReferenceSetup(12, 0);
  const AccelBlock block = ReferenceBlock(setup.frf_set, kN, false);
  auto map = MapFrfToBlockGrid(setup.frf_set.decoupled, kN, kFs);
  if (!map) {
    state.SkipWithError(map.error().c_str());
    return;
  }
  auto op = IdentificationOperator::Create(*map->in_range, setup.options.identification);
  if (!op) {
    state.SkipWithError(op.error().c_str());
    return;
  }
  const std::size_t channels = block.channels.size();
  const std::size_t bins = kN / 2 + 1;
  std::vector<double> time(channels * kN);
  for (std::size_t i = 0; i < time.size(); ++i) time[i] = block.samples[i];
  std::vector<std::complex<double>> spec(channels * bins);
  auto spectrum = Spectrum::Create(kN, channels, kFs);
  if (!spectrum || !spectrum->Process(time, spec).ok()) {
    state.SkipWithError("spectrum");
    return;
  }
  const Eigen::Index in_range = map->frf.bins();
  Eigen::MatrixXcd x(static_cast<Eigen::Index>(channels), in_range);
  for (Eigen::Index i = 0; i < in_range; ++i) {
    for (std::size_t c = 0; c < channels; ++c) {
      x(static_cast<Eigen::Index>(c), i) = spec[c * bins + map->first_bin + static_cast<std::size_t>(i)];
    }
  }
  Eigen::MatrixXcd forces(op->paths(), in_range);
  BinFigures fig;
  for (auto _ : state) {
    for (Eigen::Index i = 0; i < in_range; ++i) {
      (void)op->Identify(i, x.col(i), forces.col(i), figures ? &fig : nullptr);
    }
    benchmark::DoNotOptimize(forces.data());
  }
}
BENCHMARK(BM_ReferenceIdentify)->ArgName("figures")->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

// A machine's first block after Create + Prepare (as the daemon does at start and before a
// reload's swap), against BM_ReferenceBlock's later blocks: the precompute is not timed, the
// first Process() is (the bar: it costs no more than a normal block). block:0 is a new machine's
// first block (it learns, and takes the machine's one tracking decision, MachineState::
// order_tracking_mode); block:1 times its second block instead (the first processed untimed),
// a learning block like it; block:2 is the first block after a reload: the new processor
// imports what a machine past its baseline learned (as the daemon's reload and a start with a
// state directory do), so it is a scored block like BM_ReferenceBlock's. Counters: the minor
// page faults of the timed block (getrusage) and each stage's wall time in it, in ms (as
// BM_ReferenceStages). drift:1 streams the reference machine with its speed drifting within
// each block, so that the decision tracks it (counter `tracked`).
void BM_ReferenceFirstBlock(benchmark::State& state) {
  const MachineSetup setup = ReferenceSetup(12, 0);
  AccelBlock block = ReferenceBlock(setup.frf_set, 16000, state.range(1) != 0);
  const int variant = static_cast<int>(state.range(0));
  LearnedState learned;
  std::uint64_t seq = 0;
  if (variant == 2) {
    auto warm = BlockProcessor::Create(setup);
    if (!warm.ok() || !warm->Prepare(16000).ok()) {
      state.SkipWithError("create / prepare");
      return;
    }
    BlockResult r;
    for (int i = 0; i < 21; ++i) {
      block.sequence = ++seq;
      (void)warm->Process(block.view(), r);
    }
    learned = warm->ExportLearnedState();
  }
  double faults = 0.0;
  int tracked = -1;
  std::vector<double> stage_ms;
  std::vector<std::string> stage_names;
  for (auto _ : state) {
    state.PauseTiming();
    auto processor = BlockProcessor::Create(setup);
    if (!processor.ok() || !processor->Prepare(16000).ok() ||
        (variant == 2 && !processor->ImportLearnedState(learned).ok())) {
      state.SkipWithError("create / prepare / import");
      return;
    }
    BlockResult result;
    block.sequence = variant == 2 ? seq + 1 : 1;
    if (variant == 1) {
      (void)processor->Process(block.view(), result);
      block.sequence = 2;
    }
    processor->set_stage_timing(true);
    rusage before{};
    getrusage(RUSAGE_SELF, &before);
    state.ResumeTiming();
    const ProcessOutcome o = processor->Process(block.view(), result);
    benchmark::DoNotOptimize(o.reason);
    state.PauseTiming();
    rusage after{};
    getrusage(RUSAGE_SELF, &after);
    faults += static_cast<double>(after.ru_minflt - before.ru_minflt);
    const auto times = processor->stage_times();
    stage_ms.resize(times.size(), 0.0);
    stage_names.resize(times.size());
    for (std::size_t i = 0; i < times.size(); ++i) {
      stage_names[i] = std::string(times[i].stage);
      stage_ms[i] += 1e3 * times[i].total_s;
    }
    tracked = processor->ExportLearnedState().order_tracking_mode;
    processor = Error{"released untimed"};
    state.ResumeTiming();
  }
  const auto iterations = static_cast<double>(state.iterations());
  state.counters["page_faults"] = faults / iterations;
  state.counters["tracked"] = tracked;
  for (std::size_t i = 0; i < stage_ms.size(); ++i) {
    if (stage_ms[i] > 0.0) state.counters[stage_names[i] + "_ms"] = stage_ms[i] / iterations;
  }
}
BENCHMARK(BM_ReferenceFirstBlock)
    ->ArgNames({"block", "drift"})
    ->Args({0, 0})
    ->Args({1, 0})
    ->Args({2, 0})
    ->Args({0, 1})
    ->Args({1, 1})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(5);

// Create + Prepare of the reference machine (the precompute before READY=1). Its per-bin
// operators are built on every hardware thread: the CPU time is that of every thread (the
// single-thread cost), the real time what a machine waits.
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
BENCHMARK(BM_ReferencePrecompute)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3)
    ->MeasureProcessCPUTime()
    ->UseRealTime();

}  // namespace
}  // namespace gearpath
