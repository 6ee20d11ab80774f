// DirectoryScanner: which files in the export directory are complete and in what order.
//
// Acquisition software writes its export in place, so a file is taken only once it has stood
// still: its size and modification time unchanged for the settle period, measured on the
// scanner's own clock (injected, so tests drive it without sleeping). A producer that can
// rename may instead write `NAME.part` (or `NAME.tmp`, or a hidden `.NAME`) and rename it when
// done: those names are never taken. Sub-directories are ignored.
#pragma once

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "core/common/result.h"

namespace gearpath::tools {

enum class FileOrder { kName, kMtime };

struct ScannedFile {
  std::string name;
  std::uintmax_t size = 0;
  std::int64_t mtime_ns = 0;
  bool settled = false;  // unchanged for the settle period: safe to read
};

// Names the bridge never takes: hidden files, `.part` / `.tmp` / `~` ends.
bool IsIgnoredExportName(const std::string& name);

class DirectoryScanner {
 public:
  using Clock = std::function<std::chrono::nanoseconds()>;  // monotonic
  DirectoryScanner(std::filesystem::path directory, std::chrono::nanoseconds settle,
                   FileOrder order, Clock clock = {});

  // The directory's regular files in order (by name, or by mtime then name), each marked
  // settled or not. An unreadable directory is an error naming it.
  Result<std::vector<ScannedFile>> Scan();

 private:
  struct Seen {
    std::uintmax_t size = 0;
    std::int64_t mtime_ns = 0;
    std::chrono::nanoseconds since{0};  // first scan that saw this size and mtime
  };
  std::filesystem::path directory_;
  std::chrono::nanoseconds settle_;
  FileOrder order_;
  Clock clock_;
  std::map<std::string, Seen> seen_;
};

}  // namespace gearpath::tools
