// Evaluation runner: one scenario end to end through the daemon's per-block engine
// (gearpath::BlockProcessor, no DDS), and its score.
//
// A scenario's machine: MachineSetup{machine id, the plant's MODEL FRF set (or the identity set,
// RunnerOptions::identity_frf), the train layout
// (TrainLayoutFromGearTrain), DEFAULT AnalysisOptions except sample_rate_hz = 8 kHz}; blocks
// of 8192 samples carry the (mean) input speed. The plant's stream (PlantStream, plant_stream.h:
// the frequency-domain PlantSimulator or the time-domain ParametricPlantSimulator) delivers
// kBaselineBlocks (20) healthy blocks, which the processor learns its baseline from, then
// kEvaluationBlocks (5) evaluation blocks (faulty, or still healthy for fault kind none) of the
// same machine, continuing in time and sequence. Every verdict is recorded.
//
// Fault severity is normalised per scenario, at the first evaluation block: the fault depths
// (PlantFaultSeverity) are scaled by one common factor so that the raw RMS change of the most
// affected channel (noise-free, that block, faulty vs healthy) is target_rms_change (3 %;
// solved exactly for the linear families, by secant steps for the time-domain one), each depth
// clamped to its physical cap. A fault is then a modest change everywhere, whatever the plant's
// sensitivity; a smooth wear_dip usually hits its cap first and stays well under the target
// (it is meant to be hard).
//
// Scoring (ScoreVerdicts), over the evaluation blocks only:
//  - alarmed block: state is neither no_fault nor learning (suspected or alarm);
//  - detected: a majority of the evaluation blocks is alarmed (faulty scenarios);
//  - right gear, per block: the block is alarmed and its named gears (the candidate list, or
//    the gear name when there is no list) contain the true gear, and every named gear is the
//    true gear or physically inseparable from it (same shaft rate within 2 % AND the same
//    mesh: e.g. Table 1's G3 / G4). An over-broad list (G2, G3 for a G2 fault) does not count.
//    The scenario's gear is right when a majority of its evaluation blocks is;
//  - first alarm: 1-based index of the first alarmed evaluation block, 0 = none;
//  - flips: number of state changes between consecutive evaluation blocks (a fault's onset,
//    no_fault -> suspected -> alarm, is two);
//  - reversals: the changes to a LESS severe state (alarm -> suspected or no_fault, suspected
//    -> no_fault): a verdict that flickers; 0 for a steady scenario whose onset escalates;
//  - false alarms (healthy scenarios): the number of alarmed evaluation blocks;
//  - learning: evaluation blocks still in kLearning (the pipeline wanted a longer baseline
//    than the 20 blocks it got; they count as not alarmed).
#pragma once

#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "core/diagnosis/gear_verdict.h"
#include "core/diagnosis/train_layout.h"
#include "core/evaluation/scenario_matrix.h"

