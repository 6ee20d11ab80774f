#include "tools/common/replay_input.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>

#include "core/io/uff58.h"
#include "core/io/uff58_import.h"
#include "idl/gearpath.h"

namespace gearpath::tools {
namespace {

namespace fs = std::filesystem;

std::string Lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

std::string ChannelLabel(const ChannelInfo& c) {
  return c.sensor + "-" + static_cast<char>(std::toupper(AxisName(c.axis)[0]));
}

// Applies "COLUMN=SENSOR:AXIS" / "COLUMN=-" to `channels` (names: the written column names, may
// be empty). Returns the kept channel indices in order.
Result<std::vector<std::size_t>> ApplyChannelMap(const std::vector<std::string>& map,
                                                 std::vector<ChannelInfo>& channels,
                                                 const std::vector<std::string>& names) {
  std::vector<bool> keep(channels.size(), true);
  for (const std::string& entry : map) {
    const std::size_t eq = entry.find('=');
    if (eq == std::string::npos || eq == 0) {
      return Error{"--channel " + entry + ": expected COLUMN=SENSOR:AXIS or COLUMN=-"};
    }
    const std::string column = entry.substr(0, eq), target = entry.substr(eq + 1);
    std::size_t index = channels.size();
    for (std::size_t c = 0; c < channels.size(); ++c) {
      if ((c < names.size() && names[c] == column) || ChannelLabel(channels[c]) == column ||
          std::to_string(c + 1) == column) {
        index = c;
        break;
      }
    }
    if (index == channels.size()) {
      std::string known;
      for (std::size_t c = 0; c < channels.size(); ++c) {
        known += (c ? ", " : "") + (c < names.size() ? names[c] : ChannelLabel(channels[c]));
      }
      return Error{"--channel " + entry + ": no channel named \"" + column +
                   "\" (channels: " + known + ")"};
    }
    if (target == "-") {
      keep[index] = false;
      continue;
    }
    const std::size_t colon = target.rfind(':');
    if (colon == std::string::npos || colon == 0) {
      return Error{"--channel " + entry + ": expected SENSOR:AXIS after '=' (e.g. A1:x)"};
    }
    Result<Axis> axis = ParseAxisName(target.substr(colon + 1));
    if (!axis) return Error{"--channel " + entry + ": " + axis.error()};
    channels[index].sensor = target.substr(0, colon);
    channels[index].axis = *axis;
  }
  std::vector<std::size_t> kept;
  for (std::size_t c = 0; c < channels.size(); ++c) {
    if (keep[c]) kept.push_back(c);
  }
  if (kept.empty()) return Error{"--channel: every channel was dropped"};
  return kept;
}

Result<ContinuousAcquisition> FromUff(const fs::path& path) {
  Result<std::vector<Uff58Record>> records = ReadUff58(path);
  if (!records) return Error{records.error()};
  Result<TimeHistories> th = ExtractTimeHistories(*records);
  if (!th) return Error{path.string() + ": " + th.error()};
  if (th->channels.empty()) {
    return Error{path.string() + ": holds no time-response record (UFF 58 function type 1)"};
  }
  ContinuousAcquisition acq;
  acq.sample_rate_hz = th->sample_rate_hz;
  acq.start_time_s = th->start_time_s;
  const auto n = static_cast<std::size_t>(th->samples.rows());
  acq.samples_per_channel = n;
  for (std::size_t c = 0; c < th->channels.size(); ++c) {
    const TimeHistories::Channel& ch = th->channels[c];
    ChannelInfo info;
    const int dir = std::abs(ch.direction);
    if (dir < 1 || dir > 3) {
      return Error{path.string() + ": time history " + std::to_string(c + 1) + " (node " +
                   std::to_string(ch.node) + ") has direction " + UffDirectionName(ch.direction) +
                   "; only translations (+/-X, Y, Z) are accelerometer channels"};
    }
    info.sensor = std::to_string(ch.node);
    info.axis = dir == 1 ? Axis::kX : dir == 2 ? Axis::kY : Axis::kZ;
    info.unit = (ch.unit.empty() || ch.unit == "NONE") ? "m/s^2" : ch.unit;
    const double scale = NormaliseAccelerationUnit(&info.unit) * (ch.direction < 0 ? -1.0 : 1.0);
    acq.channels.push_back(info);
    acq.column_names.push_back(ch.label.empty() || ch.label == "NONE" ? ChannelLabel(info)
                                                                      : ch.label);
    for (std::size_t k = 0; k < n; ++k) {
      acq.samples.push_back(static_cast<float>(
          th->samples(static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(c)) * scale));
    }
  }
  return acq;
}

// Keeps only the recordings' blocks whose t0 lies in [start, end) from the earliest t0.
void TrimRecordings(std::vector<Recording>& recordings, double start_s, double end_s) {
  if (start_s <= 0 && end_s <= 0) return;
  std::int64_t t_first = INT64_MAX;
  for (const Recording& r : recordings) {
    if (!r.blocks.empty()) t_first = std::min(t_first, r.blocks.front().t0_ns);
  }
  for (Recording& r : recordings) {
    Recording out;
    out.layout = r.layout;
    for (std::size_t i = 0; i < r.block_count(); ++i) {
      const double offset = static_cast<double>(r.blocks[i].t0_ns - t_first) * 1e-9;
      if (offset < start_s - 1e-12) continue;
      if (end_s > 0 && offset >= end_s) continue;
      out.blocks.push_back(r.blocks[i]);
      const AccelBlockView v = r.block(i);
      out.samples.insert(out.samples.end(), v.samples.begin(), v.samples.end());
    }
    r = std::move(out);
  }
}

Status MapRecordingChannels(Recording& r, const std::vector<std::string>& map) {
  if (map.empty()) return Status::Ok();
  Result<std::vector<std::size_t>> kept = ApplyChannelMap(map, r.layout.channels, {});
  if (!kept) return Error{kept.error()};
  if (kept->size() == r.layout.channels.size()) return Status::Ok();
  std::vector<float> samples;
  std::vector<ChannelInfo> channels;
  for (std::size_t c : *kept) channels.push_back(r.layout.channels[c]);
  for (std::size_t b = 0; b < r.block_count(); ++b) {
    const AccelBlockView v = r.block(b);
    for (std::size_t c : *kept) {
      const auto ch = v.channel(c);
      samples.insert(samples.end(), ch.begin(), ch.end());
    }
  }
  r.layout.channels = std::move(channels);
  r.samples = std::move(samples);
  return Status::Ok();
}

}  // namespace

std::string MachineDirectoryName(const std::string& machine_id) {
  std::string out = machine_id;
  for (char& c : out) {
    const bool ok = std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '_' || c == '-';
    if (!ok) c = '_';
  }
  if (out.empty() || out == "." || out == "..") out = "_" + out;
  return out;
}

ReplayFormat GuessReplayFormat(const fs::path& path) {
  if (fs::is_directory(path)) return ReplayFormat::kRecording;
  const std::string ext = Lower(path.extension().string());
  if (ext == ".unv" || ext == ".uff" || ext == ".uf") return ReplayFormat::kUff58;
  return ReplayFormat::kText;
}

Result<Recording> BlockContinuous(const ContinuousAcquisition& acquisition,
                                  const std::string& machine_id, const ReplayInputOptions& options,
                                  std::size_t* dropped_samples) {
  ContinuousAcquisition acq = acquisition;
  Result<std::vector<std::size_t>> kept =
      ApplyChannelMap(options.channel_map, acq.channels, acq.column_names);
  if (!kept) return Error{kept.error()};
  const std::size_t n = acq.samples_per_channel;
  const double fs = acq.sample_rate_hz;
  auto index_of = [&](double seconds) {
    return static_cast<std::size_t>(
        std::clamp(std::llround(seconds * fs), 0ll, static_cast<long long>(n)));
  };
  const std::size_t begin = index_of(options.start_s);
  const std::size_t end = options.end_s > 0 ? index_of(options.end_s) : n;
  if (begin >= end) {
    return Error{"--start " + std::to_string(options.start_s) + " s / --end " +
                 std::to_string(options.end_s) + " s leave no sample of the " +
                 std::to_string(static_cast<double>(n) / fs) + " s input"};
  }
  const std::size_t channels = kept->size();
  std::size_t length = options.block_length;
  if (length == 0) {
    length = std::min<std::size_t>(4096, end - begin);
    length = std::min<std::size_t>(length, gearpath_MAX_BLOCK_SAMPLES / channels);
  }
  if (length > gearpath_MAX_SAMPLES_PER_CHANNEL || length * channels > gearpath_MAX_BLOCK_SAMPLES) {
    return Error{"--block-length " + std::to_string(length) + " x " + std::to_string(channels) +
                 " channels exceeds the AccelBlock bounds (" +
                 std::to_string(gearpath_MAX_SAMPLES_PER_CHANNEL) + " per channel, " +
                 std::to_string(gearpath_MAX_BLOCK_SAMPLES) + " per block)"};
  }
  if (channels > gearpath_MAX_CHANNELS) {
    return Error{std::to_string(channels) + " channels exceed the AccelBlock bound of " +
                 std::to_string(gearpath_MAX_CHANNELS) + " (drop some with --channel COLUMN=-)"};
  }
  const std::size_t n_blocks = (end - begin) / length;
  if (n_blocks == 0) {
    return Error{"the input holds " + std::to_string(end - begin) +
                 " samples per channel, fewer than one block of " + std::to_string(length)};
  }
  if (dropped_samples) *dropped_samples = (end - begin) - n_blocks * length;
  Recording r;
  r.layout.machine_id = machine_id;
  r.layout.sample_rate_hz = fs;
  for (std::size_t c : *kept) r.layout.channels.push_back(acq.channels[c]);
  r.layout.samples_per_channel = static_cast<std::uint32_t>(length);
  if (options.load > 0) r.layout.load_unit = options.load_unit;
  const std::int64_t t0 = options.t0_ns != 0
                              ? options.t0_ns
                              : std::chrono::duration_cast<std::chrono::nanoseconds>(
                                    std::chrono::system_clock::now().time_since_epoch())
                                    .count();
  r.samples.reserve(n_blocks * channels * length);
  for (std::size_t b = 0; b < n_blocks; ++b) {
    const std::size_t first = begin + b * length;
    const double offset_s = static_cast<double>(first - begin) / fs;
    r.blocks.push_back(
        {b, t0 + std::llround(offset_s * 1e9), options.shaft_speed_hz,
         options.shaft_speed_hz > 0 ? SpeedSource::kConfiguration : SpeedSource::kUnknown,
         options.load});
    for (std::size_t c : *kept) {
      const auto ch = acq.channel(c).subspan(first, length);
      r.samples.insert(r.samples.end(), ch.begin(), ch.end());
    }
  }
  return r;
}

Result<ReplayInput> LoadReplayInput(const fs::path& path, const ReplayInputOptions& options) {
  if (!fs::exists(path)) return Error{path.string() + ": no such file or directory"};
  const ReplayFormat format =
      options.format == ReplayFormat::kAuto ? GuessReplayFormat(path) : options.format;
  ReplayInput input;
  if (format == ReplayFormat::kRecording) {
    if (options.block_length != 0) {
      return Error{
          "--block-length re-blocks continuous inputs (text, UFF); a recording keeps "
          "its blocks"};
    }
    std::vector<fs::path> dirs;
    if (fs::exists(path / kRecordingManifestName)) {
      dirs.push_back(path);
    } else if (fs::is_directory(path)) {
      for (const auto& entry : fs::directory_iterator(path)) {
        if (entry.is_directory() && fs::exists(entry.path() / kRecordingManifestName)) {
          dirs.push_back(entry.path());
        }
      }
      std::sort(dirs.begin(), dirs.end());
    }
    if (dirs.empty()) {
      return Error{path.string() +
                   ": neither a recording (no manifest.json) nor a directory of "
                   "recordings"};
    }
    for (const fs::path& dir : dirs) {
      Result<Recording> r = ReadRecording(dir);
      if (!r) return Error{r.error()};
      if (!options.select.empty() && std::find(options.select.begin(), options.select.end(),
                                               r->layout.machine_id) == options.select.end()) {
        continue;
      }
      input.recordings.push_back(std::move(*r));
    }
    for (const std::string& wanted : options.select) {
      const bool found =
          std::any_of(input.recordings.begin(), input.recordings.end(),
                      [&](const Recording& r) { return r.layout.machine_id == wanted; });
      if (!found) {
        std::string have;
        for (const fs::path& dir : dirs)
          have += (have.empty() ? "" : ", ") + dir.filename().string();
        return Error{path.string() + ": unknown machine \"" + wanted + "\" (recordings: " + have +
                     ")"};
      }
    }
    if (!options.machine.empty()) {
      if (input.recordings.size() != 1) {
        return Error{"--machine renames a single stream, but " + path.string() + " holds " +
                     std::to_string(input.recordings.size()) +
                     " machines' recordings (choose one with --select)"};
      }
      input.recordings[0].layout.machine_id = options.machine;
    }
    for (Recording& r : input.recordings) {
      if (Status st = MapRecordingChannels(r, options.channel_map); !st) return Error{st.error()};
    }
    TrimRecordings(input.recordings, options.start_s, options.end_s);
    input.description = "recording " + path.string();
    return input;
  }
  if (!options.select.empty()) {
    return Error{"--select picks machines from a directory of recordings; " + path.string() +
                 " holds one stream (use --machine to name it)"};
  }
  ContinuousAcquisition acq;
  if (format == ReplayFormat::kText) {
    Result<TextExport> text = ReadTextExport(path, {.sample_rate_hz = options.sample_rate_hz});
    if (!text) return Error{text.error()};
    acq = std::move(text->acquisition);
    input.description = "text export " + path.string();
  } else {
    Result<ContinuousAcquisition> uff = FromUff(path);
    if (!uff) return Error{uff.error()};
    acq = std::move(*uff);
    input.description = "UFF 58 time histories " + path.string();
  }
  const std::string machine = options.machine.empty() ? path.stem().string() : options.machine;
  Result<Recording> r = BlockContinuous(acq, machine, options, &input.dropped_samples);
  if (!r) return Error{path.string() + ": " + r.error()};
  input.recordings.push_back(std::move(*r));
  return input;
}

}  // namespace gearpath::tools
