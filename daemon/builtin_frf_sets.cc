// The built-in FRF sets (`"frf_set": "builtin:<name>"`), computed at start-up.
//
// builtin:table1: the seed's Table-1 two-stage gearbox decoupled at the bearing seats by Eq. 22
// (MakeTable1FrfSet, core/simulation/model_frf_set.h); other block lengths than its 8192-sample
// grid are interpolated by the pipeline.
#include <fmt/format.h>

#include "core/simulation/model_frf_set.h"
#include "daemon/machine_setup_builder.h"

namespace gearpath::daemon {

Result<FrfSet> BuiltinFrfSet(const std::string& name) {
  if (name != "table1") {
    return Error{fmt::format("unknown built-in FRF set \"{}\" (known: table1)", name)};
  }
  return MakeTable1FrfSet();
}

}  // namespace gearpath::daemon
