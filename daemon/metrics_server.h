// MetricsServer: the HTTP endpoint that serves the metrics text (GET /metrics), on Debian's
// libmicrohttpd.
//
// One internal thread (libmicrohttpd's polling thread) answers every request, so the producer
// is never called concurrently with itself. It calls the producer once per scrape; what the
// producer reads is its own business (gearpathd reads its counters under their locks). No TLS,
// no authentication: the endpoint listens on loopback unless the configuration says otherwise
// (docs/deployment.md, "Metrics"). At most 16 connections, each closed after 10 s idle.
#pragma once

#include <functional>
#include <memory>
#include <string>

#include "core/common/result.h"

namespace gearpath::daemon {

class MetricsServer {
 public:
  using Producer = std::function<std::string()>;

  // Listens on `address` (a numeric IPv4 or IPv6 address) and `port` (0: a free port chosen
  // by the kernel, see port()). Errors name the address and say why.
  static Result<std::unique_ptr<MetricsServer>> Start(const std::string& address, int port,
                                                      Producer producer);
  ~MetricsServer();  // stops listening; a request in progress is finished first
  MetricsServer(const MetricsServer&) = delete;
  MetricsServer& operator=(const MetricsServer&) = delete;

  int port() const noexcept;  // the port bound (the chosen one when 0 was asked for)
  std::string url() const;    // http://address:port/metrics

  struct Impl;  // public for libmicrohttpd's C callbacks only

 private:
  explicit MetricsServer(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace gearpath::daemon
