#include "tools/bridge/directory_bridge.h"

#include <cmath>
#include <set>

namespace gearpath::tools {

namespace fs = std::filesystem;

DirectoryBridge::DirectoryBridge(DirectoryBridgeOptions options, BridgeState* state,
                                 BlockSink* sink, BridgeLog log)
    : options_(std::move(options)),
      state_(state),
      sink_(sink),
      log_(std::move(log)),
      scanner_(options_.directory, options_.settle, options_.order, options_.clock) {
  if (!log_) log_ = [](const std::string&) {};
}

Status DirectoryBridge::Save() { return SaveBridgeState(*state_, options_.state_file); }

Result<std::size_t> DirectoryBridge::Poll(const std::atomic<bool>* stop) {
  Result<std::vector<ScannedFile>> files = scanner_.Scan();
  if (!files) return Error{files.error()};
  if (Status st = Forget(*files); !st) return Error{st.error()};
  std::error_code ec;
  const fs::path state_path = fs::weakly_canonical(options_.state_file, ec);
  std::size_t published = 0;
  for (const ScannedFile& file : *files) {
    if (stop && stop->load()) break;
    if (!state_path.empty() &&
        fs::weakly_canonical(options_.directory / file.name, ec) == state_path) {
      continue;  // the state file kept inside the watched directory
    }
    if (const BridgeFileRecord* done = state_->FindFile(file.name)) {
      if (done->status == FileStatus::kPublished) continue;  // once, even if rewritten
      // A failed file is retried only once it has changed: never in a loop.
      if (done->status == FileStatus::kFailed && done->size == file.size &&
          done->mtime_ns == file.mtime_ns) {
        continue;
      }
    }
    if (!file.settled) break;  // still being written: later files wait, order is kept
    Result<std::size_t> n = PublishFile(file, stop);
    if (!n) return n;
    published += *n;
  }
  return published;
}

Status DirectoryBridge::Forget(const std::vector<ScannedFile>& present) {
  std::set<std::string> names;
  for (const ScannedFile& f : present) names.insert(f.name);
  std::vector<std::string> forgotten;
  std::erase_if(state_->files, [&](const BridgeFileRecord& r) {
    if (names.count(r.name)) return false;
    if (r.status == FileStatus::kPublishing) {
      // Gone half published: the rest of it can never go out.
      const std::string error = (options_.directory / r.name).string() + ": removed after " +
                                std::to_string(r.blocks_published) + " of its " +
                                std::to_string(r.blocks_total) +
                                " blocks were published; the rest is not published";
      ++state_->counters.files_failed;
      state_->last_error = error;
      log_(error);
    }
    forgotten.push_back(r.name);
    return true;
  });
  if (forgotten.empty()) return Status::Ok();
  std::string list;
  for (std::size_t i = 0; i < forgotten.size() && i < 5; ++i) {
    list += (i ? ", " : "") + forgotten[i];
  }
  if (forgotten.size() > 5) list += ", ...";
  log_(std::to_string(forgotten.size()) + " file(s) no longer in " + options_.directory.string() +
       " dropped from the state file (" + list +
       "); a new file of such a name is new data and will be published");
  return Save();
}

Status DirectoryBridge::Fail(BridgeFileRecord& record, const std::string& error) {
  record.status = FileStatus::kFailed;
  record.error = error;
  ++state_->counters.files_failed;
  state_->last_error = error;
  std::string where = "skipped, recorded in the state file";
  if (!options_.failed_directory.empty()) {
    std::error_code ec;
    fs::create_directories(options_.failed_directory, ec);
    fs::rename(options_.directory / record.name, options_.failed_directory / record.name, ec);
    where = ec ? "could not be moved to " + options_.failed_directory.string() + ": " + ec.message()
               : "moved to " + options_.failed_directory.string();
  }
  log_(error + " (" + where + "; not retried unless the file changes)");
  return Save();
}

Result<std::size_t> DirectoryBridge::PublishFile(const ScannedFile& file,
                                                 const std::atomic<bool>* stop) {
  BridgeFileRecord* record = state_->FindFile(file.name);
  const bool resuming = record && record->status == FileStatus::kPublishing;
  if (!record) {
    state_->files.push_back({});
    record = &state_->files.back();
    record->name = file.name;
  }
  if (!resuming) {
    *record = BridgeFileRecord{};
    record->name = file.name;
    record->size = file.size;
    record->mtime_ns = file.mtime_ns;
    record->first_sequence = state_->next_sequence;
  }

  ReplayInputOptions in = options_.input;
  in.t0_ns = 1;  // blocks at 1 + offset; shifted to the file's t0 below
  Result<ReplayInput> loaded = LoadReplayInput(options_.directory / file.name, in);
  if (!loaded) {
    if (Status st = Fail(*record, loaded.error()); !st) return Error{st.error()};
    return std::size_t{0};
  }
  const Recording& r = loaded->recordings.at(0);
  if (!resuming) {
    // The export is written when the acquisition ends: its first sample is the file's mtime
    // minus its duration. Fixed here, so a resumed file keeps the same times.
    const double samples = static_cast<double>(r.block_count() * r.layout.samples_per_channel +
                                               loaded->dropped_samples);
    record->t0_ns = file.mtime_ns - std::llround(samples / r.layout.sample_rate_hz * 1e9);
    record->blocks_total = r.block_count();
    record->dropped_samples = loaded->dropped_samples;
  } else if (record->blocks_total != r.block_count()) {
    // Changed under us after part of it went out: publishing the rest could duplicate or skip.
    const std::string error = (options_.directory / file.name).string() + ": changed after " +
                              std::to_string(record->blocks_published) + " of its " +
                              std::to_string(record->blocks_total) +
                              " blocks were published (it now holds " +
                              std::to_string(r.block_count()) + "); the rest is not published";
    state_->next_sequence = record->first_sequence + record->blocks_published;
    if (Status st = Fail(*record, error); !st) return Error{st.error()};
    return std::size_t{0};
  }

  log_(file.name + ": publishing " +
       (resuming ? "from block " + std::to_string(record->blocks_published) + " of "
                 : std::string()) +
       std::to_string(record->blocks_total) + " blocks");
  std::size_t published = 0;
  for (std::uint64_t i = record->blocks_published; i < record->blocks_total; ++i) {
    if (stop && stop->load()) return published;
    AccelBlockView block = r.block(static_cast<std::size_t>(i));
    block.sequence = record->first_sequence + i;
    block.t0_ns = block.t0_ns - 1 + record->t0_ns;
    if (Status st = sink_->Publish(block); !st) {
      return Error{(options_.directory / file.name).string() + ": block " + std::to_string(i) +
                   " (sequence " + std::to_string(block.sequence) + "): " + st.error()};
    }
    ++published;
    record->blocks_published = i + 1;
    state_->next_sequence = block.sequence + 1;
    ++state_->counters.blocks_published;
    if (record->blocks_published == record->blocks_total) {
      record->status = FileStatus::kPublished;
      ++state_->counters.files_published;
      state_->counters.dropped_samples += record->dropped_samples;
    }
    if (Status st = Save(); !st) return Error{st.error()};
  }
  log_(file.name + ": " + std::to_string(record->blocks_total) + " blocks published (sequence " +
       std::to_string(record->first_sequence) + ".." +
       std::to_string(record->first_sequence + record->blocks_total - 1) + ")" +
       (record->dropped_samples ? ", last " + std::to_string(record->dropped_samples) +
                                      " samples per channel short of a block not sent"
                                : std::string()));
  return published;
}

}  // namespace gearpath::tools
