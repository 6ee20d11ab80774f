// gearpathd: gearbox fault tracing daemon (AccelBlock in, DominantPath / SuspectedGear /
// EnvelopeIndicators / Status out, over DDS). See docs/configuration.md.
//
// Exit codes: 0 clean stop (or valid configuration with --check-config), 1 runtime failure
// (DDS set-up, signal set-up, processing loop), 2 invalid configuration or command line.
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <iostream>

#include "daemon/config_schema.h"
#include "daemon/daemon_config.h"
#include "daemon/dds_setup.h"
#include "daemon/gearpathd.h"
#include "daemon/machine_runtime.h"
#include "daemon/signal_events.h"

namespace {

constexpr int kExitOk = 0;
constexpr int kExitFailure = 1;
constexpr int kExitBadConfig = 2;

}  // namespace

int main(int argc, char** argv) {
  using namespace gearpath::daemon;
  CLI::App app{"gearpathd: traces gear faults to their transfer path, block by block, over DDS"};
  std::string config_path;
  std::string log_level;
  bool check_config = false;
  bool print_default = false;
  bool print_reference = false;
  app.add_option("-c,--config", config_path,
                 "Configuration file (JSON). Default: the embedded config/gearpathd.json")
      ->check(CLI::ExistingFile);
  app.add_flag("--check-config", check_config,
               "Validate the configuration, load every FRF set and build every machine, then "
               "exit: 0 valid, 2 invalid");
  app.add_option("--log-level", log_level, "Log level, overrides daemon.log_level")
      ->check(CLI::IsMember({"trace", "debug", "info", "warn", "error", "critical", "off"}));
  app.add_flag("--print-default-config", print_default,
               "Print the embedded default configuration and exit");
  app.add_flag("--print-config-reference", print_reference,
               "Print the configuration reference table (Markdown) and exit");
  app.set_version_flag("--version", std::string("gearpathd ") + GEARPATH_VERSION);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? kExitOk : kExitBadConfig;
  }
  if (print_default) {
    std::cout << DefaultConfigText();
    return kExitOk;
  }
  if (print_reference) {
    std::cout << RenderSchemaReference(DaemonConfigSchema());
    return kExitOk;
  }

  // Before any other thread exists (spdlog's and Cyclone's inherit the blocked mask).
  auto signals = SignalEvents::Open();
  if (!signals) {
    std::fprintf(stderr, "gearpathd: %s\n", signals.error().c_str());
    return kExitFailure;
  }
  spdlog::set_default_logger(spdlog::stderr_color_mt("gearpathd"));
  spdlog::set_pattern("%Y-%m-%dT%H:%M:%S.%e %^%l%$ %v");

  auto config = config_path.empty() ? ParseDaemonConfig(DefaultConfigText(), kEmbeddedOrigin)
                                    : LoadDaemonConfigFile(config_path);
  if (!config) {
    spdlog::critical("invalid configuration:\n{}", config.error());
    return kExitBadConfig;
  }
  ApplyLogLevel(log_level.empty() ? config->log_level : log_level);
  spdlog::info("gearpathd {} starting with {} ({} machine(s))", GEARPATH_VERSION,
               config->origin, config->machines.size());

  auto machines = BuildMachines(*config);
  if (!machines) {
    spdlog::critical("invalid configuration:\n{}", machines.error());
    return kExitBadConfig;
  }
  for (const auto& [id, m] : machines->machines) spdlog::info("machine {}: {}", id, m->summary);
  if (gearpath::Status dds_files = CheckDdsFiles(*config); !dds_files) {
    spdlog::critical("invalid configuration:\n{}", dds_files.error());
    return kExitBadConfig;
  }
  if (check_config) {
    std::printf("%s: configuration valid, %zu machine(s) built\n", config->origin.c_str(),
                machines->machines.size());
    return kExitOk;
  }

  auto daemon = Gearpathd::Create(std::move(config.value()), std::move(machines.value()),
                                  DaemonOptions{config_path, log_level, GEARPATH_VERSION});
  if (!daemon) {
    spdlog::critical("{}", daemon.error());
    return kExitFailure;
  }
  return (*daemon)->Run(*signals);
}
