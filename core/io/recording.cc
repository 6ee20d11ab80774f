#include "core/io/recording.h"

#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <nlohmann/json.hpp>
#include <system_error>

#include "core/io/json_read.h"
#include "core/io/npy.h"

namespace gearpath {
namespace {

static_assert(std::endian::native == std::endian::little,
              "samples.npy is written little-endian from host memory");

using nlohmann::json;

// The .npy header of samples.npy always takes this many bytes (magic, version, length, dict,
// padding), so Close can rewrite it with the final block count in place.
constexpr std::size_t kNpyHeaderBytes = 128;

std::string NpyHeaderBytes(std::size_t n_blocks, std::size_t n_channels, std::size_t length) {
  std::string dict = "{'descr': '<f4', 'fortran_order': False, 'shape': (" +
                     std::to_string(n_blocks) + ", " + std::to_string(n_channels) + ", " +
                     std::to_string(length) + "), }";
  const std::size_t prefix = 10;  // magic (6) + version (2) + header length (2)
  dict.append(kNpyHeaderBytes - prefix - dict.size() - 1, ' ');
  dict += '\n';
  std::string out("\x93NUMPY\x01\x00", 8);
  const auto len = static_cast<std::uint16_t>(dict.size());
  out += static_cast<char>(len & 0xff);
  out += static_cast<char>(len >> 8);
  return out + dict;
}

std::string Quoted(const std::string& s) { return "\"" + s + "\""; }

json DoubleJson(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

// Version 2 only when there is a load to keep: recordings of plain AccelBlocks stay version 1,
// readable by every earlier build. A NaN load counts (it is kept, and the daemon rejects it).
bool CarriesLoad(const RecordingLayout& layout, const std::vector<RecordedBlockInfo>& blocks) {
  if (!layout.load_unit.empty()) return true;
  for (const RecordedBlockInfo& b : blocks) {
    if (b.load != 0.0) return true;
  }
  return false;
}

json ManifestOf(const RecordingLayout& layout, const std::vector<RecordedBlockInfo>& blocks) {
  json channels = json::array();
  for (const ChannelInfo& c : layout.channels) {
    channels.push_back({{"sensor", c.sensor},
                        {"axis", AxisName(c.axis)},
                        {"unit", c.unit},
                        {"sensitivity_mv_per_unit", DoubleJson(c.sensitivity)}});
  }
  const bool with_load = CarriesLoad(layout, blocks);
  json sequence = json::array(), t0 = json::array(), speed = json::array(), source = json::array(),
       load = json::array();
  for (const RecordedBlockInfo& b : blocks) {
    sequence.push_back(b.sequence);
    t0.push_back(b.t0_ns);
    speed.push_back(DoubleJson(b.speed_hz));
    source.push_back(SpeedSourceName(b.speed_source));
    if (with_load) load.push_back(DoubleJson(b.load));
  }
  json m;
  m["format"] = kRecordingFormatName;
  m["format_version"] = with_load ? kRecordingFormatVersion : 1;
  m["machine_id"] = layout.machine_id;
  m["sample_rate_hz"] = DoubleJson(layout.sample_rate_hz);
  m["samples_per_channel"] = layout.samples_per_channel;
  m["channels"] = channels;
  if (with_load) m["load_unit"] = layout.load_unit;
  m["samples"] = {{"file", kRecordingSamplesName},
                  {"dtype", "float32"},
                  {"shape", {blocks.size(), layout.channels.size(), layout.samples_per_channel}},
                  {"axes", {"block", "channel", "sample"}}};
  m["blocks"] = {{"count", blocks.size()},
                 {"sequence", sequence},
                 {"t0_ns", t0},
                 {"speed_hz", speed},
                 {"speed_source", source}};
  if (with_load) m["blocks"]["load"] = load;
  return m;
}

Status WriteManifest(const std::filesystem::path& dir, const json& manifest) {
  const auto final_path = dir / kRecordingManifestName;
  const auto tmp = dir / (std::string(kRecordingManifestName) + ".tmp");
  {
    Result<std::string> text = DumpJson(manifest, 1, final_path.string());
    if (!text) return Error{text.error()};
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) return Error{tmp.string() + ": cannot open for writing"};
    out << *text << '\n';
    if (!out) return Error{tmp.string() + ": write error"};
  }
  std::error_code ec;
  std::filesystem::rename(tmp, final_path, ec);
  if (ec) return Error{final_path.string() + ": cannot rename into place: " + ec.message()};
  return Status::Ok();
}

std::string LayoutMismatch(const RecordingLayout& layout, const AccelBlockView& block) {
  if (block.machine_id != layout.machine_id) {
    return "machine_id " + Quoted(std::string(block.machine_id)) +
           " differs from the recording's " + Quoted(layout.machine_id);
  }
  if (std::bit_cast<std::uint64_t>(block.sample_rate_hz) !=
      std::bit_cast<std::uint64_t>(layout.sample_rate_hz)) {
    return "sample_rate_hz " + std::to_string(block.sample_rate_hz) +
           " differs from the recording's " + std::to_string(layout.sample_rate_hz);
  }
  if (block.samples_per_channel != layout.samples_per_channel) {
    return "samples_per_channel " + std::to_string(block.samples_per_channel) +
           " differs from the recording's " + std::to_string(layout.samples_per_channel);
  }
  if (block.channels.size() != layout.channels.size()) {
    return std::to_string(block.channels.size()) + " channels differ from the recording's " +
           std::to_string(layout.channels.size());
  }
  for (std::size_t c = 0; c < block.channels.size(); ++c) {
    const ChannelInfo& a = block.channels[c];
    const ChannelInfo& b = layout.channels[c];
    if (a.sensor != b.sensor || a.axis != b.axis || a.unit != b.unit ||
        std::bit_cast<std::uint64_t>(a.sensitivity) !=
            std::bit_cast<std::uint64_t>(b.sensitivity)) {
      return "channels[" + std::to_string(c) + "] differs from the recording's";
    }
  }
  return {};
}

// A recording's manifest lists every block (about 60 bytes each): allow long recordings.
constexpr JsonReadLimits kRecordingJsonLimits{kMaxJsonDepth, std::size_t{1} << 30};

// Every string of the layout goes into the manifest, which must be UTF-8: checked when the
// recording is opened, so a bad channel name fails before any file is written.
std::string LayoutUtf8Problem(const RecordingLayout& layout) {
  if (auto why = Utf8Problem(layout.machine_id)) return "machine_id is not UTF-8: " + *why;
  if (auto why = Utf8Problem(layout.load_unit)) return "load_unit is not UTF-8: " + *why;
  for (std::size_t c = 0; c < layout.channels.size(); ++c) {
    const ChannelInfo& ch = layout.channels[c];
    for (const auto& [field, text] : {std::pair{"sensor", &ch.sensor}, std::pair{"unit", &ch.unit}}) {
      if (auto why = Utf8Problem(*text)) {
        return "channels[" + std::to_string(c) + "]." + field + " is not UTF-8: " + *why;
      }
    }
  }
  return {};
}

// Manifest access with key-path errors.
class ManifestReader {
 public:
  ManifestReader(const json& root, std::string file) : root_(root), file_(std::move(file)) {}

