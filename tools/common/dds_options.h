// DdsOptions: how a gearpath tool joins the DDS domain, the same choices as the daemon's `dds`
// section (docs/deployment.md):
//   --dds-config FILE    a Cyclone XML configuration file (the daemon's `dds.config`): it alone
//                        decides interfaces, peers and ports; without it CYCLONEDDS_URI if set,
//                        else the built-in loopback configuration
//   --dds-security FILE  a JSON object with the six DDS Security files, the daemon's
//                        `dds.security` object (tools/make-security-fixtures.sh writes one per
//                        identity); relative paths are taken from the file's directory
#pragma once

#include <CLI/CLI.hpp>
#include <string>

#include "core/common/result.h"
#include "idl/dds/domain.h"
#include "idl/dds/security.h"

namespace gearpath::tools {

struct DdsOptions {
  std::string config_file;
  std::string security_file;
};

// Adds --dds-config and --dds-security to `cmd`.
void AddDdsOptions(CLI::App* cmd, DdsOptions* options);

// A publishing tool's (replay, bridge) --domain, --dds-config, --dds-security, --subscribers
// (readers to wait for before the first block) and --wait (seconds to wait for them).
void AddPublishingOptions(CLI::App* cmd, int* domain_id, DdsOptions* options, int* subscribers,
                          double* wait_s);

// The domain configuration in force for these options (throws std::runtime_error naming the
// file if it cannot be read).
dds::DomainConfig ToolDomainConfig(const DdsOptions& options);

// The security files of --dds-security (disabled without it). Errors name the file and key.
Result<dds::SecurityFiles> LoadSecurityFiles(const std::string& path);

// Both, for a tool's participant; throws std::runtime_error with the reason.
dds::SecurityFiles ToolSecurityFiles(const DdsOptions& options);

}  // namespace gearpath::tools
