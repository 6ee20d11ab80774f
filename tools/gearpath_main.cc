// gearpath: command-line tools around the gearpath daemon (thin fronts over core/ and idl/).
#include <CLI/CLI.hpp>
#include <cstdio>
#include <string>

#include "tools/commands/commands.h"

int main(int argc, char** argv) {
  CLI::App app{"gearpath: gearbox fault tracing by transfer path analysis - tools"};
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("gearpath ") + GEARPATH_VERSION);
  int exit_code = gearpath::tools::kExitOk;
  // Subcommands register here, one line each.
  gearpath::tools::AddValidateCommand(app, exit_code);
  gearpath::tools::AddMonitorCommand(app, exit_code);
  gearpath::tools::AddRecordCommand(app, exit_code);
  gearpath::tools::AddReplayCommand(app, exit_code);
  gearpath::tools::AddDecoupleCommand(app, exit_code);
  gearpath::tools::AddInspectCommand(app, exit_code);
  gearpath::tools::AddReportCommand(app, exit_code);
  gearpath::tools::AddSimCommand(app, exit_code);
  gearpath::tools::AddEvaluateCommand(app, exit_code);
  gearpath::tools::AddBridgeCommand(app, exit_code);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help and --version are "errors" that exit 0; every real command-line error is bad
    // input, exit 2, whatever code CLI11 gives it internally.
    if (e.get_exit_code() == 0) return app.exit(e);
    // Named like every other error of the tools: "gearpath <subcommand>: ...".
    std::string who = "gearpath";
    for (const CLI::App* sub : app.get_subcommands()) who += " " + sub->get_name();
    std::fprintf(stderr, "%s: %s\nRun '%s --help' for more information.\n", who.c_str(), e.what(),
                 who.c_str());
    return gearpath::tools::kExitBadInput;
  }
  return exit_code;
}