  const json* Get(const json& obj, const std::string& key, const std::string& path,
                  json::value_t type) {
    if (!error_.empty()) return nullptr;
    auto it = obj.find(key);
    if (it == obj.end()) {
      error_ = file_ + ": missing key " + Quoted(path);
      return nullptr;
    }
    const bool ok = type == json::value_t::number_float      ? (it->is_number() || it->is_null())
                    : type == json::value_t::number_unsigned ? it->is_number_unsigned()
                                                             : it->type() == type;
    if (!ok) {
      error_ = file_ + ": " + path + " has the wrong type (" + it->type_name() + ")";
      return nullptr;
    }
    return &*it;
  }
  void Fail(const std::string& why) {
    if (error_.empty()) error_ = file_ + ": " + why;
  }
  bool ok() const { return error_.empty(); }
  Error error() const { return Error{error_}; }
  const json& root() const { return root_; }

 private:
  const json& root_;
  std::string file_;
  std::string error_;
};

double AsDouble(const json& j) {
  return j.is_null() ? std::numeric_limits<double>::quiet_NaN() : j.get<double>();
}

}  // namespace

const char* AxisName(Axis axis) noexcept {
  switch (axis) {
    case Axis::kX:
      return "x";
    case Axis::kY:
      return "y";
    case Axis::kZ:
      return "z";
  }
  return "x";
}

Result<Axis> ParseAxisName(const std::string& name) {
  if (name == "x" || name == "X") return Axis::kX;
  if (name == "y" || name == "Y") return Axis::kY;
  if (name == "z" || name == "Z") return Axis::kZ;
  return Error{"axis must be \"x\", \"y\" or \"z\", got " + Quoted(name)};
}

const char* SpeedSourceName(SpeedSource source) noexcept {
  switch (source) {
    case SpeedSource::kUnknown:
      return "unknown";
    case SpeedSource::kAcquisition:
      return "acquisition";
    case SpeedSource::kConfiguration:
      return "configuration";
    case SpeedSource::kEstimated:
      return "estimated";
  }
  return "unknown";
}

Result<SpeedSource> ParseSpeedSourceName(const std::string& name) {
  for (SpeedSource s : {SpeedSource::kUnknown, SpeedSource::kAcquisition,
                        SpeedSource::kConfiguration, SpeedSource::kEstimated}) {
    if (name == SpeedSourceName(s)) return s;
  }
  return Error{
      "speed source must be \"unknown\", \"acquisition\", \"configuration\" or "
      "\"estimated\", got " +
      Quoted(name)};
}

bool Recording::carries_load() const { return CarriesLoad(layout, blocks); }

AccelBlockView Recording::block(std::size_t i) const {
  const RecordedBlockInfo& b = blocks[i];
  AccelBlockView v;
  v.machine_id = layout.machine_id;
  v.sequence = b.sequence;
  v.t0_ns = b.t0_ns;
  v.sample_rate_hz = layout.sample_rate_hz;
  v.speed_hz = b.speed_hz;
  v.speed_source = b.speed_source;
  v.load = b.load;
  v.channels = layout.channels;
  v.samples_per_channel = layout.samples_per_channel;
  v.samples = std::span<const float>(samples).subspan(i * block_values(), block_values());
  return v;
}

RecordingLayout LayoutOf(const AccelBlockView& block, std::string load_unit) {
  return {std::string(block.machine_id), block.sample_rate_hz,
          std::vector<ChannelInfo>(block.channels.begin(), block.channels.end()),
          block.samples_per_channel, std::move(load_unit)};
}

bool MatchesLayout(const RecordingLayout& layout, const AccelBlockView& block,
                   std::string_view load_unit) {
  return layout.load_unit == load_unit && LayoutMismatch(layout, block).empty();
}

bool IsRecordingDirectory(const std::filesystem::path& dir) {
  if (!std::ifstream(dir / kRecordingManifestName)) return false;
  const Result<json> root = ReadJsonFile<json>(dir / kRecordingManifestName, kRecordingJsonLimits);
  if (!root || !root->is_object()) return false;
  const auto format = root->find("format");
  return format != root->end() && format->is_string() &&
         format->get_ref<const std::string&>() == kRecordingFormatName;
}

Result<Recording> ReadRecording(const std::filesystem::path& dir) {
  const std::string mf = (dir / kRecordingManifestName).string();
  if (!std::ifstream(dir / kRecordingManifestName)) {
    return Error{mf + ": missing manifest (not a recording directory?)"};
  }
  Result<json> manifest = ReadJsonFile<json>(dir / kRecordingManifestName, kRecordingJsonLimits);
  if (!manifest) return Error{manifest.error()};
  const json root = std::move(manifest.value());
  if (!root.is_object()) return Error{mf + ": the manifest must be a JSON object"};
  ManifestReader r(root, mf);
  const json* format = r.Get(root, "format", "format", json::value_t::string);
  if (!r.ok()) return r.error();
  if (format->get<std::string>() != kRecordingFormatName) {
    return Error{mf + ": format: expected " + Quoted(kRecordingFormatName) + ", got " +
                 Quoted(format->get<std::string>())};
  }
  const json* version =
      r.Get(root, "format_version", "format_version", json::value_t::number_unsigned);
  if (!r.ok()) return r.error();
  const long long format_version = version->get<long long>();
  if (format_version < 1 || format_version > kRecordingFormatVersion) {
    return Error{mf + ": format_version " + version->dump() +
                 " is not supported (this build reads 1 to " +
                 std::to_string(kRecordingFormatVersion) + ")"};
  }
  const bool with_load = format_version >= 2;
  Recording rec;
  const json* machine = r.Get(root, "machine_id", "machine_id", json::value_t::string);
  const json* rate = r.Get(root, "sample_rate_hz", "sample_rate_hz", json::value_t::number_float);
  const json* length =
      r.Get(root, "samples_per_channel", "samples_per_channel", json::value_t::number_unsigned);
  const json* channels = r.Get(root, "channels", "channels", json::value_t::array);
  const json* blocks = r.Get(root, "blocks", "blocks", json::value_t::object);
  if (!r.ok()) return r.error();
  rec.layout.machine_id = machine->get<std::string>();
  if (rec.layout.machine_id.empty()) return Error{mf + ": machine_id must not be empty"};
  rec.layout.sample_rate_hz = AsDouble(*rate);
  if (!(rec.layout.sample_rate_hz > 0) || !std::isfinite(rec.layout.sample_rate_hz)) {
    return Error{mf + ": sample_rate_hz must be a finite number > 0, got " + rate->dump()};
  }
  if (length->get<std::uint64_t>() == 0 ||
      length->get<std::uint64_t>() > std::numeric_limits<std::uint32_t>::max()) {
    return Error{mf + ": samples_per_channel must be >= 1, got " + length->dump()};
  }
  rec.layout.samples_per_channel = length->get<std::uint32_t>();
  if (with_load) {
    const json* unit = r.Get(root, "load_unit", "load_unit", json::value_t::string);
    if (!r.ok()) return r.error();
    rec.layout.load_unit = unit->get<std::string>();
  }
  if (channels->empty()) return Error{mf + ": channels is empty"};
  for (std::size_t c = 0; c < channels->size(); ++c) {
    const std::string at = "channels[" + std::to_string(c) + "]";
    const json& jc = (*channels)[c];
    if (!jc.is_object()) return Error{mf + ": " + at + " must be an object"};
    const json* sensor = r.Get(jc, "sensor", at + ".sensor", json::value_t::string);
    const json* axis = r.Get(jc, "axis", at + ".axis", json::value_t::string);
    const json* unit = r.Get(jc, "unit", at + ".unit", json::value_t::string);
    const json* sens = r.Get(jc, "sensitivity_mv_per_unit", at + ".sensitivity_mv_per_unit",
                             json::value_t::number_float);
    if (!r.ok()) return r.error();
    Result<Axis> parsed = ParseAxisName(axis->get<std::string>());
    if (!parsed) return Error{mf + ": " + at + ".axis: " + parsed.error()};
    rec.layout.channels.push_back(
        {sensor->get<std::string>(), *parsed, unit->get<std::string>(), AsDouble(*sens)});
  }
  const json* count = r.Get(*blocks, "count", "blocks.count", json::value_t::number_unsigned);
  const json* seq = r.Get(*blocks, "sequence", "blocks.sequence", json::value_t::array);
  const json* t0 = r.Get(*blocks, "t0_ns", "blocks.t0_ns", json::value_t::array);
  const json* speed = r.Get(*blocks, "speed_hz", "blocks.speed_hz", json::value_t::array);
  const json* source = r.Get(*blocks, "speed_source", "blocks.speed_source", json::value_t::array);
  const json* load =
      with_load ? r.Get(*blocks, "load", "blocks.load", json::value_t::array) : nullptr;
  if (!r.ok()) return r.error();
  const std::size_t n = count->get<std::size_t>();
  for (const auto& [name, arr] :
       {std::pair{"sequence", seq}, std::pair{"t0_ns", t0}, std::pair{"speed_hz", speed},
        std::pair{"speed_source", source}, std::pair{"load", load}}) {
    if (arr && arr->size() != n) {
      return Error{mf + ": blocks." + name + " has " + std::to_string(arr->size()) +
                   " entries but blocks.count is " + std::to_string(n)};
    }
  }
  rec.blocks.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::string at = "[" + std::to_string(i) + "]";
    const json& js = (*seq)[i];
    const json& jt = (*t0)[i];
    const json& jv = (*speed)[i];
    const json& jsrc = (*source)[i];
    if (!js.is_number_unsigned())
      return Error{mf + ": blocks.sequence" + at + " is not an unsigned integer"};
    if (!jt.is_number_integer()) return Error{mf + ": blocks.t0_ns" + at + " is not an integer"};
    if (!jv.is_number() && !jv.is_null())
      return Error{mf + ": blocks.speed_hz" + at + " is not a number"};
    if (!jsrc.is_string()) return Error{mf + ": blocks.speed_source" + at + " is not a string"};
    Result<SpeedSource> src = ParseSpeedSourceName(jsrc.get<std::string>());
    if (!src) return Error{mf + ": blocks.speed_source" + at + ": " + src.error()};
    rec.blocks[i] = {js.get<std::uint64_t>(), jt.get<std::int64_t>(), AsDouble(jv), *src};
    if (load) {
      const json& jl = (*load)[i];
      if (!jl.is_number() && !jl.is_null())
        return Error{mf + ": blocks.load" + at + " is not a number"};
      rec.blocks[i].load = AsDouble(jl);
    }
  }
  const auto samples_path = dir / kRecordingSamplesName;
  if (!std::filesystem::exists(samples_path)) {
    return Error{samples_path.string() + ": missing samples array"};
  }
  Result<NpyArray<float>> samples = ReadNpy<float>(samples_path);
  if (!samples) return Error{samples.error()};
  const std::vector<std::size_t> expected = {n, rec.layout.channels.size(),
                                             rec.layout.samples_per_channel};
  if (samples->shape != expected) {
    auto shape_text = [](const std::vector<std::size_t>& s) {
      std::string t = "(";
      for (std::size_t i = 0; i < s.size(); ++i) t += (i ? ", " : "") + std::to_string(s[i]);
      return t + ")";
    };
    return Error{samples_path.string() + ": shape " + shape_text(samples->shape) +
                 " does not match the manifest: expected " + shape_text(expected) +
                 " (blocks, channels, samples_per_channel)"};
  }
  rec.samples = std::move(samples->data);
  return rec;
}

