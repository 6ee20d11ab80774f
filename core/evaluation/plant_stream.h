// PlantStream: the block source of one evaluation scenario, whatever the plant's physics. The
// runner (evaluation_runner.h) sees only this: a continuous stream of AccelBlocks, healthy or
// faulty block by block, and one call that normalises the fault's severity at the current
// position of the stream.
//
// Two implementations:
//  - LinearPlantStream (linear_plant_stream.h): the frequency-domain PlantSimulator of the
//    families whose truth is a linear TE -> response transfer (lumped_*, modal_housing); the
//    fault is linear in its depths, so the severity factor is solved exactly.
//  - ParametricPlantSimulator (parametric_plant_simulator.h): the time-domain simulation of
//    the parametric_plate family (time-varying mesh stiffness, plate housing); the response is
//    not linear in the depths, so the factor is found by secant steps.
// MakePlantStream picks the one the plant's truth calls for (Plant::dynamics or
// Plant::parametric).
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "core/common/accel_block.h"
#include "core/common/result.h"
#include "core/evaluation/plant_excitation.h"
#include "core/evaluation/scenario_matrix.h"

namespace gearpath {

struct SeverityFit {
  double scale = 1.0;       // factor asked of the default depths (before the caps)
  double rms_change = 0.0;  // achieved signed raw RMS change of the most affected channel
  int evaluations = 0;      // noise-free faulty blocks simulated to find the factor
};

class PlantStream {
 public:
  virtual ~PlantStream() = default;
  // Scales every fault depth by one factor (each clamped to its physical cap) so that the raw
  // RMS of the most affected channel, noise-free, faulty vs healthy, changes by `target`
  // (e.g. 0.03) on the NEXT block of the stream. Does not advance the stream. A fault that
  // cannot reach the target under its caps stays at the caps. Healthy plants: no-op.
  virtual SeverityFit NormaliseSeverity(double target) = 0;
  // The fault depths in use (the defaults until NormaliseSeverity).
  virtual PlantFaultSeverity severity() const = 0;
  // Writes the next block (noise and unmodelled sources included) and advances the stream.
  virtual void NextBlock(bool fault_on, AccelBlock& block) = 0;
};

struct PlantStreamConfig {
  std::string machine_id = "plant";
  double sample_rate_hz = 8000.0;
  std::uint32_t block_length = 8192;
  // The first block's sequence number and start time: a stream that continues another one
  // (the evaluation's speed step) goes on where it stopped.
  std::uint64_t first_sequence = 0;
  std::int64_t start_time_ns = 0;
  // The transmitted load x this (> 0; the evaluation's load step). The parametric plant's load
  // torque and viscous load are scaled, and through them every mesh's deflection; the linear
  // plants, driven by their meshes' transmission errors, get their healthy errors scaled (the
  // elastic part of a loaded mesh's error grows with its load; the fault's stays as drawn).
  double load_factor = 1.0;
};

// The scenario's stream: its plant's truth driven at the scenario's speed, fault, gear, noise
// and unmodelled sources, seeded from scenario.seed.
Result<std::unique_ptr<PlantStream>> MakePlantStream(const Plant& plant, const Scenario& scenario,
                                                     const PlantStreamConfig& config);

}  // namespace gearpath
