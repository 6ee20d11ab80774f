// Test helper: runs the built `gearpath` binary as a child process with a deadline, its stdout
// and stderr captured in files, and CYCLONEDDS_URI set to the built-in loopback configuration
// plus a per-test-process Cyclone discovery tag (CYCLONEDDS_URI replaces the built-in
// configuration, so it carries all of it) so concurrently running tests never see each other's
// blocks. The tag changes nothing but discovery matching: everything stays on 127.0.0.1 with
// multicast off.
#pragma once

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "idl/dds/domain.h"

namespace gearpath::tools::testing {

inline std::string DiscoveryTagFragment() {
  return "<CycloneDDS><Domain Id=\"any\"><Discovery><Tag>gearpath-tools-test-" +
         std::to_string(getpid()) + "</Tag></Discovery></Domain></CycloneDDS>";
}

// The domain id for this test process: unlikely to clash, and the tag isolates it anyway.
inline int TestDomainId() { return 201 + static_cast<int>(getpid() % 30); }

// The configuration a test's own participant uses: exactly what the children end up with.
inline std::string TestDomainConfig() {
  return std::string(dds::kLoopbackConfigXml) + "," + DiscoveryTagFragment();
}

inline std::string ReadText(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

class ToolProcess {
 public:
  ToolProcess(const std::vector<std::string>& args, const std::filesystem::path& log_dir,
              const std::string& name)
      : out_(log_dir / (name + ".out")), err_(log_dir / (name + ".err")) {
    std::vector<std::string> argv_storage{GEARPATH_TOOL_PATH};
    argv_storage.insert(argv_storage.end(), args.begin(), args.end());
    const std::string uri = TestDomainConfig();
    pid_ = fork();
    if (pid_ == 0) {
      const int o = open(out_.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      const int e = open(err_.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      dup2(o, STDOUT_FILENO);
      dup2(e, STDERR_FILENO);
      setenv("CYCLONEDDS_URI", uri.c_str(), 1);
      sigset_t none;
      sigemptyset(&none);
      sigprocmask(SIG_SETMASK, &none, nullptr);
      std::vector<char*> argv;
      for (auto& a : argv_storage) argv.push_back(a.data());
      argv.push_back(nullptr);
      execv(argv[0], argv.data());
      _exit(127);
    }
  }
  ~ToolProcess() {
    if (pid_ > 0 && !code_) {
      kill(pid_, SIGKILL);
      int status = 0;
      waitpid(pid_, &status, 0);
    }
  }
  ToolProcess(const ToolProcess&) = delete;
  ToolProcess& operator=(const ToolProcess&) = delete;

  void Signal(int signo) const { kill(pid_, signo); }

  // Exit code (or -signal), or nullopt if still running at the deadline.
  std::optional<int> Wait(std::chrono::milliseconds timeout) {
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    while (!code_) {
      int status = 0;
      if (waitpid(pid_, &status, WNOHANG) == pid_) {
        code_ = WIFEXITED(status) ? WEXITSTATUS(status) : -WTERMSIG(status);
        break;
      }
      if (std::chrono::steady_clock::now() >= deadline) return std::nullopt;
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    return code_;
  }

  // Polls stderr until it contains `text`.
  bool WaitForStderr(const std::string& text, std::chrono::milliseconds timeout) {
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    while (std::chrono::steady_clock::now() < deadline) {
      if (Err().find(text) != std::string::npos) return true;
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    return false;
  }

  std::string Out() const { return ReadText(out_); }
  std::string Err() const { return ReadText(err_); }

 private:
  std::filesystem::path out_, err_;
  pid_t pid_ = -1;
  std::optional<int> code_;
};

// Runs to completion (20 s deadline); returns the exit code, -1000 on timeout.
inline int RunTool(const std::vector<std::string>& args, const std::filesystem::path& log_dir,
                   const std::string& name, std::string* out = nullptr,
                   std::string* err = nullptr) {
  ToolProcess p(args, log_dir, name);
  const std::optional<int> code = p.Wait(std::chrono::seconds(20));
  if (out) *out = p.Out();
  if (err) *err = p.Err();
  return code.value_or(-1000);
}

}  // namespace gearpath::tools::testing
