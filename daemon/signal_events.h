// SignalEvents: SIGTERM, SIGINT and SIGHUP as readable events (Linux signalfd), not handlers.
//
// No work happens in a signal handler: the signals are blocked in every thread and read from a
// signalfd by the thread that owns the lifecycle. Construct it in main() BEFORE any other
// thread exists (the DDS library starts threads when the domain is created): threads inherit
// the signal mask, so a signal can then only be delivered through the descriptor.
#pragma once

#include <chrono>

#include "core/common/result.h"

namespace gearpath::daemon {

enum class SignalEvent { kNone, kTerminate, kReload };

class SignalEvents {
 public:
  // Blocks SIGTERM, SIGINT and SIGHUP in the calling thread and opens the signalfd.
  static Result<SignalEvents> Open();
  SignalEvents(SignalEvents&& other) noexcept;
  SignalEvents& operator=(SignalEvents&&) = delete;
  SignalEvents(const SignalEvents&) = delete;
  ~SignalEvents();

  // Waits up to `timeout` for one signal. kNone on timeout.
  SignalEvent Wait(std::chrono::milliseconds timeout) const;
  int signal_of_last_event() const { return last_signal_; }

 private:
  explicit SignalEvents(int fd) : fd_(fd) {}
  int fd_ = -1;
  mutable int last_signal_ = 0;
};

}  // namespace gearpath::daemon
