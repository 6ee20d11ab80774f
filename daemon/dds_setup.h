// The daemon's DDS set-up decisions, made and logged once at start-up: which Cyclone
// configuration is in force (`dds.config`, else CYCLONEDDS_URI, else the embedded loopback
// configuration; never a merge of them, idl/dds/domain.h), the network interfaces Cyclone
// selects with it, and whether DDS Security is on and with which files (`dds.security`).
#pragma once

#include "daemon/daemon_config.h"
#include "idl/dds/domain.h"
#include "idl/dds/security.h"

namespace gearpath::daemon {

// `dds.config` and the `dds.security` files exist and are readable (Cyclone verifies their
// content when the domain and participant are created). Errors name the key and the file, one
// per line. gearpathd --check-config runs it, as the start does.
Status CheckDdsFiles(const DaemonConfig& config);

// The configuration for the daemon's Domain. Logs its origin and the interfaces Cyclone selects
// (found by a probe, so call it before the daemon's Domain exists). Throws std::runtime_error
// naming `dds.config` and the file if it cannot be read, or with Cyclone's reason if Cyclone
// refuses the configuration (an interface that does not exist, one selected twice).
dds::DomainConfig DaemonDomainConfig(const DaemonConfig& config);

// `dds.security` for the daemon's Participant (disabled when no file is named). Logs whether
// DDS Security is on. Throws std::runtime_error naming each `dds.security.<key>` whose file
// cannot be read.
dds::SecurityFiles DaemonSecurityFiles(const DaemonConfig& config);

}  // namespace gearpath::daemon
