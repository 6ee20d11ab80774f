// Cost of the evaluation's time-domain plant (core/evaluation/parametric_plant_simulator.h): one
// faulty parametric_plate scenario's stream (20 healthy blocks, the severity fit, 5 faulty blocks
// of 8192 samples, the daemon's processing not included). It bounds how many held-out scenarios
// a CI slice can afford (~1.5 s each when this was written); measured here, not asserted in a
// unit test, since sanitizer builds and a loaded machine multiply it.
#include <benchmark/benchmark.h>

#include <memory>

#include "core/common/accel_block.h"
#include "core/evaluation/evaluation_runner.h"
#include "core/evaluation/parametric_plant_simulator.h"
#include "core/evaluation/parametric_plate_plant.h"
#include "core/model/gear_train.h"

namespace gearpath {
namespace {

void BM_ParametricPlateScenarioStream(benchmark::State& state) {
  const GearTrain train = GearTrain::Table1();
  auto plant = DrawParametricPlatePlant(train, true, 31);
  auto fault = DrawToothFault(plant.value(), train, PlantFaultKind::kCombined, "G2", 31);
  if (!plant.ok() || !fault.ok()) {
    state.SkipWithError("cannot draw the plant or its fault");
    return;
  }
  ParametricSimulatorConfig c;
  c.input_speed_hz = 15.0;
  c.noise_relative = 0.05;
  c.tones = c.bursts = c.speed_drift = true;
  AccelBlock block;
  for (auto _ : state) {
    auto sim = ParametricPlantSimulator::Create(plant->truth, plant->channel_points,
                                                {{"p1"}, {"p2"}, {"p3"}, {"m1"}}, *fault, c);
    if (!sim.ok()) {
      state.SkipWithError(sim.error().c_str());
      return;
    }
    for (int b = 0; b < kBaselineBlocks + kEvaluationBlocks; ++b) {
      if (b == kBaselineBlocks) sim->NormaliseSeverity(0.03);
      sim->NextBlock(b >= kBaselineBlocks, block);
    }
    benchmark::DoNotOptimize(block.samples.data());
  }
}
BENCHMARK(BM_ParametricPlateScenarioStream)->Unit(benchmark::kSecond)->Iterations(3)
    ->MeasureProcessCPUTime();

}  // namespace
}  // namespace gearpath