namespace gearpath {

struct BlockResult;  // core/pipeline/block_processor.h

inline constexpr int kBaselineBlocks = 20;
inline constexpr int kEvaluationBlocks = 5;

struct RunnerOptions {
  int baseline_blocks = kBaselineBlocks;
  int evaluation_blocks = kEvaluationBlocks;
  double sample_rate_hz = 8000.0;
  std::uint32_t block_length = 8192;
  double target_rms_change = 0.03;  // <= 0: keep the default severities
  bool order_tracking = true;       // AnalysisOptions::order_tracking of every machine
  bool localisation_tracking = true;  // AnalysisOptions::localisation_tracking
  bool transient_gate = true;         // AnalysisOptions::transient_gate
  // The evaluation blocks run at input_rpm x (1 + speed_step): a machine whose speed moved
  // after its baseline was learned (the baseline blocks stay at input_rpm). 0: no step.
  double speed_step = 0.0;
  // The evaluation blocks run at the scenario's load x (1 + load_step) (PlantStreamConfig::
  // load_factor): a machine whose load moved after its baseline was learned. 0: no step.
  double load_step = 0.0;
  // Every block carries its load (AccelBlock::load) relative to the scenario's, as from a
  // torque reading: 1, or 1 + load_step on the evaluation blocks of a load step. Off, the
  // blocks carry none and every load is judged (AnalysisOptions::load_tolerance).
  bool load_reading = true;
  // AnalysisOptions::operating_bands of every machine (1: one baseline).
  int operating_bands = 1;
  // With a speed or load step: this many healthy blocks at the new speed and load come between
  // the baseline and the evaluation blocks (a machine with operating bands learns one there).
  int step_learning_blocks = 0;
  // AnalysisOptions::speed_tolerance of every machine; negative keeps the default.
  double speed_tolerance = -1.0;
  // Give the machine the identity FRF set (core/frf/identity_frf_set.h: every sensor its own
  // path, the configuration before the hammer test) instead of the plant's model FRFs. A seat
  // sensor sits near its bearing's gears, the housing sensor near every gear.
  bool identity_frf = false;
  // Optional: called after every processed block (baseline and evaluation) with the block's
  // index (0-based; evaluation blocks from baseline_blocks + step_learning_blocks on) and its
  // result, on the
  // scenario's worker thread (the callee serialises). For analysts studying the indicators.
  std::function<void(const Scenario&, int block, const BlockResult&)> observe;
};

// A verdict copied out of a BlockResult (which only holds views into its processor).
struct BlockVerdictRecord {
  FaultState state = FaultState::kLearning;
  std::string gear;
  std::vector<std::string> candidates;
  std::string shaft;
};

struct ScenarioScore {
  bool faulty = false;
  int blocks = 0;
  int alarmed_blocks = 0;
  int learning_blocks = 0;
  int right_gear_blocks = 0;
  bool detected = false;
  bool right_gear = false;
  int first_alarm_block = 0;  // 1-based, 0 = never
  int flips = 0;
  int reversals = 0;
  // Changes of the gears named (gear and candidates) from one alarmed block to the next
  // alarmed one: a verdict that keeps its state but moves its gear flickers all the same.
  int gear_changes = 0;
  int false_alarm_blocks = 0;  // healthy scenarios only
};

struct ScenarioOutcome {
  Scenario scenario;
  std::string error;  // non-empty: the scenario could not run (score is empty)
  std::vector<BlockVerdictRecord> verdicts;  // the evaluation blocks
  ScenarioScore score;
  double severity_scale = 1.0;  // factor asked of the default fault depths (before caps)
  PlantFaultSeverity severity;  // the depths actually used
  double rms_change = 0.0;      // achieved max-channel raw RMS change (signed), faulty scenarios
  double seconds = 0.0;
};

// True when gears a and b (indices into layout.gears) turn at the same rate (relative
// tolerance) and share a mesh: the envelope and the paths cannot tell them apart.
bool GearsInseparable(const TrainLayout& layout, int a, int b, double rate_tolerance = 0.02);
// Whether one block's verdict names `true_gear` acceptably (see the file comment).
bool VerdictNamesGear(const BlockVerdictRecord& verdict, const std::string& true_gear,
                      const TrainLayout& layout);
// true_gear empty = healthy scenario.
ScenarioScore ScoreVerdicts(std::span<const BlockVerdictRecord> evaluation,
                            const std::string& true_gear, const TrainLayout& layout);

ScenarioOutcome RunScenario(const Scenario& scenario, const RunnerOptions& options = {});

// Runs scenarios on `threads` threads (each scenario has its own processor); outcomes in the
// scenarios' order. progress (optional) is called after each scenario, serialised.
std::vector<ScenarioOutcome> RunScenarios(
    const std::vector<Scenario>& scenarios, const RunnerOptions& options, int threads,
    const std::function<void(std::size_t done, std::size_t total, const ScenarioOutcome&)>&
        progress = {});

}  // namespace gearpath
