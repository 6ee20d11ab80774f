#include "daemon/heap_trim.h"

#include <malloc.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace gearpath::daemon {

HeapTrimmer::HeapTrimmer(Clock::duration period, Clock::time_point now)
    : period_(period), next_(now + period) {}

bool HeapTrimmer::MaybeTrim(Clock::time_point now) {
  if (now < next_) return false;
  (void)Trim();
  next_ = now + period_;
  return true;
}

long HeapTrimmer::Trim() {
  const long before = ResidentKb();
  ::malloc_trim(0);
  const long after = ResidentKb();
  return before < 0 || after < 0 ? 0 : before - after;
}

long HeapTrimmer::ResidentKb() {
  std::FILE* f = std::fopen("/proc/self/status", "re");
  if (f == nullptr) return -1;
  char line[256];
  long kb = -1;
  while (std::fgets(line, sizeof line, f) != nullptr) {
    if (std::strncmp(line, "VmRSS:", 6) == 0) {
      kb = std::strtol(line + 6, nullptr, 10);
      break;
    }
  }
  std::fclose(f);
  return kb;
}

}  // namespace gearpath::daemon
