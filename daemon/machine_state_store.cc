#include "daemon/machine_state_store.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <fmt/format.h>

#include <cctype>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <system_error>

#include "core/io/json_read.h"
#include "core/pipeline/learned_state_json.h"

namespace gearpath::daemon {
namespace {

using nlohmann::json;

constexpr std::string_view kFormat = "gearpathd-machine-state";
constexpr int kVersion = 1;
// A learned state holds N x K samples only while learning; a few MB at most.
constexpr std::size_t kMaxStateFileBytes = std::size_t{256} << 20;

std::string Errno(std::string_view what, const std::string& path) {
  return fmt::format("{}: {} failed: {}", path, what, std::strerror(errno));
}

// The not-judged counts by cause name; causes with none are left out.
json NotJudgedToJson(const MachineCounters& c) {
  json j = json::object();
  for (std::size_t i = 1; i < c.not_judged.size(); ++i) {
    if (c.not_judged[i] > 0) {
      j[std::string(ToString(static_cast<NotJudgedCause>(i)))] = c.not_judged[i];
    }
  }
  return j;
}

json CountersToJson(const MachineCounters& c) {
  return json{{"received", c.received},
              {"processed", c.processed},
              {"rejected", c.rejected},
              {"lost", c.lost},
              {"rejected_by_reason", c.rejected_by_reason},
              {"not_judged", NotJudgedToJson(c)}};
}

std::uint64_t Count(const json& parent, const char* key) {
  const json& v = parent.at(key);
  if (!v.is_number_unsigned()) throw std::invalid_argument(std::string(key) + ": not a count");
  return v.get<std::uint64_t>();
}

MachineCounters CountersFromJson(const json& j) {
  MachineCounters c;
  c.received = Count(j, "received");
  c.processed = Count(j, "processed");
  c.rejected = Count(j, "rejected");
  c.lost = Count(j, "lost");
  for (const auto& [reason, n] : j.at("rejected_by_reason").items()) {
    if (!n.is_number_unsigned()) throw std::invalid_argument("rejected_by_reason: not a count");
    c.rejected_by_reason[reason] = n.get<std::uint64_t>();
  }
  // Absent from a state saved before the count existed; a cause this build does not know
  // (a later build's) is dropped.
  if (const auto it = j.find("not_judged"); it != j.end()) {
    if (!it->is_object()) throw std::invalid_argument("not_judged: not an object");
    for (std::size_t i = 1; i < c.not_judged.size(); ++i) {
      const auto cause = ToString(static_cast<NotJudgedCause>(i));
      if (it->contains(cause)) c.not_judged[i] = Count(*it, std::string(cause).c_str());
    }
  }
  return c;
}

// Writes `text` to `path` so that readers see the old file or the new one, never a mix.
Status WriteAtomically(const std::string& directory, const std::string& path,
                       std::string_view text) {
  const std::string tmp = fmt::format("{}.tmp.{}", path, ::getpid());
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0600);
  if (fd < 0) return Error{Errno("open", tmp)};
  std::size_t done = 0;
  while (done < text.size()) {
    const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
    if (n < 0) {
      if (errno == EINTR) continue;
      const std::string e = Errno("write", tmp);
      ::close(fd);
      ::unlink(tmp.c_str());
      return Error{e};
    }
    done += static_cast<std::size_t>(n);
  }
  if (::fsync(fd) != 0 || ::close(fd) != 0) {
    const std::string e = Errno("fsync/close", tmp);
    ::unlink(tmp.c_str());
    return Error{e};
  }
  if (::rename(tmp.c_str(), path.c_str()) != 0) {
    const std::string e = Errno("rename", tmp);
    ::unlink(tmp.c_str());
    return Error{e};
  }
  // The rename itself must reach the disk too.
  const int dir = ::open(directory.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dir >= 0) {
    (void)::fsync(dir);
    ::close(dir);
  }
  return Status::Ok();
}

}  // namespace

