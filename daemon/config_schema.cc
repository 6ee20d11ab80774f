#include "daemon/config_schema.h"

#include <fmt/format.h>

#include <cmath>
#include <set>

namespace gearpath::daemon {
namespace {

using nlohmann::json;

std::string Join(const std::vector<std::string>& items, std::string_view separator) {
  std::string out;
  for (std::size_t i = 0; i < items.size(); ++i) {
    if (i > 0) out += separator;
    out += items[i];
  }
  return out;
}

// A value as the user wrote it, shortened so one bad key cannot flood the log.
std::string Shown(const json& value) {
  std::string text = value.dump();
  constexpr std::size_t kMax = 60;
  if (text.size() > kMax) text = text.substr(0, kMax) + "...";
  return text;
}

std::string TypeName(ParamKind kind) {
  switch (kind) {
    case ParamKind::kObject: return "object";
    case ParamKind::kArray: return "array";
    case ParamKind::kString: return "string";
    case ParamKind::kEnum: return "string";
    case ParamKind::kInteger: return "integer";
    case ParamKind::kNumber: return "number";
    case ParamKind::kBoolean: return "boolean";
  }
  return "?";
}

std::string Number(double v) {
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  return fmt::format("{}", v);
}

std::string Child(const std::string& path, const std::string& key) {
  return path.empty() ? key : path + "." + key;
}

std::string RangeText(const ParamSpec& spec);

class Validator {
 public:
  std::vector<std::string> errors;

  // Returns the value with defaults filled in (meaningful only when no error was added).
  json Apply(const ParamSpec& spec, const json& value, const std::string& path) {
    const std::string where = path.empty() ? "(root)" : path;
    switch (spec.kind) {
      case ParamKind::kObject: return ApplyObject(spec, value, path, where);
      case ParamKind::kArray: return ApplyArray(spec, value, path, where);
      case ParamKind::kString:
        if (!value.is_string()) return Fail(where, "a string", value);
        CheckSize(spec, value.get_ref<const std::string&>().size(), where, "characters");
        return value;
      case ParamKind::kEnum: {
        const auto* text = value.is_string() ? &value.get_ref<const std::string&>() : nullptr;
        bool known = false;
        for (const auto& c : spec.choices) known = known || (text != nullptr && *text == c);
        if (!known) {
          errors.push_back(fmt::format("{}: expected one of {}, got {}", where,
                                       Join(spec.choices, ", "), Shown(value)));
        }
        return value;
      }
      case ParamKind::kInteger: {
        if (!value.is_number() ||
            (value.is_number_float() && value.get<double>() != std::floor(value.get<double>()))) {
          return Fail(where, "an integer", value);
        }
        const double v = value.get<double>();
        CheckRange(spec, v, where);
        // An integral float beyond int64 (6.6e56, found by fuzzing) has failed the range check
        // already; converting it would be undefined behaviour, so it stays as written.
        const bool fits = std::abs(v) < 0x1p63;
        return value.is_number_float() && fits ? json(static_cast<std::int64_t>(v)) : value;
      }
      case ParamKind::kNumber:
        if (!value.is_number()) return Fail(where, "a number", value);
        CheckRange(spec, value.get<double>(), where);
        return value;
      case ParamKind::kBoolean:
        if (!value.is_boolean()) return Fail(where, "true or false", value);
        return value;
    }
    return value;
  }

 private:
  json Fail(const std::string& where, std::string_view expected, const json& value) {
    errors.push_back(fmt::format("{}: expected {}, got {} {}", where, expected,
                                 value.type_name(), Shown(value)));
    return value;
  }

  void CheckRange(const ParamSpec& spec, double v, const std::string& where) {
    const bool below = spec.min_exclusive ? !(v > spec.min) : !(v >= spec.min);
    const bool above = spec.max_exclusive ? !(v < spec.max) : !(v <= spec.max);
    if (below || above || !std::isfinite(v)) {
      errors.push_back(fmt::format("{}: expected a value in {}, got {}", where, RangeText(spec),
                                   Number(v)));
    }
  }

  void CheckSize(const ParamSpec& spec, std::size_t size, const std::string& where,
                 std::string_view unit) {
    if (size < spec.min_size) {
      errors.push_back(fmt::format("{}: expected at least {} {}, got {}", where, spec.min_size,
                                   unit, size));
    } else if (size > spec.max_size) {
      errors.push_back(
          fmt::format("{}: expected at most {} {}, got {}", where, spec.max_size, unit, size));
    }
  }

