// ConfigSchema: every gearpathd configuration parameter, declared once.
//
// A parameter is declared with its name, meaning, type, range or choices and default (the
// Essentia way). The same declaration tree (1) validates a JSON config, naming the key path of
// every error (`machines[0].analysis.inverse.method: expected one of ...`), rejecting unknown
// keys, (2) fills in defaults, and (3) renders the reference table of docs/configuration.md,
// so the documentation cannot drift from what the daemon accepts. Cross-field rules (unique
// machine ids, gear references) are not expressible here; daemon_config.h checks them.
#pragma once

#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/common/result.h"

namespace gearpath::daemon {

enum class ParamKind { kObject, kArray, kString, kEnum, kInteger, kNumber, kBoolean };

struct ParamSpec {
  std::string name;
  std::string meaning;
  ParamKind kind = ParamKind::kString;
  bool required = false;
  nlohmann::json default_value;  // filled in when absent and not required (null: left absent)
  double min = -std::numeric_limits<double>::infinity();  // kInteger / kNumber, inclusive
  double max = std::numeric_limits<double>::infinity();
  bool min_exclusive = false;         // kNumber: value must be > min rather than >= min
  bool max_exclusive = false;         // kNumber: value must be < max rather than <= max
  std::vector<std::string> choices;   // kEnum
  std::size_t min_size = 0;           // kString: minimum length; kArray: minimum items
  std::size_t max_size = std::numeric_limits<std::size_t>::max();
  std::vector<ParamSpec> fields;      // kObject: the allowed keys
  std::vector<ParamSpec> element;     // kArray: exactly one spec, the element's
};

// The gearpathd configuration schema (root object).
const ParamSpec& DaemonConfigSchema();

// Checks `config` against `schema`. Returns the config with every default filled in, or all
// errors found, one per line, each starting with the key path (`dds.domain_id: ...`).
Result<nlohmann::json> ApplySchema(const ParamSpec& schema, const nlohmann::json& config);

// The parameter reference as a Markdown table (one row per leaf key, e.g.
// `machines[].analysis.inverse.method`), generated from the schema.
std::string RenderSchemaReference(const ParamSpec& schema);

}  // namespace gearpath::daemon
