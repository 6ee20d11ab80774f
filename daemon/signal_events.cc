#include "daemon/signal_events.h"

#include <fmt/format.h>
#include <poll.h>
#include <pthread.h>
#include <sys/signalfd.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstring>

namespace gearpath::daemon {

Result<SignalEvents> SignalEvents::Open() {
  sigset_t set;
  sigemptyset(&set);
  sigaddset(&set, SIGTERM);
  sigaddset(&set, SIGINT);
  sigaddset(&set, SIGHUP);
  if (const int rc = pthread_sigmask(SIG_BLOCK, &set, nullptr); rc != 0) {
    return Error{fmt::format("cannot block SIGTERM/SIGINT/SIGHUP: {}", std::strerror(rc))};
  }
  const int fd = signalfd(-1, &set, SFD_CLOEXEC);
  if (fd < 0) return Error{fmt::format("signalfd failed: {}", std::strerror(errno))};
  return SignalEvents(fd);
}

SignalEvents::SignalEvents(SignalEvents&& other) noexcept
    : fd_(other.fd_), last_signal_(other.last_signal_) {
  other.fd_ = -1;
}

SignalEvents::~SignalEvents() {
  if (fd_ >= 0) close(fd_);
}

SignalEvent SignalEvents::Wait(std::chrono::milliseconds timeout) const {
  pollfd pfd{fd_, POLLIN, 0};
  const int ready = poll(&pfd, 1, static_cast<int>(timeout.count()));
  if (ready <= 0) return SignalEvent::kNone;  // timeout, or EINTR from a debugger
  signalfd_siginfo info{};
  if (read(fd_, &info, sizeof info) != static_cast<ssize_t>(sizeof info)) {
    return SignalEvent::kNone;
  }
  last_signal_ = static_cast<int>(info.ssi_signo);
  switch (info.ssi_signo) {
    case SIGTERM:
    case SIGINT: return SignalEvent::kTerminate;
    case SIGHUP: return SignalEvent::kReload;
    default: return SignalEvent::kNone;
  }
}

}  // namespace gearpath::daemon
