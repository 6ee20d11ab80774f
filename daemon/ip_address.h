// Numeric IP addresses as the configuration gives them (metrics.address): parsed, classified
// (loopback or not) and turned into a socket address. No name resolution: a host name would
// make the address the daemon listens on depend on DNS at start-up.
#pragma once

#include <sys/socket.h>

#include <string>

namespace gearpath::daemon {

// Fills `out` (port in network order) for a numeric IPv4 ("127.0.0.1") or IPv6 ("::1")
// address; false for anything else.
bool ToSocketAddress(const std::string& address, int port, sockaddr_storage& out);
// True when `address` is a numeric IPv4 or IPv6 address.
bool IsNumericAddress(const std::string& address);
// True for 127.0.0.0/8 and ::1.
bool IsLoopbackAddress(const std::string& address);

}  // namespace gearpath::daemon
