// DaemonConfig: gearpathd's validated configuration (one JSON file, docs/configuration.md).
//
// Parsing goes JSON text -> schema (config_schema.h: types, ranges, unknown keys, defaults) ->
// cross-field rules (unique machine ids, unique channel rows, sample limits, gear-train
// consistency) -> this struct. Every error names its key path, e.g.
// `machines[0].analysis.inverse.method: expected one of mwi, tikhonov, least_squares, got "mwii"`.
// What needs files (the FRF sets) is checked when the machines are built (machine_runtime.h),
// still naming the key. The default configuration is config/gearpathd.json, compiled in.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "core/common/result.h"

namespace gearpath::daemon {

struct TopicNames {
  std::string accel_block;
  std::string accel_block_v2;  // empty: not read
  std::string dominant_path;
  std::string suspected_gear;
  std::string envelope_indicators;
  std::string condition_indicators;
  std::string status;
  std::string machine_health;
  bool operator==(const TopicNames&) const = default;
};

// dds.security: the six DDS Security files (idl/dds/security.h); all empty = no DDS Security.
struct DdsSecurityFiles {
  std::string identity_ca;
  std::string identity_certificate;
  std::string identity_private_key;
  std::string permissions_ca;
  std::string governance;
  std::string permissions;
  bool operator==(const DdsSecurityFiles&) const = default;
};

// metrics: the Prometheus endpoint (docs/deployment.md, "Metrics").
struct MetricsConfig {
  bool enabled = false;
  std::string address = "127.0.0.1";  // numeric; loopback unless allow_remote
  int port = 9469;                     // 0: a free port, logged
  bool allow_remote = false;
  bool operator==(const MetricsConfig&) const = default;
};

struct MachineConfig {
  std::string key_path;   // "machines[2]", for messages
  std::string id;
  std::string frf_set;    // directory, or "builtin:<name>"
  nlohmann::json settings;  // the machine's object, validated, defaults filled in
};

struct DaemonConfig {
  std::string origin;  // file name, or "<embedded default>"
  std::string daemon_id;
  std::string log_level;
  double status_period_s = 1.0;
  double throughput_log_period_s = 60.0;
  int workers = 0;       // daemon.workers: processing threads, 0 = hardware threads
  int queue_blocks = 32;  // daemon.queue_blocks: blocks queued per machine
  std::string state_directory;  // as configured; empty = $STATE_DIRECTORY or none
  double state_save_period_s = 30.0;
  std::string standby_primary;   // standby.primary: empty = a primary, always publishes
  double takeover_after_s = 0.0;  // standby.takeover_after_s, resolved (> 0 when standby)
  int domain_id = 0;
  TopicNames topics;
  std::string dds_config_file;    // dds.config: empty = CYCLONEDDS_URI, else loopback
  DdsSecurityFiles dds_security;  // dds.security
  MetricsConfig metrics;
  std::vector<MachineConfig> machines;
  nlohmann::json normalized;  // the whole config with defaults filled in
};

inline constexpr std::string_view kBuiltinPrefix = "builtin:";
// `"frf_set": "identity"`: monitoring before the hammer test (docs/configuration.md).
inline constexpr std::string_view kIdentityFrfSet = "identity";
inline constexpr std::string_view kEmbeddedOrigin = "<embedded default>";

// Parses and validates config text. `origin` prefixes JSON syntax errors.
Result<DaemonConfig> ParseDaemonConfig(std::string_view text, std::string_view origin);

// Reads and parses a config file (errors name the file).
Result<DaemonConfig> LoadDaemonConfigFile(const std::string& path);

// The embedded default configuration: config/gearpathd.json, compiled in at build time.
std::string_view DefaultConfigText();

}  // namespace gearpath::daemon
