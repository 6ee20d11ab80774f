// gearpath: command-line tools around the gearpath daemon (thin fronts over core/ and idl/).
#include <CLI/CLI.hpp>

#include "tools/commands/commands.h"

int main(int argc, char** argv) {
  CLI::App app{"gearpath: gearbox fault tracing by transfer path analysis - tools"};
  app.require_subcommand(1);
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
    return app.exit(e) == 0 ? gearpath::tools::kExitOk : gearpath::tools::kExitBadInput;
  }
  return exit_code;
}
