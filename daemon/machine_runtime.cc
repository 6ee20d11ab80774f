#include "daemon/machine_runtime.h"

#include <fmt/format.h>

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

}  // namespace

Result<MachineSet> BuildMachines(const DaemonConfig& config) {
  MachineSet set;
  for (const MachineConfig& machine : config.machines) {
    auto setup = BuildMachineSetup(machine);
    if (!setup) return Error{setup.error()};
    std::string summary = Summary(*setup);
    auto processor = BlockProcessor::Create(std::move(setup.value()));
    if (!processor) {
      return Error{fmt::format("{} (machine \"{}\"): {}", machine.key_path, machine.id,
                               processor.error())};
    }
    auto runtime = std::unique_ptr<MachineRuntime>(
        new MachineRuntime{machine.id, std::move(summary), std::move(processor.value()), {}, {}});
    runtime->indicator_names = IndicatorNamesOf(runtime->processor);
    set.machines.emplace(machine.id, std::move(runtime));
  }
  return set;
}

}  // namespace gearpath::daemon
