// TcpListener: the bridge's listening socket for stream mode. One connection at a time: a
// stream's blocks must keep their order and the state its single sequence counter.
#pragma once

#include <atomic>
#include <cstdint>
#include <string>

#include "core/common/result.h"

namespace gearpath::tools {

class TcpListener {
 public:
  // Binds `address` (an IPv4 literal; 127.0.0.1 by default in the command) and `port`
  // (0: any free port, see port()). Errors name the address and the failing call.
  static Result<TcpListener> Listen(const std::string& address, std::uint16_t port);
  ~TcpListener();
  TcpListener(TcpListener&& other) noexcept;
  TcpListener& operator=(TcpListener&&) = delete;
  TcpListener(const TcpListener&) = delete;

  std::uint16_t port() const { return port_; }

  // Waits for the next connection; returns its descriptor (the caller closes it), or -1 once
  // `stop` is set. Errors are the accept call's.
  Result<int> Accept(const std::atomic<bool>& stop, std::string* peer);

 private:
  TcpListener(int fd, std::uint16_t port) : fd_(fd), port_(port) {}
  int fd_ = -1;
  std::uint16_t port_ = 0;
};

}  // namespace gearpath::tools
