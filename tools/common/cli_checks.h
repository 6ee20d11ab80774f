// Command-line value checks shared by the subcommands. CLI11's NonNegativeNumber and
// PositiveNumber print their range with DBL_MAX written out in full (300 digits); these say
// what was expected in words.
#pragma once

#include <CLI/CLI.hpp>

namespace gearpath::tools {

// A number >= 0 (integers and decimals alike; the option's own type does the conversion).
CLI::Validator NonNegative();
// A number > 0.
CLI::Validator Positive();

}  // namespace gearpath::tools
