// MachineStateStore: gearpathd's memory across restarts, one JSON file per machine in the
// state directory (docs/state.md): the machine's LearnedState (healthy baseline, alarm state,
// core/pipeline/learned_state.h) and its lifetime counters.
//
// Files are written atomically (a temporary file in the same directory, fsync, rename, fsync
// of the directory), so a crash or power loss leaves the previous file or the new one, never a
// torn one. Only this daemon writes there (systemd's StateDirectory=); a file that is missing
// means "learn"; a file that cannot be used says why and the machine learns again.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "core/common/result.h"
#include "core/pipeline/learned_state.h"
#include "daemon/daemon_config.h"
#include "daemon/machine_runtime.h"

namespace gearpath::daemon {

struct SavedMachine {
  std::string machine_id;
  std::int64_t saved_at_ns = 0;  // wall clock
  LearnedState learned;
  MachineCounters counters;  // received, processed, rejected (by reason), lost
};

// Reads one state file as MachineStateStore::Load does, whichever machine it names (for
// `gearpath inspect`); errors name the file.
Result<SavedMachine> ReadSavedMachine(const std::string& path);

// The configured directory, else the first entry of $STATE_DIRECTORY (systemd), else empty.
std::string ResolveStateDirectory(const DaemonConfig& config);

class MachineStateStore {
 public:
  // Creates the directory if needed (mode 0700) and checks that it can write there.
  static Result<MachineStateStore> Open(std::string directory);

  // Nothing when the machine has no file yet; an error when the file is unreadable, not JSON
  // or not a state of this machine (the message names the file).
  Result<std::optional<SavedMachine>> Load(std::string_view machine_id) const;
  Status Save(const SavedMachine& machine) const;

  // <directory>/<machine id, bytes outside [A-Za-z0-9._-] as %XX>.state.json
  std::string PathOf(std::string_view machine_id) const;
  const std::string& directory() const noexcept { return directory_; }

 private:
  explicit MachineStateStore(std::string directory) : directory_(std::move(directory)) {}
  std::string directory_;
};

}  // namespace gearpath::daemon
