#include "tools/bridge/directory_scanner.h"

#include <sys/stat.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <set>

namespace gearpath::tools {

namespace fs = std::filesystem;

bool IsIgnoredExportName(const std::string& name) {
  auto ends_with = [&](const char* suffix) {
    const std::size_t n = std::strlen(suffix);
    return name.size() >= n && name.compare(name.size() - n, n, suffix) == 0;
  };
  return name.empty() || name[0] == '.' || ends_with(".part") || ends_with(".tmp") ||
         ends_with("~");
}

DirectoryScanner::DirectoryScanner(fs::path directory, std::chrono::nanoseconds settle,
                                   FileOrder order, Clock clock)
    : directory_(std::move(directory)), settle_(settle), order_(order), clock_(std::move(clock)) {
  if (!clock_) {
    clock_ = [] { return std::chrono::steady_clock::now().time_since_epoch(); };
  }
}

Result<std::vector<ScannedFile>> DirectoryScanner::Scan() {
  const std::chrono::nanoseconds now = clock_();
  std::vector<ScannedFile> files;
  std::error_code ec;
  fs::directory_iterator it(directory_, ec);
  if (ec) return Error{directory_.string() + ": cannot list the directory: " + ec.message()};
  std::set<std::string> present;
  for (; it != fs::directory_iterator(); it.increment(ec)) {
    if (ec) return Error{directory_.string() + ": listing failed: " + ec.message()};
    const std::string name = it->path().filename().string();
    if (IsIgnoredExportName(name)) continue;
    // stat, not the cached entry: size and mtime must be current, with nanoseconds.
    struct stat st {};
    if (::stat(it->path().c_str(), &st) != 0 || !S_ISREG(st.st_mode))
      continue;  // gone / not a file
    ScannedFile f;
    f.name = name;
    f.size = static_cast<std::uintmax_t>(st.st_size);
    f.mtime_ns = static_cast<std::int64_t>(st.st_mtim.tv_sec) * 1000000000 + st.st_mtim.tv_nsec;
    present.insert(name);
    auto [seen, inserted] = seen_.try_emplace(name, Seen{f.size, f.mtime_ns, now});
    if (!inserted && (seen->second.size != f.size || seen->second.mtime_ns != f.mtime_ns)) {
      seen->second = Seen{f.size, f.mtime_ns, now};  // still being written: start over
    }
    f.settled = now - seen->second.since >= settle_;
    files.push_back(std::move(f));
  }
  std::erase_if(seen_, [&](const auto& kv) { return !present.count(kv.first); });
  std::sort(files.begin(), files.end(), [&](const ScannedFile& a, const ScannedFile& b) {
    if (order_ == FileOrder::kMtime && a.mtime_ns != b.mtime_ns) return a.mtime_ns < b.mtime_ns;
    return a.name < b.name;
  });
  return files;
}

}  // namespace gearpath::tools
