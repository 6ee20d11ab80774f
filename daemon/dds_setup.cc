#include "daemon/dds_setup.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cstdlib>
#include <stdexcept>
#include <string>

namespace gearpath::daemon {

dds::DomainConfig DaemonDomainConfig(const DaemonConfig& config) {
  dds::DomainConfig resolved;
  try {
    resolved = dds::ResolveDomainConfig(config.dds_config_file, dds::EnvironmentConfig::kApply);
  } catch (const std::exception& e) {
    throw std::runtime_error(std::string("dds.config: ") + e.what());
  }
  const char* uri = std::getenv("CYCLONEDDS_URI");  // NOLINT(concurrency-mt-unsafe): start-up
  if (!config.dds_config_file.empty() && uri != nullptr && *uri != '\0') {
    spdlog::warn("CYCLONEDDS_URI is set but ignored: dds.config names the DDS configuration");
  }
  const std::string interfaces = dds::SelectedInterfaces(config.domain_id, resolved.text);
  spdlog::info("DDS domain {}: configuration from {}; selected interfaces: {}", config.domain_id,
               resolved.origin, interfaces);
  return resolved;
}

dds::SecurityFiles DaemonSecurityFiles(const DaemonConfig& config) {
  const DdsSecurityFiles& s = config.dds_security;
  const dds::SecurityFiles files{s.identity_ca,    s.identity_certificate, s.identity_private_key,
                                 s.permissions_ca, s.governance,           s.permissions};
  if (!files.enabled()) {
    spdlog::info(
        "DDS Security off (dds.security names no files): any participant on the "
        "domain may publish blocks and read or write results");
    return files;
  }
  if (Status readable = dds::CheckSecurityFiles(files); !readable) {
    std::string message;
    std::size_t from = 0;
    const std::string& lines = readable.error();
    while (from < lines.size()) {  // prefix every "key: why" line with the section
      const std::size_t end = std::min(lines.find('\n', from), lines.size());
      message += (message.empty() ? "" : "\n") + ("dds.security." + lines.substr(from, end - from));
      from = end + 1;
    }
    throw std::runtime_error(message);
  }
  spdlog::info("DDS Security on: identity {}, permissions {}, governance {} (plugins from {})",
               files.identity_certificate, files.permissions, files.governance,
               *dds::SecurityPluginDirectory() != '\0' ? dds::SecurityPluginDirectory()
                                                       : "Cyclone's default library path");
  return files;
}

}  // namespace gearpath::daemon
