// Text exports of a DH8303-class acquisition (Donghua DHDAS and similar): header, then one column
// per channel. The accepted layout and its variants are documented in docs/tools.md ("Text
// exports"); in short:
//
//   optional metadata lines     "Sample rate: 2560 Hz", "Fs;2,56 kHz", "Sampling interval = 1e-4 s"
//   names row                   "Time;A1-X;A1-Y;A2-Z"      (one name per column, required)
//   optional units row          "s;m/s^2;m/s^2;g"          (or units in the names: "A1-X [g]")
//   data rows                   "0,0000;0,0123;0,0456;-1,2e-3"
//
// Separator: tab, semicolon, comma, or runs of spaces (detected on the last data row: tab, then
// semicolon, then comma, then spaces). Decimal comma: detected when the separator is not a comma
// and the data rows hold commas (so "0,0123;0,0456" reads as 0.0123 and 0.0456). An optional
// time column: the first column when its name is a time name ("Time", "t", "s", "time [s]"...,
// or its unit is "s") and its values increase strictly. Sample rate: from the header metadata
// (rate or interval), else from the time column ((n-1) / (t_last - t_first)); when both exist
// they must agree to 1e-6 relative (a mismatch names both values). Channel names "A1-X",
// "A1_y", "A1 Z", "A1.x", "A1(X)" give sensor "A1" and an axis; other names become the sensor
// with axis x. Acceleration units are normalised to m/s^2 ("g" scaled by 9.80665, "mm/s^2" by
// 1e-3); other units are kept as written. Errors name the file, the line and the column.
//
// Configuration-time code (loads a whole file): allocates, returns Result.
#pragma once

#include <cstddef>
#include <filesystem>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "core/common/accel_block.h"
#include "core/common/result.h"

namespace gearpath {

// Continuous samples of simultaneously sampled channels (what a text export or a UFF time
// history holds; replay cuts it into blocks).
struct ContinuousAcquisition {
  double sample_rate_hz = 0.0;
  double start_time_s = 0.0;  // the time column's first value; 0 without one
  std::vector<ChannelInfo> channels;
  std::vector<std::string> column_names;  // as written in the names row, per channel
  std::size_t samples_per_channel = 0;
  std::vector<float> samples;  // planar: channel 0's samples, then channel 1's...

  std::span<const float> channel(std::size_t c) const {
    return std::span<const float>(samples).subspan(c * samples_per_channel, samples_per_channel);
  }
};

// What the reader found out about the file's layout (reported by `gearpath inspect`/`replay`).
struct TextExportLayout {
  char separator = ',';  // '\t', ';', ',' or ' ' (runs of spaces)
  bool decimal_comma = false;
  bool time_column = false;
  bool units_row = false;
  std::size_t first_data_line = 0;  // 1-based
  std::string sample_rate_from;     // "header", "time column" or "header and time column"
};

struct TextExport {
  ContinuousAcquisition acquisition;
  TextExportLayout layout;
};

struct TextExportOptions {
  double sample_rate_hz = 0.0;  // > 0: use this rate (overrides the header, not the time column)
};

Result<TextExport> ReadTextExport(const std::filesystem::path& file,
                                  const TextExportOptions& options = {});
// Same, from the contents in memory; `name` is used in messages.
Result<TextExport> ParseTextExport(std::string_view contents, const std::string& name,
                                   const TextExportOptions& options = {});

// "A1-X" -> {"A1", kX}; a name without a recognisable axis -> {name, kX} and false.
bool SplitChannelName(const std::string& name, std::string* sensor, Axis* axis);

// Normalises an acceleration unit: sets *unit to "m/s^2" and returns the factor that converts
// values in the written unit to it; other units are left as written with factor 1.
double NormaliseAccelerationUnit(std::string* unit);

}  // namespace gearpath
