#include "daemon/machine_runtime.h"

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <thread>

#include "daemon/dds_bridge.h"
#include "daemon/machine_setup_builder.h"

namespace gearpath::daemon {
namespace {

std::string_view MethodName(InverseMethod method) {
  switch (method) {
    case InverseMethod::kMwi: return "mwi";
    case InverseMethod::kTikhonov: return "tikhonov";
    case InverseMethod::kLeastSquares: return "least_squares";
  }
  return "?";
}

std::string Summary(const MachineSetup& s) {
  const FrfMatrix& h = s.frf_set.decoupled;
  const double lo = h.bins() > 0 ? h.frequency_hz[0] : 0.0;
  const double hi = h.bins() > 0 ? h.frequency_hz[h.bins() - 1] : 0.0;
  std::string paths;
  for (const auto& p : s.frf_set.paths) paths += (paths.empty() ? "" : ",") + p.name;
  return fmt::format(
      "FRF {} channels x {} paths x {} bins ({:.1f}-{:.1f} Hz, {}), paths [{}], {} shafts, {} "
      "gears, {} meshes, fs {} Hz, blocks {}-{} samples, inverse {} K={}, nominal speed {} Hz",
      h.outputs(), h.inputs(), h.bins(), lo, hi, s.frf_set.decoupling, paths,
      s.train.shafts.size(), s.train.gears.size(), s.train.meshes.size(),
      s.options.sample_rate_hz, s.options.min_samples_per_channel,
      s.options.max_samples_per_channel, MethodName(s.options.identification.method),
      s.options.identification.iterations, s.options.nominal_speed_hz);
}

// Configures every machine for its listed block lengths, machines in parallel (one worker per
// core): the per-bin operators of a reference FRF set take seconds, and a daemon that did this
// on its first block would keep every machine waiting behind it.
Status PrepareMachines(const DaemonConfig& config, MachineSet& set) {
  struct Job {
    const MachineConfig* config;
    MachineRuntime* machine;
    std::uint32_t samples;
    std::string error;
  };
  std::vector<Job> jobs;
  for (const MachineConfig& mc : config.machines) {
    const auto& lengths = mc.settings["acquisition"]["prepare_samples_per_channel"];
    for (const auto& n : lengths) {
      jobs.push_back({&mc, set.machines.at(mc.id).get(), n.get<std::uint32_t>(), {}});
    }
  }
  // Shapes of one machine share its processor: one worker per machine, lengths in turn.
  std::vector<std::vector<Job*>> per_machine;
  for (Job& job : jobs) {
    if (per_machine.empty() || per_machine.back().front()->machine != job.machine) {
      per_machine.emplace_back();
    }
    per_machine.back().push_back(&job);
  }
  std::atomic<std::size_t> next{0};
  auto work = [&] {
    // Checks that each machine's scratch can be made; the workers' own are readied later
    // (PrepareWorkerScratch), so no processor keeps a scratch of its own.
    BlockScratch scratch;
    for (std::size_t i = next++; i < per_machine.size(); i = next++) {
      for (Job* job : per_machine[i]) {
        if (Status st = job->machine->processor.Prepare(job->samples, scratch); !st) {
          job->error = st.error();
        }
      }
    }
  };
  const std::size_t workers =
      std::min<std::size_t>(per_machine.size(), std::max(1u, std::thread::hardware_concurrency()));
  std::vector<std::thread> threads;
  for (std::size_t w = 1; w < workers; ++w) threads.emplace_back(work);
  work();
  for (auto& t : threads) t.join();
  for (const Job& job : jobs) {
    if (!job.error.empty()) {
      return Error{fmt::format("{}.acquisition.prepare_samples_per_channel ({}): {}",
                               job.config->key_path, job.samples, job.error)};
    }
  }
  for (const Job& job : jobs) job.machine->prepared_samples.push_back(job.samples);
  return Status::Ok();
}

}  // namespace

Result<MachineSet> BuildMachines(const DaemonConfig& config,
                                 std::shared_ptr<FrfRegistry> registry) {
  MachineSet set;
  set.frf_registry = registry ? std::move(registry) : std::make_shared<FrfRegistry>();
  FrfRegistry& frf = *set.frf_registry;
  struct EndBuild {  // the next build reads every source again, whatever happens here
    FrfRegistry& r;
    ~EndBuild() { r.EndBuild(); }
  } end_build{frf};
  for (const MachineConfig& machine : config.machines) {
    auto setup = BuildMachineSetup(machine, &frf);
    if (!setup) return Error{setup.error()};
    std::string summary = Summary(*setup);
    auto processor = BlockProcessor::Create(std::move(setup.value()));
    if (!processor) {
      return Error{fmt::format("{} (machine \"{}\"): {}", machine.key_path, machine.id,
                               processor.error())};
    }
    auto runtime = std::unique_ptr<MachineRuntime>(new MachineRuntime{
        machine.id, std::move(summary), std::move(processor.value()), {}, {}, {}});
    runtime->indicator_names = IndicatorNamesOf(runtime->processor);
    set.machines.emplace(machine.id, std::move(runtime));
  }
  if (Status st = PrepareMachines(config, set); !st) return Error{st.error()};
  return set;
}

Status PrepareWorkerScratch(MachineSet& set, std::span<BlockScratch> scratch) {
  for (BlockScratch& s : scratch) {
    for (auto& [id, machine] : set.machines) {
      for (std::uint32_t n : machine->prepared_samples) {
        if (Status st = machine->processor.Prepare(n, s); !st) {
          return Error{fmt::format("machine \"{}\": worker scratch for {} samples: {}", id, n,
                                   st.error())};
        }
      }
    }
  }
  return Status::Ok();
}

}  // namespace gearpath::daemon
