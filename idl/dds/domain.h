// Domain and Participant: a Cyclone DDS domain created from an explicit XML configuration, and
// the participants on it.
//
// Cyclone reads CYCLONEDDS_URI only when a domain is created implicitly (by the first
// dds_create_participant on an id that has no domain yet). dds_create_domain(id, config) uses
// exactly the string it is given and ignores the environment (Cyclone 0.10
// src/core/ddsc/src/dds_domain.c). So Domain builds that string itself: the project's loopback
// configuration (kLoopbackConfigXml, generated from config/cyclonedds-loopback.xml) first and,
// if CYCLONEDDS_URI is set and EnvironmentConfig::kApply is chosen, the variable's value after
// it. Cyclone's configuration string is a comma-separated list of file URIs and XML fragments
// applied in order, so an element set in CYCLONEDDS_URI overrides the same element of the
// loopback configuration (list elements such as Peers accumulate). Tests use kIgnore so they
// stay on loopback whatever the environment says.
//
// One Domain per domain id per process (Cyclone refuses a second dds_create_domain on the same
// id); every Participant keeps its Domain alive.
#pragma once

#include <dds/dds.h>

#include <string>
#include <string_view>

#include "idl/dds/entity.h"
#include "idl/dds/loopback_config_xml.h"

namespace gearpath::dds {

enum class EnvironmentConfig {
  kApply,   // append CYCLONEDDS_URI (if set) after the given configuration
  kIgnore,  // use the given configuration only
};

// The configuration string Domain passes to dds_create_domain.
std::string ComposeDomainConfig(std::string_view config_xml, EnvironmentConfig environment);

class Domain : public Entity {
 public:
  // Throws std::runtime_error naming dds_create_domain and the id if Cyclone rejects the
  // configuration or the id already has a domain in this process. `id` must not be
  // DDS_DOMAIN_DEFAULT.
  explicit Domain(dds_domainid_t id, std::string_view config_xml = kLoopbackConfigXml,
                  EnvironmentConfig environment = EnvironmentConfig::kApply);

  dds_domainid_t id() const noexcept { return id_; }
  // The configuration string actually used.
  const std::string& config() const noexcept { return config_; }

 private:
  Domain(dds_domainid_t id, std::string config);

  dds_domainid_t id_;
  std::string config_;
};

class Participant : public Entity {
 public:
  // Throws std::runtime_error naming dds_create_participant on failure.
  explicit Participant(const Domain& domain);

  dds_domainid_t domain_id() const noexcept { return domain_id_; }

 private:
  dds_domainid_t domain_id_;
};

}  // namespace gearpath::dds
