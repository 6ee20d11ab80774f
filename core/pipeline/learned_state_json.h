// The JSON form of a LearnedState (docs/state.md): what gearpathd writes to its state
// directory. Doubles are written with 17 significant digits, so a round trip is exact.
#pragma once

#include <nlohmann/json.hpp>

#include "core/common/result.h"
#include "core/pipeline/learned_state.h"

namespace gearpath {

nlohmann::json ToJson(const LearnedState& state);
// Checks types and presence (messages name the key); the values themselves are validated
// when a processor imports the state (BlockProcessor::ImportLearnedState). Never throws.
Result<LearnedState> LearnedStateFromJson(const nlohmann::json& j);

}  // namespace gearpath
