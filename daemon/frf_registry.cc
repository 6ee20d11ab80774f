#include "daemon/frf_registry.h"

#include <utility>

#include "daemon/machine_setup_builder.h"

namespace gearpath::daemon {

Result<SharedFrf> FrfRegistry::Get(const MachineConfig& machine) {
  // An identity set depends on the machine's channels and acquisition, not on a source name:
  // it is built for each machine and shared by content like any other.
  const bool identity = machine.frf_set == kIdentityFrfSet;
  if (!identity) {
    if (auto it = loaded_.find(machine.frf_set); it != loaded_.end()) return it->second;
  }
  auto set = identity ? IdentityFrfSetFor(machine)
                      : LoadFrfSource(machine.frf_set, machine.key_path + ".frf_set");
  if (!set) return Error{set.error()};
  ++loads_;
  auto shared = Share(std::move(set.value()));
  if (shared && !identity) loaded_.emplace(machine.frf_set, shared.value());
  return shared;
}

Result<SharedFrf> FrfRegistry::Share(FrfSet set) {
  SharedFrf out;
  std::erase_if(live_, [](const auto& w) { return w.expired(); });
  for (const auto& weak : live_) {
    auto operators = weak.lock();
    if (operators && SameFrfMatrix(operators->decoupled(), set.decoupled)) {
      out.operators = std::move(operators);
      break;
    }
  }
  if (!out.operators) {
    out.operators = std::make_shared<SharedFrfOperators>(
        std::make_shared<const FrfMatrix>(std::move(set.decoupled)));
    live_.push_back(out.operators);
    ++sets_created_;
  }
  // The pipeline reads names and the decoupled matrix only; the matrices stay out of the
  // per-machine copies (the shared operators hold the decoupled one).
  set.decoupled = FrfMatrix{};
  set.coupled.reset();
  out.names = std::make_shared<const FrfSet>(std::move(set));
  return out;
}

}  // namespace gearpath::daemon
