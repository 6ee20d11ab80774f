#include "tools/bridge/bridge_state.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>

namespace gearpath::tools {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

constexpr const char* kFormat = "gearpath-bridge-state";
constexpr int kVersion = 1;

const char* StatusName(FileStatus s) {
  switch (s) {
    case FileStatus::kPublishing:
      return "publishing";
    case FileStatus::kPublished:
      return "published";
    case FileStatus::kFailed:
      return "failed";
  }
  return "failed";
}

Result<FileStatus> ParseStatus(const std::string& s) {
  if (s == "publishing") return FileStatus::kPublishing;
  if (s == "published") return FileStatus::kPublished;
  if (s == "failed") return FileStatus::kFailed;
  return Error{"unknown file status \"" + s + "\""};
}

Status WriteAll(int fd, const std::string& text, const std::string& name) {
  std::size_t done = 0;
  while (done < text.size()) {
    const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) return Error{name + ": write: " + std::strerror(errno)};
    done += static_cast<std::size_t>(n);
  }
  return Status::Ok();
}

}  // namespace

BridgeFileRecord* BridgeState::FindFile(const std::string& name) {
  for (BridgeFileRecord& f : files) {
    if (f.name == name) return &f;
  }
  return nullptr;
}

Result<BridgeState> LoadBridgeState(const fs::path& path) {
  BridgeState state;
  std::error_code ec;
  if (!fs::exists(path, ec)) return state;
  const std::string name = path.string();
  std::ifstream in(path, std::ios::binary);
  if (!in) return Error{name + ": cannot open the bridge state file"};
  try {
    const json j = json::parse(in);
    if (!j.is_object() || j.value("format", "") != kFormat) {
      return Error{name + ": not a gearpath bridge state file (\"format\" is not \"" +
                   std::string(kFormat) + "\")"};
    }
    if (j.at("version").get<int>() != kVersion) {
      return Error{name + ": state file version " + j.at("version").dump() +
                   " is not supported (expected " + std::to_string(kVersion) + ")"};
    }
    state.machine_id = j.at("machine").get<std::string>();
    state.next_sequence = j.at("next_sequence").get<std::uint64_t>();
    state.last_error = j.value("last_error", "");
    const json& c = j.at("counters");
    state.counters.blocks_published = c.at("blocks_published").get<std::uint64_t>();
    state.counters.files_published = c.at("files_published").get<std::uint64_t>();
    state.counters.files_failed = c.at("files_failed").get<std::uint64_t>();
    state.counters.streams_ended = c.at("streams_ended").get<std::uint64_t>();
    state.counters.stream_errors = c.at("stream_errors").get<std::uint64_t>();
    state.counters.dropped_samples = c.at("dropped_samples").get<std::uint64_t>();
    for (const json& f : j.at("files")) {
      BridgeFileRecord r;
      r.name = f.at("name").get<std::string>();
      r.size = f.at("size").get<std::uintmax_t>();
      r.mtime_ns = f.at("mtime_ns").get<std::int64_t>();
      Result<FileStatus> st = ParseStatus(f.at("status").get<std::string>());
      if (!st) return Error{name + ": file \"" + r.name + "\": " + st.error()};
      r.status = *st;
      r.t0_ns = f.at("t0_ns").get<std::int64_t>();
      r.first_sequence = f.at("first_sequence").get<std::uint64_t>();
      r.blocks_total = f.at("blocks_total").get<std::uint64_t>();
      r.blocks_published = f.at("blocks_published").get<std::uint64_t>();
      r.dropped_samples = f.value("dropped_samples", std::uint64_t{0});
      r.error = f.value("error", "");
      state.files.push_back(std::move(r));
    }
  } catch (const json::exception& e) {
    return Error{name + ": bridge state file unreadable: " + e.what()};
  }
  return state;
}

Status SaveBridgeState(const BridgeState& state, const fs::path& path) {
  json files = json::array();
  for (const BridgeFileRecord& f : state.files) {
    json r = {{"name", f.name},
              {"size", f.size},
              {"mtime_ns", f.mtime_ns},
              {"status", StatusName(f.status)},
              {"t0_ns", f.t0_ns},
              {"first_sequence", f.first_sequence},
              {"blocks_total", f.blocks_total},
              {"blocks_published", f.blocks_published},
              {"dropped_samples", f.dropped_samples}};
    if (!f.error.empty()) r["error"] = f.error;
    files.push_back(std::move(r));
  }
  const BridgeCounters& c = state.counters;
  const json j = {{"format", kFormat},
                  {"version", kVersion},
                  {"machine", state.machine_id},
                  {"next_sequence", state.next_sequence},
                  {"counters",
                   {{"blocks_published", c.blocks_published},
                    {"files_published", c.files_published},
                    {"files_failed", c.files_failed},
                    {"streams_ended", c.streams_ended},
                    {"stream_errors", c.stream_errors},
                    {"dropped_samples", c.dropped_samples}}},
                  {"last_error", state.last_error},
                  {"files", files}};
  // Invalid UTF-8 in a file name must not make the state unwritable: replace it.
  const std::string text = j.dump(1, ' ', false, json::error_handler_t::replace) + "\n";

  const fs::path dir = path.parent_path().empty() ? fs::path(".") : path.parent_path();
  std::string tmp_name = path.filename().string();  // appended, not "." + name: GCC 12's
  tmp_name.insert(0, 1, '.');                       // -Wrestrict false positive
  tmp_name += ".tmp";
  const std::string tmp = (dir / tmp_name).string();
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) return Error{tmp + ": cannot create: " + std::strerror(errno)};
  Status written = WriteAll(fd, text, tmp);
  if (written && ::fsync(fd) != 0) written = Error{tmp + ": fsync: " + std::strerror(errno)};
  ::close(fd);
  if (!written) {
    ::unlink(tmp.c_str());
    return written;
  }
  if (::rename(tmp.c_str(), path.c_str()) != 0) {
    const std::string why = std::strerror(errno);
    ::unlink(tmp.c_str());
    return Error{path.string() + ": rename from " + tmp + ": " + why};
  }
  // The rename itself is durable only once the directory is synced.
  const int dfd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dfd >= 0) {
    ::fsync(dfd);
    ::close(dfd);
  }
  return Status::Ok();
}

}  // namespace gearpath::tools
