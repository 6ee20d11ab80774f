#include "idl/dds/domain.h"

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>

#include "idl/dds/error.h"

namespace gearpath::dds {
namespace {

dds_entity_t CreateDomain(dds_domainid_t id, const std::string& config) {
  if (id == DDS_DOMAIN_DEFAULT) {
    throw std::invalid_argument(
        "gearpath::dds::Domain: the domain id must be explicit, not DDS_DOMAIN_DEFAULT");
  }
  return CheckDds(dds_create_domain(id, config.c_str()),
                  "dds_create_domain(" + std::to_string(id) + ")");
}

// Collects Cyclone's log or trace lines (SelectedInterfaces).
void Collect(void* text, const dds_log_data_t* data) {
  auto& out = *static_cast<std::string*>(text);
  out.append(data->message, data->size);
  if (out.empty() || out.back() != '\n') out += '\n';
}

}  // namespace

DomainConfig ResolveDomainConfig(DomainConfig base, EnvironmentConfig environment) {
  if (environment == EnvironmentConfig::kApply) {
    // getenv is read once, at configuration time, on the thread that builds the domain.
    const char* uri = std::getenv("CYCLONEDDS_URI");  // NOLINT(concurrency-mt-unsafe)
    if (uri != nullptr && *uri != '\0') return {uri, "CYCLONEDDS_URI"};
  }
  return base;
}

DomainConfig ResolveDomainConfig(std::string_view config_file, EnvironmentConfig environment) {
  if (config_file.empty()) {
    return ResolveDomainConfig(
        DomainConfig{std::string(kLoopbackConfigXml),
                     "embedded loopback configuration (config/cyclonedds-loopback.xml)"},
        environment);
  }
  const std::string path(config_file);
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  if (!in || in.bad()) throw std::runtime_error(path + ": cannot read the DDS configuration file");
  std::string xml = text.str();
  // Cyclone takes an XML string only if it starts with '<'.
  xml.erase(0, xml.find_first_not_of(" \t\r\n"));
  if (xml.empty() || xml.front() != '<') {
    throw std::runtime_error(path + ": not a Cyclone DDS XML configuration (must start with '<')");
  }
  return {std::move(xml), "file " + path};
}

std::string SelectedInterfaces(dds_domainid_t id, const std::string& config) {
  // Config tracing on, to the capture sink; the output file only matters if a sink is reset.
  const std::string probe = config +
                            ",<CycloneDDS><Domain Id=\"any\"><Tracing><Verbosity>config</Verbosity>"
                            "<OutputFile>/dev/null</OutputFile></Tracing></Domain></CycloneDDS>";
  std::string trace;
  std::string log;
  dds_set_trace_sink(Collect, &trace);
  dds_set_log_sink(Collect, &log);
  const dds_entity_t domain = dds_create_domain(id, probe.c_str());
  if (domain > 0) (void)dds_delete(domain);
  dds_set_log_sink(nullptr, nullptr);
  dds_set_trace_sink(nullptr, nullptr);
  while (!log.empty() && (log.back() == '\n' || log.back() == ' ')) log.pop_back();
  if (domain < 0) {
    throw std::runtime_error(
        DdsErrorMessage("dds_create_domain(" + std::to_string(id) + ")", domain) +
        (log.empty() ? "" : "; Cyclone says: " + log));
  }
  constexpr std::string_view kKey = "selected interfaces: ";
  const auto at = trace.find(kKey);
  if (at == std::string::npos) return "(not reported by Cyclone)";
  const auto begin = at + kKey.size();
  std::string selected = trace.substr(begin, trace.find('\n', begin) - begin);
  while (!selected.empty() && selected.back() == ' ') selected.pop_back();
  return selected;
}

Domain::Domain(dds_domainid_t id, std::string_view config_xml, EnvironmentConfig environment)
    : Domain(id, ResolveDomainConfig(
                     DomainConfig{std::string(config_xml), config_xml == kLoopbackConfigXml
                                                               ? "embedded loopback configuration"
                                                               : "configuration given in code"},
                     environment)) {}

Domain::Domain(dds_domainid_t id, DomainConfig config)
    : Entity(CreateDomain(id, config.text), nullptr), id_(id), config_(std::move(config)) {}

Participant::Participant(const Domain& domain, const SecurityFiles& security)
    : Entity(CheckDds(dds_create_participant(domain.id(), SecurityQos(security).get(), nullptr),
                      "dds_create_participant(" + std::to_string(domain.id()) + ")"),
             domain.node()),
      domain_id_(domain.id()) {}

}  // namespace gearpath::dds
