// Recording: a captured stream of AccelBlocks of one machine, on disk (docs/recording_format.md).
//
// A recording is a directory holding manifest.json (format "gearpath-recording", version 1: the
// machine id, sample rate, channels, block length and, per block, sequence number, t0_ns and
// speed) and samples.npy, float32 shaped (n_blocks, n_channels, samples_per_channel). That is
// exactly the planar layout of an AccelBlock, block after block, so a block is one contiguous
// slice (replay publishes it without copying) and replay reproduces every sample bit for bit;
// a NumPy user gets the continuous signal with samples.transpose(1, 0, 2).reshape(C, -1).
// Per-block integers (uint64 sequence, int64 t0_ns) live in the manifest as JSON integers,
// which both nlohmann::json and Python's json hold exactly (NumPy's int64 would do too, but the
// project's .npy layer reads no 64-bit integer dtype). Doubles are written shortest-round-trip.
//
// One recording = one machine and one block layout (channels, sample rate, block length);
// `gearpath record` starts a new recording when either changes. The writer streams: it appends
// blocks to samples.npy (header rewritten with the final shape on Close) and writes the manifest
// last, via a temporary file and rename, so a recording without a manifest is incomplete.
#pragma once

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "core/common/accel_block.h"
#include "core/common/result.h"

namespace gearpath {

inline constexpr char kRecordingFormatName[] = "gearpath-recording";
inline constexpr int kRecordingFormatVersion = 1;
inline constexpr char kRecordingManifestName[] = "manifest.json";
inline constexpr char kRecordingSamplesName[] = "samples.npy";

// What every block of a recording shares.
struct RecordingLayout {
  std::string machine_id;
  double sample_rate_hz = 0.0;
  std::vector<ChannelInfo> channels;
  std::uint32_t samples_per_channel = 0;
};

// What differs from block to block, besides the samples.
struct RecordedBlockInfo {
  std::uint64_t sequence = 0;
  std::int64_t t0_ns = 0;
  double speed_hz = 0.0;
  SpeedSource speed_source = SpeedSource::kUnknown;
};

struct Recording {
  RecordingLayout layout;
  std::vector<RecordedBlockInfo> blocks;
  std::vector<float> samples;  // blocks.size() x channels x samples_per_channel, C order

  std::size_t block_count() const { return blocks.size(); }
  std::size_t block_values() const {
    return layout.channels.size() * std::size_t{layout.samples_per_channel};
  }
  // View of block i (valid while this Recording lives and is not modified).
  AccelBlockView block(std::size_t i) const;
};

// "x", "y", "z" and back; "unknown", "acquisition", "configuration", "estimated" and back.
const char* AxisName(Axis axis) noexcept;
Result<Axis> ParseAxisName(const std::string& name);
const char* SpeedSourceName(SpeedSource source) noexcept;
Result<SpeedSource> ParseSpeedSourceName(const std::string& name);

// The layout of `block` (machine, rate, channels, length).
RecordingLayout LayoutOf(const AccelBlockView& block);
// True if `block` fits `layout` (same machine, rate, channels and length).
bool MatchesLayout(const RecordingLayout& layout, const AccelBlockView& block);

// True if `dir` holds a manifest whose "format" is kRecordingFormatName.
bool IsRecordingDirectory(const std::filesystem::path& dir);

// Reads a whole recording. Errors name the file and the manifest key or array at fault.
Result<Recording> ReadRecording(const std::filesystem::path& dir);

// Writes a whole recording (same bytes as streaming it through RecordingWriter).
Status WriteRecording(const Recording& recording, const std::filesystem::path& dir);

// Streams blocks into a recording directory.
class RecordingWriter {
 public:
  // Creates `dir` (it must not already hold a recording manifest) and samples.npy. The
  // layout's strings (machine id, sensors, units) must be UTF-8, since the manifest is JSON:
  // checked before any file is written.
  static Result<std::unique_ptr<RecordingWriter>> Open(const std::filesystem::path& dir,
                                                       const RecordingLayout& layout);
  ~RecordingWriter();
  RecordingWriter(const RecordingWriter&) = delete;
  RecordingWriter& operator=(const RecordingWriter&) = delete;

  // Appends one block; it must match the layout (error names the field that differs).
  Status Append(const AccelBlockView& block);
  // Finishes samples.npy and writes the manifest. Idempotent. If the manifest cannot be
  // written, samples.npy is removed too (no half-written recording is left).
  Status Close();

  const RecordingLayout& layout() const { return layout_; }
  const std::filesystem::path& dir() const { return dir_; }
  std::size_t block_count() const { return blocks_.size(); }

 private:
  RecordingWriter(std::filesystem::path dir, RecordingLayout layout);

  std::filesystem::path dir_;
  RecordingLayout layout_;
  std::vector<RecordedBlockInfo> blocks_;
  std::ofstream samples_;
  bool closed_ = false;
};

}  // namespace gearpath
