#include "daemon/ip_address.h"

#include <arpa/inet.h>
#include <netinet/in.h>

#include <cstdint>
#include <cstring>

namespace gearpath::daemon {

bool ToSocketAddress(const std::string& address, int port, sockaddr_storage& out) {
  std::memset(&out, 0, sizeof(out));
  auto* v4 = reinterpret_cast<sockaddr_in*>(&out);
  if (inet_pton(AF_INET, address.c_str(), &v4->sin_addr) == 1) {
    v4->sin_family = AF_INET;
    v4->sin_port = htons(static_cast<std::uint16_t>(port));
    return true;
  }
  std::memset(&out, 0, sizeof(out));
  auto* v6 = reinterpret_cast<sockaddr_in6*>(&out);
  if (inet_pton(AF_INET6, address.c_str(), &v6->sin6_addr) == 1) {
    v6->sin6_family = AF_INET6;
    v6->sin6_port = htons(static_cast<std::uint16_t>(port));
    return true;
  }
  return false;
}

bool IsNumericAddress(const std::string& address) {
  sockaddr_storage sa{};
  return ToSocketAddress(address, 0, sa);
}

bool IsLoopbackAddress(const std::string& address) {
  sockaddr_storage sa{};
  if (!ToSocketAddress(address, 0, sa)) return false;
  if (sa.ss_family == AF_INET) {
    const auto* v4 = reinterpret_cast<const sockaddr_in*>(&sa);
    return (ntohl(v4->sin_addr.s_addr) >> 24) == 127;
  }
  const auto* v6 = reinterpret_cast<const sockaddr_in6*>(&sa);
  return IN6_IS_ADDR_LOOPBACK(&v6->sin6_addr);
}

}  // namespace gearpath::daemon
