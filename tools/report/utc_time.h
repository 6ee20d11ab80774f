// Block times for people: ns since the Unix epoch as ISO 8601 UTC text.
#pragma once

#include <cstdint>
#include <string>

namespace gearpath::tools {

// "2026-11-23T12:15:00.125Z" (milliseconds, truncated towards the past); 0 ->
// "1970-01-01T00:00:00.000Z". Times before 1970 are written the same way.
std::string FormatUtc(std::int64_t ns_since_epoch);

// Clock time of day only, "12:15:00" (for axis ticks; the date is in the axis title).
std::string FormatUtcClock(std::int64_t ns_since_epoch);

}  // namespace gearpath::tools
