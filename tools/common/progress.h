// Progress: a one-line progress bar with rate and ETA on a terminal, plain lines otherwise.
//
// On a terminal (isatty of the stream) the bar is redrawn in place at most ten times a second;
// on a pipe or file (CI logs, tests) one plain line is printed every `plain_interval` so logs
// stay readable and grep-able. Rate is items per second of wall time since Start; ETA assumes
// that rate holds. A total of 0 means unknown (no percentage, no ETA: e.g. replay --loop).
#pragma once

#include <chrono>
#include <cstdio>
#include <string>

namespace gearpath::tools {

class Progress {
 public:
  Progress(std::FILE* out, std::string what, std::size_t total,
           std::chrono::milliseconds plain_interval = std::chrono::milliseconds(5000));

  void Update(std::size_t done);
  // Draws the final state and ends the line.
  void Finish(std::size_t done);

  bool terminal() const { return terminal_; }
  // "12.3 s", "1:02:03"...
  static std::string FormatDuration(double seconds);

 private:
  std::string Line(std::size_t done, double elapsed_s) const;

  std::FILE* out_;
  std::string what_;
  std::size_t total_;
  bool terminal_;
  std::chrono::milliseconds interval_;
  std::chrono::steady_clock::time_point start_, last_draw_;
};

}  // namespace gearpath::tools
