#include "tools/common/progress.h"

#include <unistd.h>

#include <cmath>

namespace gearpath::tools {

Progress::Progress(std::FILE* out, std::string what, std::size_t total,
                   std::chrono::milliseconds plain_interval)
    : out_(out),
      what_(std::move(what)),
      total_(total),
      terminal_(isatty(fileno(out)) != 0),
      interval_(terminal_ ? std::chrono::milliseconds(100) : plain_interval),
      start_(std::chrono::steady_clock::now()),
      last_draw_(start_) {}

std::string Progress::FormatDuration(double seconds) {
  if (!std::isfinite(seconds) || seconds < 0) return "?";
  char buf[32];
  if (seconds < 60) {
    std::snprintf(buf, sizeof buf, "%.1f s", seconds);
  } else {
    const long s = std::lround(seconds);
    std::snprintf(buf, sizeof buf, "%ld:%02ld:%02ld", s / 3600, (s / 60) % 60, s % 60);
  }
  return buf;
}

std::string Progress::Line(std::size_t done, double elapsed_s) const {
  const double rate = elapsed_s > 0 ? static_cast<double>(done) / elapsed_s : 0.0;
  char buf[256];
  if (total_ == 0) {
    std::snprintf(buf, sizeof buf, "%s: %zu, %.1f/s, %s elapsed", what_.c_str(), done, rate,
                  FormatDuration(elapsed_s).c_str());
    return buf;
  }
  const double fraction = std::min(1.0, static_cast<double>(done) / static_cast<double>(total_));
  const double eta =
      rate > 0 ? static_cast<double>(total_ - std::min(done, total_)) / rate : std::nan("");
  if (terminal_) {
    constexpr int kWidth = 30;
    const int filled = static_cast<int>(fraction * kWidth);
    std::string bar(static_cast<std::size_t>(filled), '#');
    bar.append(static_cast<std::size_t>(kWidth - filled), '.');
    std::snprintf(buf, sizeof buf, "%s [%s] %3.0f%% %zu/%zu, %.1f/s, ETA %s", what_.c_str(),
                  bar.c_str(), 100 * fraction, done, total_, rate, FormatDuration(eta).c_str());
  } else {
    std::snprintf(buf, sizeof buf, "%s: %zu/%zu (%.0f%%), %.1f/s, ETA %s", what_.c_str(), done,
                  total_, 100 * fraction, rate, FormatDuration(eta).c_str());
  }
  return buf;
}

void Progress::Update(std::size_t done) {
  const auto now = std::chrono::steady_clock::now();
  if (now - last_draw_ < interval_) return;
  last_draw_ = now;
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  if (terminal_) {
    std::fprintf(out_, "\r\x1b[2K%s", Line(done, elapsed).c_str());
  } else {
    std::fprintf(out_, "%s\n", Line(done, elapsed).c_str());
  }
  std::fflush(out_);
}

void Progress::Finish(std::size_t done) {
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  std::fprintf(out_, terminal_ ? "\r\x1b[2K%s\n" : "%s\n", Line(done, elapsed).c_str());
  std::fflush(out_);
}

}  // namespace gearpath::tools