Status WriteRecording(const Recording& recording, const std::filesystem::path& dir) {
  Result<std::unique_ptr<RecordingWriter>> writer = RecordingWriter::Open(dir, recording.layout);
  if (!writer) return Error{writer.error()};
  for (std::size_t i = 0; i < recording.block_count(); ++i) {
    if (Status st = (*writer)->Append(recording.block(i)); !st) return st;
  }
  return (*writer)->Close();
}

RecordingWriter::RecordingWriter(std::filesystem::path dir, RecordingLayout layout)
    : dir_(std::move(dir)), layout_(std::move(layout)) {}

RecordingWriter::~RecordingWriter() { (void)Close(); }

Result<std::unique_ptr<RecordingWriter>> RecordingWriter::Open(const std::filesystem::path& dir,
                                                               const RecordingLayout& layout) {
  if (layout.machine_id.empty()) return Error{"recording layout: machine_id is empty"};
  if (layout.channels.empty()) return Error{"recording layout: no channels"};
  if (layout.samples_per_channel == 0) return Error{"recording layout: samples_per_channel is 0"};
  if (!(layout.sample_rate_hz > 0) || !std::isfinite(layout.sample_rate_hz)) {
    return Error{"recording layout: sample_rate_hz must be finite and > 0"};
  }
  if (std::string why = LayoutUtf8Problem(layout); !why.empty()) {
    return Error{"recording layout: " + why};
  }
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) return Error{dir.string() + ": cannot create directory: " + ec.message()};
  if (std::filesystem::exists(dir / kRecordingManifestName)) {
    return Error{dir.string() + ": already holds a recording (manifest.json exists)"};
  }
  std::unique_ptr<RecordingWriter> w(new RecordingWriter(dir, layout));
  const auto path = dir / kRecordingSamplesName;
  w->samples_.open(path, std::ios::binary | std::ios::trunc);
  if (!w->samples_) return Error{path.string() + ": cannot open for writing"};
  const std::string header = NpyHeaderBytes(0, layout.channels.size(), layout.samples_per_channel);
  w->samples_.write(header.data(), static_cast<std::streamsize>(header.size()));
  if (!w->samples_) return Error{path.string() + ": write error"};
  return w;
}

