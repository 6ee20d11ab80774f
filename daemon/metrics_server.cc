#include "daemon/metrics_server.h"

#include <fmt/format.h>
#include <microhttpd.h>
#include <spdlog/spdlog.h>

#include <atomic>
#include <cerrno>
#include <cstdarg>
#include <cstdio>
#include <cstring>
#include <exception>
#include <string_view>

#include "daemon/ip_address.h"

namespace gearpath::daemon {
namespace {

constexpr std::string_view kContentType = "text/plain; version=0.0.4; charset=utf-8";
constexpr unsigned kConnectionLimit = 16;
constexpr unsigned kIdleTimeoutS = 10;

MHD_Result Reply(MHD_Connection* connection, unsigned status, std::string_view type,
                 const std::string& body) {
  MHD_Response* response = MHD_create_response_from_buffer(
      body.size(), const_cast<char*>(body.data()), MHD_RESPMEM_MUST_COPY);
  if (response == nullptr) return MHD_NO;
  MHD_add_response_header(response, MHD_HTTP_HEADER_CONTENT_TYPE, std::string(type).c_str());
  if (status == MHD_HTTP_METHOD_NOT_ALLOWED) {
    MHD_add_response_header(response, MHD_HTTP_HEADER_ALLOW, "GET, HEAD");
  }
  const MHD_Result queued = MHD_queue_response(connection, status, response);
  MHD_destroy_response(response);
  return queued;
}

}  // namespace

struct MetricsServer::Impl {
  MetricsServer::Producer producer;
  std::string address;
  int port = 0;
  MHD_Daemon* daemon = nullptr;
  std::string start_errors;  // libmicrohttpd's messages while starting, for the error
  std::atomic<bool> starting{true};  // messages go to start_errors, later to the log

  static void Log(void* cls, const char* format, va_list args) {
    auto* self = static_cast<Impl*>(cls);
    char text[512];
    std::vsnprintf(text, sizeof(text), format, args);
    std::string_view line(text);
    while (!line.empty() && line.back() == '\n') line.remove_suffix(1);
    if (self->starting) {
      if (!self->start_errors.empty()) self->start_errors += "; ";
      self->start_errors += line;
    } else {
      spdlog::warn("metrics endpoint: {}", line);
    }
  }

  static MHD_Result Handle(void* cls, MHD_Connection* connection, const char* url,
                           const char* method, const char* /*version*/,
                           const char* /*upload_data*/, std::size_t* /*upload_data_size*/,
                           void** /*request_state*/) {
    auto* self = static_cast<Impl*>(cls);
    const std::string_view m(method);
    if (m != MHD_HTTP_METHOD_GET && m != MHD_HTTP_METHOD_HEAD) {
      return Reply(connection, MHD_HTTP_METHOD_NOT_ALLOWED, "text/plain; charset=utf-8",
                   "only GET and HEAD\n");
    }
    const std::string_view path(url);
    if (path == "/metrics") {
      try {
        return Reply(connection, MHD_HTTP_OK, kContentType, self->producer());
      } catch (const std::exception& e) {
        spdlog::error("metrics endpoint: the metrics could not be collected: {}", e.what());
        return Reply(connection, MHD_HTTP_INTERNAL_SERVER_ERROR, "text/plain; charset=utf-8",
                     "metrics not available\n");
      }
    }
    if (path == "/") {
      return Reply(connection, MHD_HTTP_OK, "text/plain; charset=utf-8",
                   "gearpathd: metrics at /metrics (Prometheus text format)\n");
    }
    return Reply(connection, MHD_HTTP_NOT_FOUND, "text/plain; charset=utf-8",
                 "not found: the metrics are at /metrics\n");
  }
};

Result<std::unique_ptr<MetricsServer>> MetricsServer::Start(const std::string& address,
                                                            int port, Producer producer) {
  sockaddr_storage sa{};
  if (!ToSocketAddress(address, port, sa)) {
    return Error{fmt::format("metrics.address: \"{}\" is not a numeric IPv4 or IPv6 address",
                             address)};
  }
  auto impl = std::make_unique<Impl>();
  impl->producer = std::move(producer);
  impl->address = address;
  unsigned flags = MHD_USE_AUTO_INTERNAL_THREAD | MHD_USE_ERROR_LOG;
  if (sa.ss_family == AF_INET6) flags |= MHD_USE_IPv6;
  errno = 0;
  impl->daemon = MHD_start_daemon(
      flags, static_cast<std::uint16_t>(port), nullptr, nullptr, &Impl::Handle, impl.get(),
      // The logger first: libmicrohttpd prints to stderr whatever comes before it.
      MHD_OPTION_EXTERNAL_LOGGER, &Impl::Log, impl.get(), MHD_OPTION_SOCK_ADDR,
      reinterpret_cast<sockaddr*>(&sa), MHD_OPTION_CONNECTION_LIMIT, kConnectionLimit,
      MHD_OPTION_CONNECTION_TIMEOUT, kIdleTimeoutS, MHD_OPTION_END);
  const int start_errno = errno;
  if (impl->daemon == nullptr) {
    std::string why = impl->start_errors;
    if (why.empty()) why = start_errno != 0 ? std::strerror(start_errno) : "unknown error";
    return Error{fmt::format("metrics endpoint: cannot listen on {}:{}: {}", address, port, why)};
  }
  impl->starting = false;
  const MHD_DaemonInfo* info = MHD_get_daemon_info(impl->daemon, MHD_DAEMON_INFO_BIND_PORT);
  impl->port = info != nullptr && info->port != 0 ? info->port : port;
  return std::unique_ptr<MetricsServer>(new MetricsServer(std::move(impl)));
}

MetricsServer::MetricsServer(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}

MetricsServer::~MetricsServer() {
  if (impl_ && impl_->daemon != nullptr) MHD_stop_daemon(impl_->daemon);
}

int MetricsServer::port() const noexcept { return impl_->port; }

std::string MetricsServer::url() const {
  const bool v6 = impl_->address.find(':') != std::string::npos;
  return v6 ? fmt::format("http://[{}]:{}/metrics", impl_->address, impl_->port)
            : fmt::format("http://{}:{}/metrics", impl_->address, impl_->port);
}

}  // namespace gearpath::daemon
