// Replay inputs: whatever `gearpath replay` (and `inspect`) can read, turned into recordings in
// memory, i.e. blocks with their layout, ready to publish.
//
// Three sources: the project's recording format (core/io/recording.h; one recording directory,
// or a directory of them as `gearpath record` writes for several machines), DH8303-style text
// exports (core/io/text_export.h) and UFF dataset 58 time histories (function type 1,
// core/io/uff58_import.h). Recordings keep their blocks exactly (bit for bit); continuous sources
// are cut into blocks of --block-length samples per channel (a trailing partial block is dropped
// and reported), numbered from 0, with t0 = the replay's start time plus the sample offset.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "core/common/result.h"
#include "core/io/recording.h"
#include "core/io/text_export.h"

namespace gearpath::tools {

enum class ReplayFormat { kAuto, kRecording, kText, kUff58 };

struct ReplayInputOptions {
  ReplayFormat format = ReplayFormat::kAuto;
  std::string machine;                   // override the machine id (single-stream inputs only)
  std::vector<std::string> select;       // machines to take from a directory of recordings
  double start_s = 0.0;                  // skip data before this offset from the first sample
  double end_s = 0.0;                    // stop at this offset; <= 0: to the end
  std::uint32_t block_length = 0;        // continuous inputs: samples per block; 0: 4096 (clamped)
  std::vector<std::string> channel_map;  // "COLUMN=SENSOR:AXIS" or "COLUMN=-" (drop)
  double sample_rate_hz = 0.0;           // text exports without a stated rate
  double shaft_speed_hz = 0.0;           // continuous inputs: input-shaft speed to send (0: none)
  double load = 0.0;      // continuous inputs: load to send with every block (0: none)
  std::string load_unit;  // its unit
  std::int64_t t0_ns = 0;                // continuous inputs: t0 of the first sample (0: now)
};

struct ReplayInput {
  std::string description;            // one line: what was read, for messages
  std::vector<Recording> recordings;  // one per machine stream
  std::size_t dropped_samples = 0;    // continuous inputs: tail shorter than a block
};

// Reads `path`; errors name the file and why (they are bad input: exit code 2).
Result<ReplayInput> LoadReplayInput(const std::filesystem::path& path,
                                    const ReplayInputOptions& options);

// Guesses the format from the path: a directory -> recording, ".unv"/".uff" -> UFF 58,
// anything else -> text.
ReplayFormat GuessReplayFormat(const std::filesystem::path& path);

// Cuts continuous samples into a recording (used for text and UFF inputs).
Result<Recording> BlockContinuous(const ContinuousAcquisition& acquisition,
                                  const std::string& machine_id, const ReplayInputOptions& options,
                                  std::size_t* dropped_samples);

// Machine ids become directory names: characters other than [A-Za-z0-9._-] turn into '_'.
std::string MachineDirectoryName(const std::string& machine_id);

}  // namespace gearpath::tools
