#include "tools/common/dds_options.h"

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <utility>

#include "tools/common/cli_checks.h"

namespace gearpath::tools {

namespace fs = std::filesystem;
using nlohmann::json;

void AddDdsOptions(CLI::App* cmd, DdsOptions* options) {
  cmd->add_option("--dds-config", options->config_file,
                  "Cyclone DDS XML configuration file (replaces the built-in loopback one and "
                  "CYCLONEDDS_URI; docs/deployment.md)");
  cmd->add_option("--dds-security", options->security_file,
                  "JSON file naming this participant's six DDS Security files (as the daemon's "
                  "dds.security; docs/deployment.md)");
}

void AddPublishingOptions(CLI::App* cmd, int* domain_id, DdsOptions* options, int* subscribers,
                          double* wait_s) {
  cmd->add_option("--domain", *domain_id, "DDS domain id")
      ->capture_default_str()
      ->check(CLI::Range(0, 232));
  AddDdsOptions(cmd, options);
  cmd->add_option("--subscribers", *subscribers,
                  "Wait for this many subscribers before the first block")
      ->capture_default_str()
      ->check(NonNegative());
  cmd->add_option("--wait", *wait_s, "Seconds to wait for the subscribers before the first block")
      ->capture_default_str()
      ->check(NonNegative());
}

dds::DomainConfig ToolDomainConfig(const DdsOptions& options) {
  return dds::ResolveDomainConfig(options.config_file, dds::EnvironmentConfig::kApply);
}

Result<dds::SecurityFiles> LoadSecurityFiles(const std::string& path) {
  if (path.empty()) return dds::SecurityFiles{};
  std::ifstream in(path, std::ios::binary);
  if (!in) return Error{path + ": cannot open the DDS Security file"};
  json j;
  try {
    j = json::parse(in);
  } catch (const json::exception& e) {
    return Error{path + ": not valid JSON: " + e.what()};
  }
  if (!j.is_object()) return Error{path + ": expected a JSON object of six file names"};
  dds::SecurityFiles files;
  const std::pair<const char*, std::string*> keys[] = {
      {"identity_ca", &files.identity_ca},
      {"identity_certificate", &files.identity_certificate},
      {"identity_private_key", &files.identity_private_key},
      {"permissions_ca", &files.permissions_ca},
      {"governance", &files.governance},
      {"permissions", &files.permissions}};
  for (const auto& [key, value] : j.items()) {
    bool known = false;
    for (const auto& k : keys) known = known || key == k.first;
    if (!known) return Error{path + ": " + key + ": unknown key"};
  }
  const fs::path base = fs::path(path).parent_path();
  for (const auto& [key, target] : keys) {
    const auto it = j.find(key);
    if (it == j.end() || !it->is_string() || it->get<std::string>().empty()) {
      return Error{path + ": " + key + ": required (a file name)"};
    }
    const fs::path file = it->get<std::string>();
    *target = (file.is_absolute() ? file : base / file).string();
  }
  if (Status readable = dds::CheckSecurityFiles(files); !readable) {
    return Error{path + ": " + readable.error()};
  }
  return files;
}

dds::SecurityFiles ToolSecurityFiles(const DdsOptions& options) {
  auto files = LoadSecurityFiles(options.security_file);
  if (!files) throw std::runtime_error(files.error());
  return std::move(files.value());
}

}  // namespace gearpath::tools
