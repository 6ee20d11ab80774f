// DirectoryBridge: publishes the blocks of every complete file that acquisition software exports
// into a directory (text/CSV exports and UFF 58 time histories, read by replay's readers), each
// file once, in order, resuming after a restart where the state file says it stopped.
//
// Per pass: scan (DirectoryScanner decides which files are complete), then for each file in
// order that the state does not list as done: read it, publish its blocks with sequence numbers
// continuing the state's, and record every block in the state file as it goes. The first file
// that is not complete yet stops the pass, so files go out strictly in order. A file that does
// not parse is recorded as failed with its error (and moved aside if asked): it is not retried
// unless it changes (size or mtime), so a bad file never loops. A file's record lives as long as
// the file is in the directory: once it is gone its record is dropped, so the state file does
// not grow without bound on a directory that the acquisition side cleans up.
#pragma once

#include <atomic>
#include <chrono>
#include <filesystem>
#include <functional>
#include <string>

#include "core/common/result.h"
#include "tools/bridge/bridge_state.h"
#include "tools/bridge/directory_scanner.h"
#include "tools/common/block_sink.h"
#include "tools/common/replay_input.h"

namespace gearpath::tools {

struct DirectoryBridgeOptions {
  std::filesystem::path directory;
  std::filesystem::path state_file;
  std::filesystem::path failed_directory;  // empty: failed files stay where they are
  ReplayInputOptions input;  // machine (required), format, block length, channels, rate, speed
  std::chrono::nanoseconds settle = std::chrono::seconds(2);
  FileOrder order = FileOrder::kName;
  DirectoryScanner::Clock clock;  // empty: steady_clock
};

// Receives one line per event (file published, file failed), without the command prefix.
using BridgeLog = std::function<void(const std::string&)>;

class DirectoryBridge {
 public:
  // `state` must have been loaded from options.state_file (LoadBridgeState) and outlive this.
  DirectoryBridge(DirectoryBridgeOptions options, BridgeState* state, BlockSink* sink,
                  BridgeLog log = {});

  // One pass. Returns the blocks published in it; an error (a block the sink did not take, a
  // state file that cannot be written, an unreadable directory) stops the pass, and the state
  // file then says exactly which blocks went out. `stop` is checked between blocks.
  Result<std::size_t> Poll(const std::atomic<bool>* stop = nullptr);

 private:
  // Reads, then publishes the rest of one file. Returns blocks published, or a sink/state error.
  Result<std::size_t> PublishFile(const ScannedFile& file, const std::atomic<bool>* stop);
  // Drops the records of files no longer in the directory (deleted, moved away, or moved to
  // the failed directory), so that the state file stays as long as the directory's listing; a
  // file removed half published is counted as failed. Saves the state if anything was dropped.
  Status Forget(const std::vector<ScannedFile>& present);
  Status Fail(BridgeFileRecord& record, const std::string& error);
  Status Save();

  DirectoryBridgeOptions options_;
  BridgeState* state_;
  BlockSink* sink_;
  BridgeLog log_;
  DirectoryScanner scanner_;
};

}  // namespace gearpath::tools
