// Domain and Participant: a Cyclone DDS domain created from an explicit XML configuration, and
// the participants on it, optionally with DDS Security.
//
// Which configuration is in force is decided here, once, and never by merging: Cyclone reads
// CYCLONEDDS_URI only when a domain is created implicitly (by the first dds_create_participant
// on an id that has no domain yet), while dds_create_domain(id, config) uses exactly the string
// it is given (Cyclone 0.10 src/core/ddsc/src/dds_domain.c). ResolveDomainConfig picks one of
//   1. a deployment file (the daemon's `dds.config`, the tools' `--dds-config`),
//   2. CYCLONEDDS_URI, when EnvironmentConfig::kApply is chosen and the variable is set,
//   3. the project's loopback configuration (kLoopbackConfigXml, generated from
//      config/cyclonedds-loopback.xml: 127.0.0.1, multicast off),
// and the chosen one alone determines interfaces, peers and ports. (Merging a deployment file
// into the loopback one selected `lo` twice or added the plant NIC beside it.) Tests use
// kIgnore so they stay on loopback whatever the environment says.
//
// One Domain per domain id per process (Cyclone refuses a second dds_create_domain on the same
// id); every Participant keeps its Domain alive.
#pragma once

#include <dds/dds.h>

#include <string>
#include <string_view>

#include "idl/dds/entity.h"
#include "idl/dds/loopback_config_xml.h"
#include "idl/dds/security.h"

namespace gearpath::dds {

enum class EnvironmentConfig {
  kApply,   // CYCLONEDDS_URI (if set and non-empty) replaces the given configuration
  kIgnore,  // use the given configuration only
};

// A Cyclone configuration string and where it came from.
struct DomainConfig {
  std::string text;    // what dds_create_domain gets: XML, or Cyclone's comma-separated list
  std::string origin;  // for logs: "file /etc/gearpath/cyclonedds.xml", "CYCLONEDDS_URI", ...
};

// The configuration in force (see the top of this file). `config_file`, if non-empty, is read
// here (its content is the configuration: Cyclone then never looks at the environment).
// Throws std::runtime_error naming the file if it cannot be read or is empty.
DomainConfig ResolveDomainConfig(std::string_view config_file, EnvironmentConfig environment);

// `config_xml`, or CYCLONEDDS_URI instead of it under kApply when that is set and non-empty.
DomainConfig ResolveDomainConfig(DomainConfig base, EnvironmentConfig environment);

// The network interfaces Cyclone selects for `config` on domain `id`, as its own trace says
// ("lo (index 1 priority 2 loopback)"). Found by creating the domain once with Cyclone's
// config tracing sent to a capture sink, then deleting it: no participant exists, so nothing
// is sent. Call it before the real Domain for `id` exists (one domain per id per process) and
// while no other thread uses Cyclone's log sinks. Throws std::runtime_error if Cyclone rejects
// the configuration (with Cyclone's error lines, e.g. an interface that does not exist).
std::string SelectedInterfaces(dds_domainid_t id, const std::string& config);

class Domain : public Entity {
 public:
  // Throws std::runtime_error naming dds_create_domain and the id if Cyclone rejects the
  // configuration or the id already has a domain in this process. `id` must not be
  // DDS_DOMAIN_DEFAULT.
  explicit Domain(dds_domainid_t id, std::string_view config_xml = kLoopbackConfigXml,
                  EnvironmentConfig environment = EnvironmentConfig::kApply);
  Domain(dds_domainid_t id, DomainConfig config);

  dds_domainid_t id() const noexcept { return id_; }
  // The configuration string actually used, and where it came from.
  const std::string& config() const noexcept { return config_.text; }
  const std::string& config_origin() const noexcept { return config_.origin; }

 private:
  dds_domainid_t id_;
  DomainConfig config_;
};

class Participant : public Entity {
 public:
  // Throws std::runtime_error naming dds_create_participant on failure. With `security`
  // enabled, the participant authenticates with those files (security.h); Cyclone refuses
  // it (DDS_RETCODE_NOT_ALLOWED_BY_SECURITY) if the credentials do not verify.
  explicit Participant(const Domain& domain, const SecurityFiles& security = {});

  dds_domainid_t domain_id() const noexcept { return domain_id_; }

 private:
  dds_domainid_t domain_id_;
};

}  // namespace gearpath::dds
