// systemd readiness and watchdog notifications (sd_notify), optional at build time.
//
// Built with libsystemd (GEARPATH_HAVE_SYSTEMD) these forward to sd_notify(); without it, or
// when the daemon was not started by systemd (no NOTIFY_SOCKET), they do nothing. Messages:
// READY=1, RELOADING=1, STOPPING=1, WATCHDOG=1, STATUS=<one line>.
#pragma once

#include <chrono>
#include <string_view>

namespace gearpath::daemon {

void NotifySystemd(std::string_view state);

// The watchdog period systemd expects (WatchdogSec), or zero when no watchdog is armed.
std::chrono::microseconds SystemdWatchdogPeriod();

}  // namespace gearpath::daemon
