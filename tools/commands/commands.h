// The subcommands of `gearpath`. Each Add*Command registers itself on `app`; when it runs, its
// callback stores the process exit code in `exit_code` (0 ok, 1 runtime failure, 2 bad input).
#pragma once

namespace CLI {
class App;
}

namespace gearpath::tools {

inline constexpr int kExitOk = 0;
inline constexpr int kExitFailure = 1;
inline constexpr int kExitBadInput = 2;

void AddValidateCommand(CLI::App& app, int& exit_code);
void AddMonitorCommand(CLI::App& app, int& exit_code);
void AddRecordCommand(CLI::App& app, int& exit_code);
void AddReplayCommand(CLI::App& app, int& exit_code);
void AddDecoupleCommand(CLI::App& app, int& exit_code);
void AddInspectCommand(CLI::App& app, int& exit_code);
void AddReportCommand(CLI::App& app, int& exit_code);
void AddSimCommand(CLI::App& app, int& exit_code);
void AddEvaluateCommand(CLI::App& app, int& exit_code);
void AddBridgeCommand(CLI::App& app, int& exit_code);

}  // namespace gearpath::tools
