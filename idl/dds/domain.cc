#include "idl/dds/domain.h"

#include <cstdlib>
#include <stdexcept>
#include <string>
#include <utility>

#include "idl/dds/error.h"

namespace gearpath::dds {

std::string ComposeDomainConfig(std::string_view config_xml, EnvironmentConfig environment) {
  std::string config(config_xml);
  if (environment == EnvironmentConfig::kApply) {
    // getenv is read once, at configuration time, on the thread that builds the domain.
    const char* uri = std::getenv("CYCLONEDDS_URI");  // NOLINT(concurrency-mt-unsafe)
    if (uri != nullptr && *uri != '\0') {
      config += ',';
      config += uri;
    }
  }
  return config;
}

namespace {

dds_entity_t CreateDomain(dds_domainid_t id, const std::string& config) {
  if (id == DDS_DOMAIN_DEFAULT) {
    throw std::invalid_argument(
        "gearpath::dds::Domain: the domain id must be explicit, not DDS_DOMAIN_DEFAULT");
  }
  return CheckDds(dds_create_domain(id, config.c_str()),
                  "dds_create_domain(" + std::to_string(id) + ")");
}

}  // namespace

Domain::Domain(dds_domainid_t id, std::string_view config_xml, EnvironmentConfig environment)
    : Domain(id, ComposeDomainConfig(config_xml, environment)) {}

Domain::Domain(dds_domainid_t id, std::string config)
    : Entity(CreateDomain(id, config), nullptr), id_(id), config_(std::move(config)) {}

Participant::Participant(const Domain& domain)
    : Entity(CheckDds(dds_create_participant(domain.id(), nullptr, nullptr),
                      "dds_create_participant(" + std::to_string(domain.id()) + ")"),
             domain.node()),
      domain_id_(domain.id()) {}

}  // namespace gearpath::dds
