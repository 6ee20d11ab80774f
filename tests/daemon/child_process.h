// ChildProcess: runs a program (gearpathd) as a child for tests, with its stdout and stderr in a
// file, and waits for it with a deadline so that a hung daemon fails the test instead of
// stalling it. CYCLONEDDS_URI is removed from the child's environment: gearpathd then uses only
// its built-in loopback configuration.
#pragma once

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace gearpath::testing {

class ChildProcess {
 public:
  // Starts `program` with `args`; output goes to `log_path` (truncated).
  ChildProcess(const std::string& program, const std::vector<std::string>& args,
               std::string log_path)
      : log_path_(std::move(log_path)) {
    std::vector<std::string> argv_storage{program};
    argv_storage.insert(argv_storage.end(), args.begin(), args.end());
    pid_ = fork();
    if (pid_ == 0) {
      const int fd = open(log_path_.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      if (fd >= 0) {
        dup2(fd, STDOUT_FILENO);
        dup2(fd, STDERR_FILENO);
        close(fd);
      }
      unsetenv("CYCLONEDDS_URI");
      // The test runner may block signals; the daemon must start with a clean mask.
      sigset_t none;
      sigemptyset(&none);
      sigprocmask(SIG_SETMASK, &none, nullptr);
      std::vector<char*> argv;
      for (auto& a : argv_storage) argv.push_back(a.data());
      argv.push_back(nullptr);
      execv(program.c_str(), argv.data());
      _exit(127);
    }
  }
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;

  // Never leaves a daemon behind: SIGKILL if still running.
  ~ChildProcess() {
    if (running()) {
      kill(pid_, SIGKILL);
      int status = 0;
      waitpid(pid_, &status, 0);
    }
  }

  bool started() const { return pid_ > 0; }
  pid_t pid() const { return pid_; }
  bool running() const { return pid_ > 0 && !exit_code_.has_value() && !signalled_; }
  void Signal(int signo) const {
    if (pid_ > 0) kill(pid_, signo);
  }

  // Waits up to `timeout` for the child to exit; its exit code (or -signal number if killed
  // by a signal), or nullopt if it is still running.
  std::optional<int> WaitExit(std::chrono::milliseconds timeout) {
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    while (running()) {
      int status = 0;
      const pid_t r = waitpid(pid_, &status, WNOHANG);
      if (r == pid_) {
        if (WIFEXITED(status)) {
          exit_code_ = WEXITSTATUS(status);
        } else if (WIFSIGNALED(status)) {
          signalled_ = true;
          exit_code_ = -WTERMSIG(status);
        }
        break;
      }
      if (std::chrono::steady_clock::now() >= deadline) return std::nullopt;
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    return exit_code_;
  }

  std::string Log() const {
    std::ifstream in(log_path_);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
  }

  // Polls the log until it contains `text` or `timeout` passes.
  bool WaitForLog(const std::string& text, std::chrono::milliseconds timeout) {
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    while (std::chrono::steady_clock::now() < deadline) {
      if (Log().find(text) != std::string::npos) return true;
      if (!running() || WaitExit(std::chrono::milliseconds(0)).has_value()) {
        return Log().find(text) != std::string::npos;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    return false;
  }

 private:
  std::string log_path_;
  pid_t pid_ = -1;
  std::optional<int> exit_code_;
  bool signalled_ = false;
};

// Runs `program args` to completion (deadline `timeout`); exit code, or nullopt on timeout.
inline std::optional<int> RunToCompletion(const std::string& program,
                                          const std::vector<std::string>& args,
                                          const std::string& log_path, std::string* output,
                                          std::chrono::milliseconds timeout) {
  ChildProcess child(program, args, log_path);
  auto code = child.WaitExit(timeout);
  if (output != nullptr) *output = child.Log();
  return code;
}

}  // namespace gearpath::testing
