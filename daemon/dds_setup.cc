#include "daemon/dds_setup.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cstdlib>
#include <stdexcept>
#include <string>

namespace gearpath::daemon {

namespace {

dds::SecurityFiles SecurityFilesOf(const DaemonConfig& config) {
  const DdsSecurityFiles& s = config.dds_security;
  return {s.identity_ca,    s.identity_certificate, s.identity_private_key,
          s.permissions_ca, s.governance,           s.permissions};
}

// CheckSecurityFiles' "key: why" lines, each prefixed with the section.
std::string InSecuritySection(const std::string& lines) {
  std::string message;
  std::size_t from = 0;
  while (from < lines.size()) {
    const std::size_t end = std::min(lines.find('\n', from), lines.size());
    message += (message.empty() ? "" : "\n") + ("dds.security." + lines.substr(from, end - from));
    from = end + 1;
  }
  return message;
}

}  // namespace

Status CheckDdsFiles(const DaemonConfig& config) {
  std::string errors;
  if (!config.dds_config_file.empty()) {
    try {
      (void)dds::ResolveDomainConfig(config.dds_config_file, dds::EnvironmentConfig::kIgnore);
    } catch (const std::exception& e) {
      errors = std::string("dds.config: ") + e.what();
    }
  }
  if (const dds::SecurityFiles files = SecurityFilesOf(config); files.enabled()) {
    if (Status readable = dds::CheckSecurityFiles(files); !readable) {
      errors += (errors.empty() ? "" : "\n") + InSecuritySection(readable.error());
    }
  }
  if (!errors.empty()) return Error{errors};
  return Status::Ok();
}

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
  const dds::SecurityFiles files = SecurityFilesOf(config);
  if (!files.enabled()) {
    spdlog::info(
        "DDS Security off (dds.security names no files): any participant on the "
        "domain may publish blocks and read or write results");
    return files;
  }
  if (Status readable = dds::CheckSecurityFiles(files); !readable) {
    throw std::runtime_error(InSecuritySection(readable.error()));
  }
  spdlog::info("DDS Security on: identity {}, permissions {}, governance {} (plugins from {})",
               files.identity_certificate, files.permissions, files.governance,
               *dds::SecurityPluginDirectory() != '\0' ? dds::SecurityPluginDirectory()
                                                       : "Cyclone's default library path");
  return files;
}

}  // namespace gearpath::daemon
