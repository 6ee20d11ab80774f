// Recording: a captured stream of AccelBlocks of one machine, on disk (docs/recording_format.md).
//
// A recording is a directory holding manifest.json (format "gearpath-recording": the machine id,
// sample rate, channels, block length and, per block, sequence number, t0_ns and speed; version 2
// adds the load unit and each block's load, and is written only when the blocks carry a load, so
// that recordings without one stay readable by version-1 readers) and samples.npy, float32 shaped
// (n_blocks, n_channels, samples_per_channel). That is exactly the planar layout of an AccelBlock,
// block after block, so a block is one contiguous slice (replay publishes it without copying) and
// replay reproduces every sample bit for bit; a NumPy user gets the continuous signal with
// samples.transpose(1, 0, 2).reshape(C, -1). Per-block integers (uint64 sequence, int64 t0_ns) live
// in the manifest as JSON integers, which both nlohmann::json and Python's json hold exactly
// (NumPy's int64 would do too, but the project's .npy layer reads no 64-bit integer dtype). Doubles
// are written shortest-round-trip.
//
// One recording = one machine and one block layout (channels, sample rate, block length, load
// unit); `gearpath record` starts a new recording when any of them changes. The writer streams: it appends
// blocks to samples.npy (header rewritten with the final shape on Close) and writes the manifest
// last, via a temporary file and rename, so a recording without a manifest is incomplete.
#pragma once

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "core/common/accel_block.h"
#include "core/common/result.h"

namespace gearpath {

inline constexpr char kRecordingFormatName[] = "gearpath-recording";
// The newest version this build reads and writes; it reads every older one too.
inline constexpr int kRecordingFormatVersion = 2;
inline constexpr char kRecordingManifestName[] = "manifest.json";
inline constexpr char kRecordingSamplesName[] = "samples.npy";

// What every block of a recording shares.
struct RecordingLayout {
  std::string machine_id;
  double sample_rate_hz = 0.0;
  std::vector<ChannelInfo> channels;
  std::uint32_t samples_per_channel = 0;
  // Unit of the blocks' load (AccelBlockV2::load_unit, at most 16 characters); empty when the
  // blocks came without one (AccelBlock), which is also every version-1 recording.
  std::string load_unit{};
};

// What differs from block to block, besides the samples.
struct RecordedBlockInfo {
  std::uint64_t sequence = 0;
  std::int64_t t0_ns = 0;
  double speed_hz = 0.0;
  SpeedSource speed_source = SpeedSource::kUnknown;
  double load = 0.0;  // the block's load in layout.load_unit; 0 = not carried
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
  // True when the blocks came with a load (a load unit, or any block's load not 0): replay then
  // publishes them as AccelBlockV2, and the manifest is written as version 2.
  bool carries_load() const;
};

// "x", "y", "z" and back; "unknown", "acquisition", "configuration", "estimated" and back.
const char* AxisName(Axis axis) noexcept;
Result<Axis> ParseAxisName(const std::string& name);
const char* SpeedSourceName(SpeedSource source) noexcept;
Result<SpeedSource> ParseSpeedSourceName(const std::string& name);

// The layout of `block` (machine, rate, channels, length), its load in `load_unit`.
RecordingLayout LayoutOf(const AccelBlockView& block, std::string load_unit = {});
// True if `block`, its load in `load_unit`, fits `layout` (same machine, rate, channels, length
// and load unit).
bool MatchesLayout(const RecordingLayout& layout, const AccelBlockView& block,
                   std::string_view load_unit = {});

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
