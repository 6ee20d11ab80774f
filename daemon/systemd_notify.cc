#include "daemon/systemd_notify.h"

#include <string>

#ifdef GEARPATH_HAVE_SYSTEMD
#include <systemd/sd-daemon.h>
#endif

namespace gearpath::daemon {

void NotifySystemd(std::string_view state) {
#ifdef GEARPATH_HAVE_SYSTEMD
  const std::string text(state);
  sd_notify(0, text.c_str());
#else
  (void)state;
#endif
}

std::chrono::microseconds SystemdWatchdogPeriod() {
#ifdef GEARPATH_HAVE_SYSTEMD
  std::uint64_t usec = 0;
  if (sd_watchdog_enabled(0, &usec) > 0) {
    return std::chrono::microseconds(static_cast<std::int64_t>(usec));
  }
#endif
  return std::chrono::microseconds(0);
}

}  // namespace gearpath::daemon