  json ApplyObject(const ParamSpec& spec, const json& value, const std::string& path,
                   const std::string& where) {
    if (!value.is_object()) return Fail(where, "an object", value);
    json out = json::object();
    std::vector<std::string> allowed;
    for (const auto& field : spec.fields) allowed.push_back(field.name);
    for (const auto& [key, item] : value.items()) {
      bool known = false;
      for (const auto& name : allowed) known = known || name == key;
      if (!known) {
        errors.push_back(fmt::format("{}: unknown key (allowed here: {})", Child(path, key),
                                     Join(allowed, ", ")));
      }
    }
    for (const auto& field : spec.fields) {
      const std::string child = Child(path, field.name);
      const auto it = value.find(field.name);
      if (it != value.end()) {
        out[field.name] = Apply(field, *it, child);
      } else if (field.required) {
        errors.push_back(fmt::format("{}: required key is missing", child));
      } else if (field.kind == ParamKind::kObject) {
        out[field.name] = Apply(field, json::object(), child);  // fill nested defaults
      } else if (!field.default_value.is_null()) {
        out[field.name] = field.default_value;
      }
    }
    return out;
  }

  json ApplyArray(const ParamSpec& spec, const json& value, const std::string& path,
                  const std::string& where) {
    if (!value.is_array()) return Fail(where, "an array", value);
    CheckSize(spec, value.size(), where, "items");
    json out = json::array();
    for (std::size_t i = 0; i < value.size(); ++i) {
      out.push_back(Apply(spec.element.front(), value[i], fmt::format("{}[{}]", path, i)));
    }
    return out;
  }
};

std::string Escape(std::string text) {
  std::string out;
  for (char c : text) {
    if (c == '|') out += "\\";
    out += c;
  }
  return out;
}

std::string RangeText(const ParamSpec& spec) {
  switch (spec.kind) {
    case ParamKind::kEnum: return Join(spec.choices, ", ");
    case ParamKind::kInteger:
    case ParamKind::kNumber:
      if (std::isinf(spec.min) && std::isinf(spec.max)) return "";
      return fmt::format("{}{}, {}{}", spec.min_exclusive ? "(" : "[", Number(spec.min),
                         Number(spec.max), spec.max_exclusive ? ")" : "]");
    case ParamKind::kString:
      return spec.min_size > 0 ? fmt::format("non-empty, at most {} chars", spec.max_size) : "";
    case ParamKind::kArray:
      if (spec.max_size == std::numeric_limits<std::size_t>::max()) {
        return spec.min_size > 0 ? fmt::format("at least {} items", spec.min_size) : "";
      }
      return fmt::format("{} to {} items", spec.min_size, spec.max_size);
    default: return "";
  }
}

void RenderRows(const ParamSpec& spec, const std::string& path, std::string& out) {
  if (!path.empty()) {
    std::string fallback;
    if (spec.required) {
      fallback = "required";
    } else if (!spec.default_value.is_null()) {
      fallback = "`" + spec.default_value.dump() + "`";
    } else if (spec.kind == ParamKind::kObject) {
      fallback = "";
    } else {
      fallback = "(absent)";
    }
    out += fmt::format("| `{}` | {} | {} | {} | {} |\n", path, TypeName(spec.kind),
                       Escape(RangeText(spec)), Escape(fallback), Escape(spec.meaning));
  }
  if (spec.kind == ParamKind::kObject) {
    for (const auto& field : spec.fields) RenderRows(field, Child(path, field.name), out);
  } else if (spec.kind == ParamKind::kArray && spec.element.front().kind == ParamKind::kObject) {
    for (const auto& field : spec.element.front().fields) {
      RenderRows(field, Child(path + "[]", field.name), out);
    }
  }
}

}  // namespace

Result<nlohmann::json> ApplySchema(const ParamSpec& schema, const nlohmann::json& config) {
  Validator validator;
  json out = validator.Apply(schema, config, "");
  if (!validator.errors.empty()) return Error{Join(validator.errors, "\n")};
  return out;
}

std::string RenderSchemaReference(const ParamSpec& schema) {
  std::string out =
      "| Key | Type | Range / choices | Default | Meaning |\n"
      "|---|---|---|---|---|\n";
  RenderRows(schema, "", out);
  return out;
}

}  // namespace gearpath::daemon