std::string ResolveStateDirectory(const DaemonConfig& config) {
  if (!config.state_directory.empty()) return config.state_directory;
  const char* env = std::getenv("STATE_DIRECTORY");  // systemd: colon-separated list
  if (env == nullptr) return {};
  const std::string_view list(env);
  return std::string(list.substr(0, list.find(':')));
}

Result<MachineStateStore> MachineStateStore::Open(std::string directory) {
  std::error_code ec;
  std::filesystem::create_directories(directory, ec);
  if (ec) return Error{fmt::format("state directory {}: cannot create it: {}", directory,
                                   ec.message())};
  if (!std::filesystem::is_directory(directory, ec)) {
    return Error{fmt::format("state directory {}: not a directory", directory)};
  }
  if (::access(directory.c_str(), W_OK | X_OK) != 0) {
    return Error{fmt::format("state directory {}: not writable: {}", directory,
                             std::strerror(errno))};
  }
  return MachineStateStore(std::move(directory));
}

std::string MachineStateStore::PathOf(std::string_view machine_id) const {
  std::string name;
  for (const char ch : machine_id) {
    const auto c = static_cast<unsigned char>(ch);
    if (std::isalnum(c) != 0 || c == '.' || c == '_' || c == '-') {
      name += ch;
    } else {
      name += fmt::format("%{:02X}", c);
    }
  }
  // A leading dot would hide the file, and "." / ".." are not names.
  if (!name.empty() && name.front() == '.') name = "%2E" + name.substr(1);
  return (std::filesystem::path(directory_) / (name + ".state.json")).string();
}

Result<SavedMachine> ReadSavedMachine(const std::string& path) {
  JsonReadLimits limits;
  limits.max_bytes = kMaxStateFileBytes;
  auto parsed = ReadJsonFile(path, limits);
  if (!parsed) return Error{parsed.error()};
  const json& j = parsed.value();
  try {
    if (!j.is_object() || j.value("format", "") != kFormat) {
      return Error{
          fmt::format("{}: not a gearpathd machine state (format \"{}\" expected)", path, kFormat)};
    }
    if (j.at("version") != kVersion) {
      return Error{fmt::format("{}: state version {} is not {} (written by another gearpathd "
                               "version)",
                               path, j.at("version").dump(), kVersion)};
    }
    SavedMachine m;
    m.machine_id = j.at("machine_id").get<std::string>();
    m.saved_at_ns = j.at("saved_at_ns").get<std::int64_t>();
    m.counters = CountersFromJson(j.at("counters"));
    auto learned = LearnedStateFromJson(j.at("learned"));
    if (!learned) return Error{fmt::format("{}: {}", path, learned.error())};
    m.learned = std::move(learned.value());
    return m;
  } catch (const std::exception& e) {
    return Error{fmt::format("{}: {}", path, e.what())};
  }
}

Result<std::optional<SavedMachine>> MachineStateStore::Load(std::string_view machine_id) const {
  const std::string path = PathOf(machine_id);
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) return std::optional<SavedMachine>{};
  auto m = ReadSavedMachine(path);
  if (!m) return Error{m.error()};
  if (m->machine_id != machine_id) {
    return Error{
        fmt::format("{}: holds machine \"{}\", not \"{}\"", path, m->machine_id, machine_id)};
  }
  return std::optional<SavedMachine>(std::move(m.value()));
}

Status MachineStateStore::Save(const SavedMachine& m) const {
  json j;
  j["format"] = kFormat;
  j["version"] = kVersion;
  j["machine_id"] = m.machine_id;
  j["saved_at_ns"] = m.saved_at_ns;
  j["counters"] = CountersToJson(m.counters);
  j["learned"] = ToJson(m.learned);
  const std::string path = PathOf(m.machine_id);
  auto text = DumpJson(j, -1, path);
  if (!text) return Error{text.error()};
  return WriteAtomically(directory_, path, *text);
}

}  // namespace gearpath::daemon
