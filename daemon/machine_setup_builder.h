// MachineSetup from configuration: everything the pipeline needs for one configured machine.
//
// Loads the machine's FRF set (a directory in the docs/frf_format.md format, a built-in set
// computed at start-up, `builtin:table1`: the seed's Table-1 lumped model decoupled through
// Eq. 22, or `identity`: every configured channel its own path, see IdentityFrfSetFor),
// applies the channel mapping (block channel -> FRF row; an explicit frf_row relabels that FRF
// row with the block's sensor and axis) and the path -> gear overrides, and translates the
// gear train and the analysis options into the pipeline's types. Every error names the
// configuration key it comes from (`machines[0].frf_set: ...`).
#pragma once

#include <string>

#include "core/common/result.h"
#include "core/frf/frf_set.h"
#include "core/pipeline/block_processor.h"
#include "daemon/daemon_config.h"

namespace gearpath::daemon {

// The FRF set named by a machine's `frf_set` key; errors are prefixed with `key_path`.
Result<FrfSet> LoadFrfSource(const std::string& source, const std::string& key_path);

// The built-in FRF sets (`builtin:<name>`); only "table1" exists.
Result<FrfSet> BuiltinFrfSet(const std::string& name);

// `"frf_set": "identity"` (core/frf/identity_frf_set.h): paths = the machine's `channels`, each
// with its `gears`. Grid: fs / N_max, then k fs / N_min for k = 1 .. N_min / 2, and fs / 2
// (N_min, N_max: the accepted block lengths). H is constant, so the pipeline's linear
// interpolation onto the bins of any accepted block length is exact and only DC falls outside
// the grid, while the matrices held stay (N_min / 2 + 2) x channels^2.
Result<FrfSet> IdentityFrfSetFor(const MachineConfig& machine);

class FrfRegistry;  // daemon/frf_registry.h

// With a registry, the setup's FRF set comes from it and shares its matrix and per-shape
// operators with every machine on the same set (MachineSetup::shared_frf); without one, the
// set is loaded for this machine alone.
Result<MachineSetup> BuildMachineSetup(const MachineConfig& machine,
                                       FrfRegistry* registry = nullptr);

}  // namespace gearpath::daemon
