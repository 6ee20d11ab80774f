#include "tools/common/cli_checks.h"

#include <cmath>
#include <cstdlib>
#include <string>

namespace gearpath::tools {
namespace {

// The value as a finite number, or NaN when the text is not one.
double AsNumber(const std::string& text) {
  if (text.empty()) return std::nan("");
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  return end == text.c_str() + text.size() && std::isfinite(v) ? v : std::nan("");
}

CLI::Validator NumberCheck(bool strict, const char* description) {
  return CLI::Validator(
      [strict, description](std::string& text) -> std::string {
        const double v = AsNumber(text);
        if (std::isnan(v) || (strict ? !(v > 0.0) : !(v >= 0.0))) {
          return std::string("expected ") + description + ", got '" + text + "'";
        }
        return {};
      },
      strict ? "NUMBER > 0" : "NUMBER >= 0", strict ? "POSITIVE" : "NONNEGATIVE");
}

}  // namespace

CLI::Validator NonNegative() { return NumberCheck(false, "a number >= 0"); }
CLI::Validator Positive() { return NumberCheck(true, "a number > 0"); }

}  // namespace gearpath::tools