Status RecordingWriter::Append(const AccelBlockView& block) {
  if (closed_) return Error{dir_.string() + ": recording is closed"};
  if (std::string why = LayoutMismatch(layout_, block); !why.empty()) {
    return Error{"block " + std::to_string(block.sequence) + ": " + why};
  }
  const std::size_t values = layout_.channels.size() * std::size_t{layout_.samples_per_channel};
  if (block.samples.size() != values) {
    return Error{"block " + std::to_string(block.sequence) + ": holds " +
                 std::to_string(block.samples.size()) + " samples, expected " +
                 std::to_string(values)};
  }
  samples_.write(reinterpret_cast<const char*>(block.samples.data()),
                 static_cast<std::streamsize>(block.samples.size_bytes()));
  if (!samples_) return Error{(dir_ / kRecordingSamplesName).string() + ": write error"};
  blocks_.push_back({block.sequence, block.t0_ns, block.speed_hz, block.speed_source, block.load});
  return Status::Ok();
}

Status RecordingWriter::Close() {
  if (closed_) return Status::Ok();
  closed_ = true;
  const auto path = dir_ / kRecordingSamplesName;
  const std::string header =
      NpyHeaderBytes(blocks_.size(), layout_.channels.size(), layout_.samples_per_channel);
  samples_.seekp(0);
  samples_.write(header.data(), static_cast<std::streamsize>(header.size()));
  samples_.close();
  if (!samples_) return Error{path.string() + ": write error while finishing the header"};
  Status st = WriteManifest(dir_, ManifestOf(layout_, blocks_));
  if (!st) {
    // Without its manifest the samples are no recording: leave nothing half-written behind.
    std::error_code ec;
    std::filesystem::remove(path, ec);
    std::filesystem::remove(dir_ / (std::string(kRecordingManifestName) + ".tmp"), ec);
    return Error{st.error() + " (recording removed)"};
  }
  return st;
}

}  // namespace gearpath
