// The bridge's state file: what `gearpath bridge` has published, so that a restarted bridge
// continues without losing or repeating a block. One JSON object (docs/tools.md, "bridge"):
// the machine id, the next sequence number, every directory-mode file taken (published,
// being published with the count of blocks done, or failed with its error) and the counters.
//
// Written atomically after every published block: a temporary file in the same directory,
// fsync, rename over the old one, fsync of the directory. A reader (or a crash at any point)
// sees either the old state or the new one, never a mix.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "core/common/result.h"

namespace gearpath::tools {

enum class FileStatus { kPublishing, kPublished, kFailed };

struct BridgeFileRecord {
  std::string name;  // file name inside the watched directory
  std::uintmax_t size = 0;
  std::int64_t mtime_ns = 0;  // size and mtime when taken: a failed file is retried if they change
  FileStatus status = FileStatus::kPublishing;
  std::int64_t t0_ns = 0;            // t0 of the file's first sample, fixed when first taken
  std::uint64_t first_sequence = 0;  // sequence number of its first block
  std::uint64_t blocks_total = 0;
  std::uint64_t blocks_published = 0;  // blocks [0, blocks_published) are out
  std::uint64_t dropped_samples = 0;   // tail shorter than a block, per channel
  std::string error;                   // kFailed: why
};

struct BridgeCounters {
  std::uint64_t blocks_published = 0;
  std::uint64_t files_published = 0;
  std::uint64_t files_failed = 0;
  std::uint64_t streams_ended = 0;    // stream mode: streams that ended cleanly
  std::uint64_t stream_errors = 0;    // malformed header, truncated frame, read errors
  std::uint64_t dropped_samples = 0;  // per channel: tails shorter than a block
};

struct BridgeState {
  std::string machine_id;
  std::uint64_t next_sequence = 0;
  std::vector<BridgeFileRecord> files;  // in the order taken
  BridgeCounters counters;
  std::string last_error;

  BridgeFileRecord* FindFile(const std::string& name);
};

// Reads the state file; a missing file is a fresh state (sequence 0). A file that exists but
// cannot be read or parsed is an error naming it: starting over would repeat sequence numbers.
Result<BridgeState> LoadBridgeState(const std::filesystem::path& path);

// Replaces the state file atomically (see above). Errors name the file and the failing call.
Status SaveBridgeState(const BridgeState& state, const std::filesystem::path& path);

}  // namespace gearpath::tools
