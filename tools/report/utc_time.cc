#include "tools/report/utc_time.h"

#include <fmt/format.h>

#include <ctime>

namespace gearpath::tools {
namespace {

struct UtcParts {
  std::tm tm{};
  int millisecond = 0;
};

// Split into whole seconds (floored, so times before 1970 keep a positive millisecond part)
// and the calendar fields of those seconds in UTC.
UtcParts Split(std::int64_t ns) {
  constexpr std::int64_t kNsPerMs = 1'000'000;
  const std::int64_t ms = ns / kNsPerMs - ((ns % kNsPerMs) < 0 ? 1 : 0);
  const std::int64_t sec = ms / 1000 - ((ms % 1000) < 0 ? 1 : 0);
  UtcParts p;
  p.millisecond = static_cast<int>(ms - sec * 1000);
  const std::time_t t = static_cast<std::time_t>(sec);
  gmtime_r(&t, &p.tm);
  return p;
}

}  // namespace

std::string FormatUtc(std::int64_t ns_since_epoch) {
  const UtcParts p = Split(ns_since_epoch);
  return fmt::format("{:04d}-{:02d}-{:02d}T{:02d}:{:02d}:{:02d}.{:03d}Z", p.tm.tm_year + 1900,
                     p.tm.tm_mon + 1, p.tm.tm_mday, p.tm.tm_hour, p.tm.tm_min, p.tm.tm_sec,
                     p.millisecond);
}

std::string FormatUtcClock(std::int64_t ns_since_epoch) {
  const UtcParts p = Split(ns_since_epoch);
  return fmt::format("{:02d}:{:02d}:{:02d}", p.tm.tm_hour, p.tm.tm_min, p.tm.tm_sec);
}

}  // namespace gearpath::tools
