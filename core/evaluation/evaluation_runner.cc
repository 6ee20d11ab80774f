#include "core/evaluation/evaluation_runner.h"

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <mutex>
#include <thread>

#include "core/evaluation/plant_family.h"
#include "core/evaluation/plant_stream.h"
#include "core/frf/identity_frf_set.h"
#include "core/pipeline/block_processor.h"

namespace gearpath {
namespace {

bool Alarmed(FaultState s) { return s == FaultState::kSuspected || s == FaultState::kAlarm; }

int GearIndex(const TrainLayout& layout, const std::string& name) {
  for (std::size_t g = 0; g < layout.gears.size(); ++g) {
    if (layout.gears[g].name == name) return static_cast<int>(g);
  }
  return -1;
}

int MeshOf(const TrainLayout& layout, int gear) {
  for (std::size_t m = 0; m < layout.meshes.size(); ++m) {
    if (layout.meshes[m].gear_a == gear || layout.meshes[m].gear_b == gear) {
      return static_cast<int>(m);
    }
  }
  return -1;
}

// The identity FRF set for the plant's channels: a seat channel (one per bearing, in bearing
// order, as the plant families make them) near its bearing's gears, any other near every gear.
Result<FrfSet> IdentityFrfFor(const Plant& plant) {
  std::vector<std::string> every_gear;
  for (const GearSpec& g : plant.train.gears) every_gear.push_back(g.name);
  std::vector<std::vector<std::string>> near;
  for (std::size_t c = 0; c < plant.model_frf.channels.size(); ++c) {
    near.push_back(c < plant.model_frf.paths.size() ? plant.model_frf.paths[c].gears : every_gear);
  }
  return MakeIdentityFrfSet(plant.model_frf.channels, near,
                            plant.model_frf.decoupled.frequency_hz);
}

Result<ScenarioOutcome> Run(const Scenario& sc, const RunnerOptions& options) {
  ScenarioOutcome outcome;
  outcome.scenario = sc;
  Result<Plant> plant = MakePlant({sc.family, sc.variant, sc.channels, sc.seed});
  if (!plant) return Error{plant.error()};
  PlantStreamConfig stream_config;
  stream_config.machine_id = fmt::format("eval-{}", sc.index);
  stream_config.sample_rate_hz = options.sample_rate_hz;
  stream_config.block_length = options.block_length;
  Result<std::unique_ptr<PlantStream>> stream = MakePlantStream(*plant, sc, stream_config);
  if (!stream) return Error{stream.error()};
  // With a speed or load step the evaluation blocks come from a second stream at the new speed
  // and load, which continues the first one's sequence numbers and clock.
  std::unique_ptr<PlantStream> stepped;
  if (options.speed_step != 0.0 || options.load_step != 0.0) {
    Scenario at_step = sc;
    at_step.input_rpm = sc.input_rpm * (1.0 + options.speed_step);
    PlantStreamConfig step_config = stream_config;
    step_config.load_factor = 1.0 + options.load_step;
    step_config.first_sequence = static_cast<std::uint64_t>(options.baseline_blocks);
    step_config.start_time_ns = std::llround(static_cast<double>(options.baseline_blocks) *
                                             options.block_length / options.sample_rate_hz * 1e9);
    Result<std::unique_ptr<PlantStream>> s = MakePlantStream(*plant, at_step, step_config);
    if (!s) return Error{s.error()};
    stepped = std::move(s).value();
  }
  Result<TrainLayout> layout = TrainLayoutFromGearTrain(plant->train);
  if (!layout) return Error{"train layout: " + layout.error()};

  MachineSetup setup;
  setup.machine_id = stream_config.machine_id;
  if (options.identity_frf) {
    Result<FrfSet> identity = IdentityFrfFor(*plant);
    if (!identity) return Error{"identity FRF set: " + identity.error()};
    setup.frf_set = std::move(identity).value();
  } else {
    setup.frf_set = plant->model_frf;
  }
  setup.train = *layout;
  setup.options.sample_rate_hz = options.sample_rate_hz;
  setup.options.order_tracking = options.order_tracking;
  setup.options.localisation_tracking = options.localisation_tracking;
  setup.options.transient_gate = options.transient_gate;
  setup.options.operating_bands = options.operating_bands;
  if (options.speed_tolerance >= 0.0) setup.options.speed_tolerance = options.speed_tolerance;
  Result<BlockProcessor> processor = BlockProcessor::Create(std::move(setup));
  if (!processor) return Error{"block processor: " + processor.error()};
  if (Status st = processor->Prepare(options.block_length); !st) {
    return Error{"block processor: prepare: " + st.error()};
  }

  AccelBlock block;
  BlockResult result;
  const int step_learning = stepped ? std::max(0, options.step_learning_blocks) : 0;
  const int first_evaluation = options.baseline_blocks + step_learning;
  const int total = first_evaluation + options.evaluation_blocks;
  for (int b = 0; b < total; ++b) {
    const bool at_step = b >= options.baseline_blocks;
    const bool evaluation = b >= first_evaluation;
    const bool faulty = evaluation && sc.fault != PlantFaultKind::kNone;
    PlantStream& source = at_step && stepped ? *stepped : **stream;
    if (faulty && b == first_evaluation && options.target_rms_change > 0.0) {
      // Severity normalised on the first evaluation block, at the stream's position.
      const SeverityFit fit = source.NormaliseSeverity(options.target_rms_change);
      outcome.severity_scale = fit.scale;
      outcome.rms_change = fit.rms_change;
    }
    source.NextBlock(faulty, block);
    const double load = at_step ? 1.0 + options.load_step : 1.0;
    block.load = options.load_reading ? load : 0.0;
    const ProcessOutcome po = processor->Process(block.view(), result);
    if (!po.accepted()) {
      return Error{fmt::format("block {} rejected: {}", b, po.message.view())};
    }
    if (options.observe) options.observe(sc, b, result);
    if (!evaluation) continue;
    BlockVerdictRecord rec;
    rec.state = result.verdict.state;
    rec.gear = std::string(result.verdict.gear_name);
    for (std::string_view c : result.verdict.candidate_names) rec.candidates.emplace_back(c);
    rec.shaft = std::string(result.verdict.shaft_name);
    outcome.verdicts.push_back(std::move(rec));
  }
  outcome.severity = (stepped ? *stepped : **stream).severity();
  outcome.score = ScoreVerdicts(outcome.verdicts, sc.gear, *layout);
  return outcome;
}

}  // namespace

bool GearsInseparable(const TrainLayout& layout, int a, int b, double rate_tolerance) {
  if (a == b) return true;
  const int n = static_cast<int>(layout.gears.size());
  if (a < 0 || b < 0 || a >= n || b >= n) return false;
  const int mesh = MeshOf(layout, a);
  if (mesh < 0) return false;
  const TrainMesh& m = layout.meshes[static_cast<std::size_t>(mesh)];
  if (!((m.gear_a == a && m.gear_b == b) || (m.gear_a == b && m.gear_b == a))) return false;
  Result<std::vector<double>> ratios = ShaftRateRatios(layout);
  if (!ratios) return false;
  const double ra = (*ratios)[static_cast<std::size_t>(layout.gears[a].shaft)];
  const double rb = (*ratios)[static_cast<std::size_t>(layout.gears[b].shaft)];
  return std::abs(ra - rb) <= rate_tolerance * std::max(ra, rb);
}

bool VerdictNamesGear(const BlockVerdictRecord& verdict, const std::string& true_gear,
                      const TrainLayout& layout) {
  if (!Alarmed(verdict.state) || true_gear.empty()) return false;
  std::vector<std::string> named = verdict.candidates;
  if (!verdict.gear.empty() && std::find(named.begin(), named.end(), verdict.gear) == named.end()) {
    named.push_back(verdict.gear);
  }
  if (std::find(named.begin(), named.end(), true_gear) == named.end()) return false;
  const int truth = GearIndex(layout, true_gear);
  for (const std::string& name : named) {
    if (name == true_gear) continue;
    if (!GearsInseparable(layout, GearIndex(layout, name), truth)) return false;
  }
  return true;
}

ScenarioScore ScoreVerdicts(std::span<const BlockVerdictRecord> evaluation,
                            const std::string& true_gear, const TrainLayout& layout) {
  ScenarioScore s;
  s.faulty = !true_gear.empty();
  s.blocks = static_cast<int>(evaluation.size());
  const BlockVerdictRecord* last_alarmed = nullptr;
  for (std::size_t i = 0; i < evaluation.size(); ++i) {
    const BlockVerdictRecord& v = evaluation[i];
    if (v.state == FaultState::kLearning) ++s.learning_blocks;
    if (Alarmed(v.state)) {
      ++s.alarmed_blocks;
      if (s.first_alarm_block == 0) s.first_alarm_block = static_cast<int>(i) + 1;
      if (last_alarmed != nullptr && (v.gear != last_alarmed->gear ||
                                      v.candidates != last_alarmed->candidates)) {
        ++s.gear_changes;
      }
      last_alarmed = &v;
    }
    if (s.faulty && VerdictNamesGear(v, true_gear, layout)) ++s.right_gear_blocks;
    if (i > 0 && v.state != evaluation[i - 1].state) ++s.flips;
    // FaultState is ordered learning < no_fault < suspected < alarm.
    if (i > 0 && v.state < evaluation[i - 1].state) ++s.reversals;
  }
  const bool majority = 2 * s.alarmed_blocks > s.blocks;
  if (s.faulty) {
    s.detected = majority;
    s.right_gear = 2 * s.right_gear_blocks > s.blocks;
  } else {
    s.false_alarm_blocks = s.alarmed_blocks;
  }
  return s;
}

ScenarioOutcome RunScenario(const Scenario& scenario, const RunnerOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  Result<ScenarioOutcome> r = Run(scenario, options);
  ScenarioOutcome out;
  if (r) {
    out = std::move(r).value();
  } else {
    out.scenario = scenario;
    out.error = r.error();
  }
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

std::vector<ScenarioOutcome> RunScenarios(
    const std::vector<Scenario>& scenarios, const RunnerOptions& options, int threads,
    const std::function<void(std::size_t, std::size_t, const ScenarioOutcome&)>& progress) {
  std::vector<ScenarioOutcome> outcomes(scenarios.size());
  std::atomic<std::size_t> next{0};
  std::mutex progress_mutex;
  std::size_t done = 0;
  auto worker = [&] {
    for (;;) {
      const std::size_t i = next.fetch_add(1);
      if (i >= scenarios.size()) return;
      outcomes[i] = RunScenario(scenarios[i], options);
      std::lock_guard<std::mutex> lock(progress_mutex);
      ++done;
      if (progress) progress(done, scenarios.size(), outcomes[i]);
    }
  };
  const int n = std::max(1, std::min<int>(threads, static_cast<int>(scenarios.size())));
  std::vector<std::thread> pool;
  for (int t = 1; t < n; ++t) pool.emplace_back(worker);
  worker();
  for (std::thread& t : pool) t.join();
  return outcomes;
}

}  // namespace gearpath
