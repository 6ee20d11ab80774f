// `gearpath evaluate`: the evaluation matrix (core/evaluation) run offline through the
// daemon's per-block engine, printed as tables per fault kind, gear, speed band, noise,
// family...; optionally written as JSON (docs/evaluation.md). The held-out family
// (parametric_plate) is excluded by default, reported separately when included, and must
// never be used for tuning.
#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <vector>

#include "core/evaluation/evaluation_report.h"
#include "core/evaluation/evaluation_runner.h"
#include "core/evaluation/scenario_matrix.h"
#include "core/pipeline/block_processor.h"
#include "tools/commands/commands.h"
#include "tools/common/cli_checks.h"

namespace gearpath::tools {
namespace {

struct EvaluateArgs {
  std::string matrix = "quick";
  std::string match;
  std::size_t sample = 0;
  std::vector<std::string> families;
  bool held_out_only = false;
  bool include_held_out = false;
  bool exclude_held_out = false;
  std::string json_path;
  int threads = 0;
  bool list = false;
  bool quiet = false;
  bool order_tracking = true;
  bool no_localisation_tracking = false;
  bool no_transient_gate = false;
  std::string frf = "model";
  std::string dump_blocks_path;
  double speed_step = 0.0;
  double load_step = 0.0;
  bool no_load_reading = false;
  double speed_tolerance = -1.0;
  int operating_bands = 1;
  int step_learning_blocks = 0;
};

// One JSON line per processed block: what the verdict stood on (docs/evaluation.md).
nlohmann::json BlockLine(const Scenario& sc, int block, const BlockResult& r) {
  nlohmann::json line;
  line["key"] = sc.Key();
  line["gear"] = sc.gear;
  line["block"] = block;
  line["state"] = std::string(ToString(r.verdict.state));
  line["verdict_gear"] = std::string(r.verdict.gear_name);
  line["verdict_shaft"] = std::string(r.verdict.shaft_name);
  line["score"] = r.score.score;
  line["limit_z"] = r.score.limit_z;
  line["score_indicator"] = std::string(r.score.indicator);
  line["score_signal"] = std::string(r.score.signal);
  line["score_shaft"] = std::string(r.score.shaft);
  const BlockLocalisation& loc = r.localisation;
  const auto groups = static_cast<std::size_t>(
      std::min<int>(loc.group_count, static_cast<int>(BlockLocalisation::kMaxGroups)));
  const auto meshes = static_cast<std::size_t>(
      std::min<int>(loc.mesh_count, static_cast<int>(BlockLocalisation::kMaxMeshes)));
  line["localisation"] = {
      {"group", loc.group},
      {"shaft_evidence", std::vector<double>(loc.shaft_evidence.begin(),
                                             loc.shaft_evidence.begin() + groups)},
      {"shaft_evidence_accumulated",
       std::vector<double>(loc.shaft_evidence_accumulated.begin(),
                           loc.shaft_evidence_accumulated.begin() + groups)},
      {"mesh_evidence",
       std::vector<double>(loc.mesh_evidence.begin(), loc.mesh_evidence.begin() + meshes)}};
  nlohmann::json& signatures = line["localisation"]["signature_excess"];
  signatures = nlohmann::json::array();
  for (std::size_t g = 0; g < groups; ++g) {
    nlohmann::json per_mesh = nlohmann::json::array();
    for (const auto& e : loc.signature_excess[g]) {
      per_mesh.push_back(std::vector<double>(e.begin(), e.end()));
    }
    signatures.push_back(per_mesh);
  }
  nlohmann::json& shafts = line["shafts"];
  shafts = nlohmann::json::array();
  for (const BlockShaftIndicator& s : r.shafts) {
    shafts.push_back({{"shaft", std::string(s.shaft)},
                      {"hz", s.characteristic_hz},
                      {"raw", s.raw},
                      {"reconstructed", s.reconstructed}});
  }
  nlohmann::json& condition = line["condition"];
  condition = nlohmann::json::array();
  for (const BlockConditionIndicators& c : r.condition) {
    condition.push_back({{"source", std::string(ToString(c.source))},
                         {"signal", std::string(c.signal)},
                         {"shaft", std::string(c.shaft)},
                         {"revolutions", c.revolutions},
                         {"transient_samples", c.transient_samples},
                         {"value", std::vector<double>(c.value.begin(), c.value.end())},
                         {"z", std::vector<double>(c.z.begin(), c.z.end())}});
  }
  return line;
}

int RunEvaluate(const EvaluateArgs& args) {
  const std::optional<MatrixSize> size = ParseMatrixSize(args.matrix);
  if (!size) {
    std::fprintf(stderr, "gearpath evaluate: --matrix must be quick or full, got '%s'\n",
                 args.matrix.c_str());
    return kExitBadInput;
  }
  MatrixFilter filter;
  filter.held_out = args.held_out_only      ? HeldOutSelection::kOnly
                    : args.include_held_out ? HeldOutSelection::kInclude
                                            : HeldOutSelection::kExclude;
  for (const std::string& name : args.families) {
    const std::optional<PlantFamily> f = ParsePlantFamily(name);
    if (!f) {
      std::fprintf(stderr,
                   "gearpath evaluate: --family '%s' is not a family (lumped_perturbed, "
                   "lumped_torsional, modal_housing, parametric_plate)\n",
                   name.c_str());
      return kExitBadInput;
    }
    if (IsHeldOut(*f) && filter.held_out == HeldOutSelection::kExclude) {
      std::fprintf(stderr,
                   "gearpath evaluate: --family %s is a held-out family, excluded by default; "
                   "add --held-out-only (or --include-held-out) to run it, never to tune on it\n",
                   name.c_str());
      return kExitBadInput;
    }
    filter.families.push_back(*f);
  }
  filter.key_contains = args.match;
  std::vector<Scenario> scenarios = EnumerateScenarios(*size, filter);
  if (args.sample > 0) scenarios = SampleScenarios(std::move(scenarios), args.sample);
  std::string matrix_label =
      args.sample > 0 ? args.matrix + ", sample " + std::to_string(scenarios.size()) : args.matrix;
  if (args.speed_step != 0.0) {
    matrix_label += fmt::format(", evaluation blocks at {:+g} % speed", 100.0 * args.speed_step);
  }
  if (args.load_step != 0.0) {
    matrix_label += fmt::format(", evaluation blocks at {:+g} % load", 100.0 * args.load_step);
  }
  if (args.step_learning_blocks > 0) {
    matrix_label += fmt::format(", {} healthy blocks at the step first", args.step_learning_blocks);
  }
  if (args.operating_bands > 1) {
    matrix_label += fmt::format(", {} operating bands", args.operating_bands);
  }
  if (args.no_load_reading) matrix_label += ", blocks without a load reading";
  if (args.speed_tolerance >= 0.0) {
    matrix_label += fmt::format(", speed tolerance {:g}", args.speed_tolerance);
  }
  if (scenarios.empty()) {
    std::fprintf(stderr, "gearpath evaluate: the selection holds no scenario\n");
    return kExitBadInput;
  }
  if (args.list) {
    for (const Scenario& s : scenarios) {
      std::printf("%zu %s seed=%llu\n", s.index, s.Key().c_str(),
                  static_cast<unsigned long long>(s.seed));
    }
    return kExitOk;
  }
  const int threads = args.threads > 0
                          ? args.threads
                          : std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  std::fprintf(stderr, "gearpath evaluate: %zu scenarios (%s matrix) on %d threads\n",
               scenarios.size(), matrix_label.c_str(), threads);
  const auto start = std::chrono::steady_clock::now();
  const bool quiet = args.quiet;
  RunnerOptions runner;
  runner.order_tracking = args.order_tracking;
  runner.localisation_tracking = !args.no_localisation_tracking;
  runner.transient_gate = !args.no_transient_gate;
  runner.identity_frf = args.frf == "identity";
  runner.speed_step = args.speed_step;
  runner.load_step = args.load_step;
  runner.load_reading = !args.no_load_reading;
  runner.speed_tolerance = args.speed_tolerance;
  runner.operating_bands = args.operating_bands;
  runner.step_learning_blocks = args.step_learning_blocks;
  std::ofstream dump;
  std::mutex dump_mutex;
  if (!args.dump_blocks_path.empty()) {
    dump.open(args.dump_blocks_path);
    if (!dump) {
      std::fprintf(stderr, "gearpath evaluate: cannot write --dump-blocks file '%s'\n",
                   args.dump_blocks_path.c_str());
      return kExitFailure;
    }
    runner.observe = [&dump, &dump_mutex](const Scenario& sc, int block, const BlockResult& r) {
      const std::string text = BlockLine(sc, block, r).dump(-1, ' ', false,
                                                            nlohmann::json::error_handler_t::replace);
      const std::lock_guard<std::mutex> lock(dump_mutex);
      dump << text << '\n';
    };
  }
  const std::vector<ScenarioOutcome> outcomes = RunScenarios(
      scenarios, runner, threads,
      [quiet, &start](std::size_t done, std::size_t total, const ScenarioOutcome& o) {
        if (!o.error.empty()) {
          std::fprintf(stderr, "  error in %s: %s\n", o.scenario.Key().c_str(), o.error.c_str());
        }
        if (quiet || (done % 25 != 0 && done != total)) return;
        const double elapsed =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        std::fprintf(stderr, "  [%zu/%zu] %.0f s elapsed\n", done, total, elapsed);
      });
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const std::vector<PartitionSummary> summary = Summarise(outcomes);
  std::printf("gearpath evaluate: %s matrix, %zu scenarios, %.0f s\n", matrix_label.c_str(),
              scenarios.size(), elapsed);
  std::printf(
      "columns: faulty / healthy scenarios; detection and right-gear rate over faulty "
      "scenarios (majority of %d evaluation blocks after %d baseline blocks); false "
      "alarms per healthy evaluation block; mean first alarmed block; mean state flips; "
      "evaluation blocks still learning\n\n",
      kEvaluationBlocks, kBaselineBlocks);
  std::fputs(FormatSummary(summary).c_str(), stdout);
  if (!args.json_path.empty()) {
    std::ofstream out(args.json_path);
    out << ToJson(matrix_label, outcomes, summary) << "\n";
    if (!out) {
      std::fprintf(stderr, "gearpath evaluate: cannot write --json file '%s'\n",
                   args.json_path.c_str());
      return kExitFailure;
    }
  }
  if (dump.is_open() && !dump.flush()) {
    std::fprintf(stderr, "gearpath evaluate: writing --dump-blocks file '%s' failed\n",
                 args.dump_blocks_path.c_str());
    return kExitFailure;
  }
  for (const ScenarioOutcome& o : outcomes) {
    if (!o.error.empty()) return kExitFailure;
  }
  return kExitOk;
}

}  // namespace

void AddEvaluateCommand(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<EvaluateArgs>();
  CLI::App* cmd = app.add_subcommand(
      "evaluate",
      "Run the evaluation matrix (plants of independent physics, fault models, speeds, noise) "
      "through the block processor and print detection, right-gear and false-alarm rates");
  cmd->add_option("--matrix", args->matrix, "quick or full")->capture_default_str();
  cmd->add_option("--match", args->match,
                  "only scenarios whose key contains this text, e.g. '/mesh_am/G3/' or '200rpm'");
  cmd->add_option("--sample", args->sample,
                  "run N scenarios of the selection drawn at random, the same N every run "
                  "(e.g. --matrix full --sample 400)")
      ->check(Positive());
  cmd->add_option("--family", args->families,
                  "only these families (lumped_perturbed, lumped_torsional, modal_housing, "
                  "parametric_plate)");
  auto* only = cmd->add_flag("--held-out-only", args->held_out_only,
                             "run and print only the held-out family (parametric_plate)");
  auto* include = cmd->add_flag("--include-held-out", args->include_held_out,
                                "run the held-out family too (reported separately)");
  auto* exclude = cmd->add_flag("--exclude-held-out", args->exclude_held_out,
                                "leave the held-out family out (the default; for tuning runs)");
  only->excludes(include)->excludes(exclude);
  include->excludes(exclude);
  cmd->add_option("--json", args->json_path, "write every scenario's verdicts and the summary");
  cmd->add_option("--threads", args->threads, "worker threads (default: all cores)")
      ->check(NonNegative());
  cmd->add_flag("--list", args->list, "list the selected scenarios and their seeds, run nothing");
  cmd->add_flag("--quiet", args->quiet, "no progress lines on stderr");
  cmd->add_option("--dump-blocks", args->dump_blocks_path,
                  "write one JSON line per processed block (scenario, verdict, score, envelope "
                  "and condition indicators with their z), for studying the indicators");
  cmd->add_flag("--order-tracking,!--no-order-tracking", args->order_tracking,
                "run the machines with analysis.speed.order_tracking on (the default) or off");
  cmd->add_option("--frf", args->frf,
                  "FRF set given to the machines: model (the plant's model FRFs) or identity "
                  "(each sensor its own path: monitoring before the hammer test)")
      ->check(CLI::IsMember({"model", "identity"}))
      ->capture_default_str();
  cmd->add_flag("--no-localisation-tracking", args->no_localisation_tracking,
                "run the machines with analysis.speed.localisation_tracking off (default on)");
  cmd->add_flag("--no-transient-gate", args->no_transient_gate,
                "run the machines with analysis.condition.transient_gate off (default on)");
  cmd->add_option("--speed-step", args->speed_step,
                  "run the evaluation blocks at the scenario's speed x (1 + STEP), e.g. 0.01: a "
                  "machine whose speed moved after its baseline was learned")
      ->check(CLI::Range(-0.5, 0.5));
  cmd->add_option("--load-step", args->load_step,
                  "run the evaluation blocks at the plant's load x (1 + STEP), e.g. 0.2: a "
                  "machine whose load moved after its baseline was learned")
      ->check(CLI::Range(-0.9, 2.0));
  cmd->add_flag("--no-load-reading", args->no_load_reading,
                "send the blocks without their load (by default each carries it, relative to "
                "the scenario's, so the machines judge only the loads they learned at)");
  cmd->add_option("--operating-bands", args->operating_bands,
                  "run the machines with baseline.operating_bands set to this (default 1: one "
                  "baseline; more: a baseline per band of speed and load)")
      ->check(CLI::Range(1, kMaxOperatingBands));
  cmd->add_option("--step-learning-blocks", args->step_learning_blocks,
                  "with --speed-step or --load-step: this many healthy blocks at the new speed "
                  "and load before the evaluation blocks (where a machine with operating bands "
                  "learns one)")
      ->check(CLI::Range(0, 1000));
  cmd->add_option("--speed-tolerance", args->speed_tolerance,
                  "run the machines with baseline.speed_tolerance set to this (default: the "
                  "daemon's; 1 judges every speed)")
      ->check(CLI::Range(0.0, 1.0));
  cmd->callback([args, &exit_code] { exit_code = RunEvaluate(*args); });
}

}  // namespace gearpath::tools
