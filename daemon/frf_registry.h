// FrfRegistry: each distinct FRF set of the configured machines loaded once and shared
// read-only, with its per-shape operators (core/pipeline/shared_frf_operators.h), by every
// machine that names it; per machine only the set's names (paths, channels) are copied.
//
// Within one build (BuildMachines) a source (`frf_set` directory or `builtin:<name>`) is read
// once. Sets are then matched by content, the decoupled matrix itself: two sources holding the
// same matrix share, and a reload whose sets have not changed gets the instances the running
// machines hold, so a SIGHUP recomputes no operator. A set no machine holds any more is freed
// (the registry keeps only weak references across builds).
//
// Not thread-safe: builds run one at a time (start-up, then the lifecycle thread's reloads).
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "core/common/result.h"
#include "core/frf/frf_set.h"
#include "core/pipeline/shared_frf_operators.h"
#include "daemon/daemon_config.h"

namespace gearpath::daemon {

struct SharedFrf {
  std::shared_ptr<const FrfSet> names;  // the set without its matrices (decoupled, coupled)
  std::shared_ptr<SharedFrfOperators> operators;  // the decoupled matrix and its operators
};

class FrfRegistry {
 public:
  // The set `machine` names (its `frf_set` source, or its identity set); errors name the key.
  Result<SharedFrf> Get(const MachineConfig& machine);

  // Ends a build: the next Get of a source reads it again (a reload sees an edited set).
  void EndBuild() { loaded_.clear(); }

  // Sources read or built so far; distinct matrices adopted (not found among the live ones).
  std::uint64_t loads() const noexcept { return loads_; }
  std::uint64_t sets_created() const noexcept { return sets_created_; }

 private:
  Result<SharedFrf> Share(FrfSet set);

  std::map<std::string, SharedFrf, std::less<>> loaded_;  // this build, by source
  std::vector<std::weak_ptr<SharedFrfOperators>> live_;   // every build's, while held
  std::uint64_t loads_ = 0;
  std::uint64_t sets_created_ = 0;
};

}  // namespace gearpath::daemon
