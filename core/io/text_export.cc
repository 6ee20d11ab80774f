#include "core/io/text_export.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <fstream>
#include <optional>
#include <sstream>
#include <tuple>

#include "core/io/json_read.h"

namespace gearpath {
namespace {

std::string Trim(std::string_view s) {
  std::size_t b = 0, e = s.size();
  while (b < e && std::isspace(static_cast<unsigned char>(s[b]))) ++b;
  while (e > b && std::isspace(static_cast<unsigned char>(s[e - 1]))) --e;
  std::string out(s.substr(b, e - b));
  if (out.size() >= 2 && out.front() == '"' && out.back() == '"')
    out = out.substr(1, out.size() - 2);
  return out;
}

std::string Lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

std::vector<std::string> Split(std::string_view line, char sep) {
  std::vector<std::string> out;
  if (sep == ' ') {
    std::size_t i = 0;
    while (i < line.size()) {
      while (i < line.size() && std::isspace(static_cast<unsigned char>(line[i]))) ++i;
      if (i >= line.size()) break;
      std::size_t j = i;
      while (j < line.size() && !std::isspace(static_cast<unsigned char>(line[j]))) ++j;
      out.push_back(std::string(line.substr(i, j - i)));
      i = j;
    }
    return out;
  }
  std::size_t start = 0;
  for (;;) {
    const std::size_t pos = line.find(sep, start);
    out.push_back(Trim(line.substr(start, pos == std::string_view::npos ? pos : pos - start)));
    if (pos == std::string_view::npos) break;
    start = pos + 1;
  }
  // A trailing separator (common in spreadsheet exports) adds no column.
  if (out.size() > 1 && out.back().empty()) out.pop_back();
  return out;
}

std::optional<double> ParseNumber(std::string field, bool decimal_comma) {
  field = Trim(field);
  if (field.empty()) return std::nullopt;
  if (decimal_comma) std::replace(field.begin(), field.end(), ',', '.');
  const char* first = field.data();
  if (*first == '+') ++first;
  double v = 0;
  auto [ptr, ec] = std::from_chars(first, field.data() + field.size(), v);
  if (ec != std::errc() || ptr != field.data() + field.size()) return std::nullopt;
  return v;
}

bool IsNumericRow(const std::vector<std::string>& fields, bool decimal_comma) {
  if (fields.empty()) return false;
  for (const std::string& f : fields) {
    if (!ParseNumber(f, decimal_comma)) return false;
  }
  return true;
}

// A units-row field: empty, bracketed, or a short token that reads like a unit.
bool LooksLikeUnit(std::string f) {
  f = Trim(f);
  if (f.empty() || f == "-") return true;
  if ((f.front() == '[' && f.back() == ']') || (f.front() == '(' && f.back() == ')')) return true;
  const std::string l = Lower(f);
  static const char* const kUnits[] = {
      "g",      "s",   "ms",   "hz", "v",  "mv", "n",  "pa",    "m/s^2", "m/s2", "m/s**2", "m/s²",
      "mm/s^2", "m/s", "mm/s", "m",  "mm", "um", "µm", "ms^-2", "ms-2",  "rpm",  "sec"};
  for (const char* u : kUnits) {
    if (l == u) return true;
  }
  return l.find('/') != std::string::npos && l.size() <= 12;
}

// Strips a trailing "[unit]" or "(unit)" from a name (but not "(X)", an axis).
std::string StripUnit(const std::string& name, std::string* unit) {
  const std::string t = Trim(name);
  if (t.size() >= 3 && (t.back() == ']' || t.back() == ')')) {
    const char open = t.back() == ']' ? '[' : '(';
    const std::size_t pos = t.rfind(open);
    if (pos != std::string::npos && pos > 0) {
      const std::string inside = Trim(t.substr(pos + 1, t.size() - pos - 2));
      const std::string l = Lower(inside);
      if (!(open == '(' && (l == "x" || l == "y" || l == "z"))) {
        if (unit) *unit = inside;
        return Trim(t.substr(0, pos));
      }
    }
  }
  return t;
}

bool IsTimeName(const std::string& name, const std::string& unit) {
  const std::string l = Lower(StripUnit(name, nullptr));
  if (l == "time" || l == "t" || l == "s" || l == "zeit" || l == "time(s)" || l == "time/s" ||
      l == "times" || l == "时间" || l == "x") {
    return l != "x" || Lower(unit) == "s";
  }
  const std::string u = Lower(unit);
  return (u == "s" || u == "sec") && (l.empty() || l.find("time") != std::string::npos);
}

std::optional<double> FirstNumberIn(const std::string& text, bool decimal_comma) {
  // The first token that parses as a number (with either decimal mark when unambiguous).
  std::string token;
  std::vector<std::string> tokens;
  for (char c : text) {
    if (std::isdigit(static_cast<unsigned char>(c)) || c == '.' || c == ',' || c == '-' ||
        c == '+' || c == 'e' || c == 'E') {
      token += c;
    } else {
      if (!token.empty()) tokens.push_back(token);
      token.clear();
    }
  }
  if (!token.empty()) tokens.push_back(token);
  for (const std::string& t : tokens) {
    if (auto v = ParseNumber(t, decimal_comma)) return v;
    if (auto v = ParseNumber(t, !decimal_comma)) return v;
  }
  return std::nullopt;
}

// The sample rate a metadata line states (rate or interval), if any.
std::optional<double> RateFromMetadata(const std::string& line, bool decimal_comma) {
  const std::string l = Lower(line);
  const std::size_t key_end = l.find_first_of(":=\t;,");
  if (key_end == std::string::npos) return std::nullopt;
  const std::string key = Trim(l.substr(0, key_end));
  const std::string value = l.substr(key_end + 1);
  const bool is_rate = key.find("sample rate") != std::string::npos ||
                       key.find("sampling rate") != std::string::npos ||
                       key.find("sampling frequency") != std::string::npos ||
                       key.find("sample frequency") != std::string::npos ||
                       key.find("samplerate") != std::string::npos || key == "fs" ||
                       key.find("采样频率") != std::string::npos;
  const bool is_interval = key.find("interval") != std::string::npos || key == "dt" ||
                           key == "delta t" || key.find("increment") != std::string::npos;
  if (!is_rate && !is_interval) return std::nullopt;
  std::optional<double> v = FirstNumberIn(value, decimal_comma);
  if (!v || !(*v > 0)) return std::nullopt;
  if (is_rate) {
    if (value.find("khz") != std::string::npos) *v *= 1e3;
    return *v;
  }
  if (value.find("ms") != std::string::npos)
    *v *= 1e-3;
  else if (value.find("us") != std::string::npos || value.find("µs") != std::string::npos)
    *v *= 1e-6;
  return 1.0 / *v;
}

}  // namespace

bool SplitChannelName(const std::string& name, std::string* sensor, Axis* axis) {
  const std::string t = Trim(name);
  *sensor = t;
  *axis = Axis::kX;
  if (t.size() < 2) return false;
  std::size_t end = t.size();
  char a = 0;
  if (t.back() == ')' && t.size() >= 4 && t[t.size() - 3] == '(') {
    a = t[t.size() - 2];
    end = t.size() - 3;
  } else {
    a = t.back();
    end = t.size() - 1;
    // "A1X" is sensor A1 axis X only after a digit; otherwise a separator is required.
    const char before = t[end - 1];
    const bool separated = before == '-' || before == '_' || before == ' ' || before == '.' ||
                           before == ':' || before == '/';
    if (!separated && !std::isdigit(static_cast<unsigned char>(before))) return false;
  }
  const char la = static_cast<char>(std::tolower(static_cast<unsigned char>(a)));
  if (la != 'x' && la != 'y' && la != 'z') return false;
  while (end > 0 && (t[end - 1] == '-' || t[end - 1] == '_' || t[end - 1] == ' ' ||
                     t[end - 1] == '.' || t[end - 1] == ':' || t[end - 1] == '/')) {
    --end;
  }
  if (end == 0) return false;
  *sensor = t.substr(0, end);
  *axis = la == 'x' ? Axis::kX : la == 'y' ? Axis::kY : Axis::kZ;
  return true;
}

double NormaliseAccelerationUnit(std::string* unit) {
  const std::string l = Lower(Trim(*unit));
  if (l == "m/s^2" || l == "m/s2" || l == "m/s**2" || l == "m/s²" || l == "ms^-2" || l == "ms-2" ||
      l == "m s^-2") {
    *unit = "m/s^2";
    return 1.0;
  }
  if (l == "g") {
    *unit = "m/s^2";
    return 9.80665;
  }
  if (l == "mm/s^2" || l == "mm/s2" || l == "mm/s²") {
    *unit = "m/s^2";
    return 1e-3;
  }
  return 1.0;
}

Result<TextExport> ReadTextExport(const std::filesystem::path& file,
                                  const TextExportOptions& options) {
  std::ifstream in(file, std::ios::binary);
  if (!in) return Error{file.string() + ": cannot open"};
  std::ostringstream text;
  text << in.rdbuf();
  return ParseTextExport(text.str(), file.string(), options);
}

Result<TextExport> ParseTextExport(std::string_view contents, const std::string& name,
                                   const TextExportOptions& options) {
  if (contents.substr(0, 3) == "\xEF\xBB\xBF") contents.remove_prefix(3);  // UTF-8 BOM
  std::vector<std::string> lines;
  {
    std::size_t start = 0;
    while (start <= contents.size()) {
      std::size_t pos = contents.find('\n', start);
      std::string_view line = contents.substr(
          start, pos == std::string_view::npos ? std::string_view::npos : pos - start);
      if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
      lines.emplace_back(line);
      if (pos == std::string_view::npos) break;
      start = pos + 1;
    }
  }
  auto blank = [](const std::string& l) { return Trim(l).empty(); };
  std::size_t last = lines.size();
  while (last > 0 && blank(lines[last - 1])) --last;
  if (last == 0) return Error{name + ": the file is empty"};
  const std::string& probe = lines[last - 1];

  TextExport out;
  TextExportLayout& layout = out.layout;
  if (probe.find('\t') != std::string::npos)
    layout.separator = '\t';
  else if (probe.find(';') != std::string::npos)
    layout.separator = ';';
  else if (probe.find(',') != std::string::npos)
    layout.separator = ',';
  else
    layout.separator = ' ';
  layout.decimal_comma = layout.separator != ',' && probe.find(',') != std::string::npos;
  const char sep = layout.separator;
  const bool dc = layout.decimal_comma;

  const std::vector<std::string> probe_fields = Split(probe, sep);
  if (!IsNumericRow(probe_fields, dc)) {
    return Error{name + ": line " + std::to_string(last) +
                 ": the last row is not numeric, so no data rows were found (expected a header, "
                 "then one numeric column per channel)"};
  }
  const std::size_t ncols = probe_fields.size();
  // Data: the numeric rows of ncols fields at the end of the file (blank lines skipped).
  std::size_t first = last;
  while (first > 0) {
    const std::string& l = lines[first - 1];
    if (blank(l)) {
      --first;
      continue;
    }
    std::vector<std::string> f = Split(l, sep);
    if (f.size() != ncols || !IsNumericRow(f, dc)) break;
    --first;
  }
  while (first < last && blank(lines[first])) ++first;
  layout.first_data_line = first + 1;

  // Header: names row (required) and optional units row just above the data.
  std::vector<std::size_t> header;  // line indices with ncols fields, nearest first
  for (std::size_t i = first; i > 0 && header.size() < 2; --i) {
    if (blank(lines[i - 1])) continue;
    if (Split(lines[i - 1], sep).size() == ncols)
      header.push_back(i - 1);
    else
      break;
  }
  if (header.empty()) {
    return Error{name + ": line " + std::to_string(first) + ": no names row with " +
                 std::to_string(ncols) +
                 " columns above the data (the header must name every column)"};
  }
  std::vector<std::string> names, units(ncols);
  std::size_t names_line = header[0];
  {
    const std::vector<std::string> nearest = Split(lines[header[0]], sep);
    const bool unit_like =
        std::all_of(nearest.begin(), nearest.end(), LooksLikeUnit) && !IsNumericRow(nearest, dc);
    if (unit_like && header.size() == 2) {
      layout.units_row = true;
      for (std::size_t c = 0; c < ncols; ++c) {
        std::string u = Trim(nearest[c]);
        if (u.size() >= 2 && (u.front() == '[' || u.front() == '(')) u = u.substr(1, u.size() - 2);
        units[c] = u;
      }
      names_line = header[1];
    }
  }
  names = Split(lines[names_line], sep);
  if (IsNumericRow(names, dc)) {
    return Error{name + ": line " + std::to_string(names_line + 1) +
                 ": the header row is numeric; a names row is required"};
  }
  // Names and units become channel names and units in recordings and JSON reports, which
  // must be UTF-8: a Latin-1 or GBK export is refused here, naming the cell, rather than
  // failing later with a JSON exception (or being silently mangled).
  for (std::size_t c = 0; c < ncols; ++c) {
    for (const auto& [row, text, what] :
         {std::tuple{names_line, &names[c], "channel name"},
          std::tuple{header[0], &units[c], "unit"}}) {
      if (auto why = Utf8Problem(*text)) {
        return Error{name + ": line " + std::to_string(row + 1) + ", column " +
                     std::to_string(c + 1) + ": the " + what + " is not valid UTF-8 (" + *why +
                     "); save the export as UTF-8, e.g. with iconv -f latin1 -t utf-8"};
      }
    }
  }
  for (std::size_t c = 0; c < ncols; ++c) {
    std::string unit;
    names[c] = StripUnit(names[c], &unit);
    if (units[c].empty()) units[c] = unit;
  }

  // Data into columns.
  std::vector<std::vector<double>> columns(ncols);
  for (std::size_t i = first; i < last; ++i) {
    if (blank(lines[i])) continue;
    const std::vector<std::string> f = Split(lines[i], sep);
    for (std::size_t c = 0; c < ncols; ++c) {
      const double v = *ParseNumber(f[c], dc);
      if (!std::isfinite(v)) {
        return Error{name + ": line " + std::to_string(i + 1) + ", column " +
                     std::to_string(c + 1) + " (" + names[c] + "): non-finite value"};
      }
      columns[c].push_back(v);
    }
  }
  const std::size_t n = columns[0].size();

  // Time column.
  std::optional<double> time_rate;
  if (IsTimeName(names[0], units[0])) {
    const std::vector<double>& t = columns[0];
    for (std::size_t k = 1; k < n; ++k) {
      if (!(t[k] > t[k - 1])) {
        return Error{name + ": column 1 (" + names[0] +
                     ") is named as time but does not increase strictly at data row " +
                     std::to_string(k + 1) + " (line " + std::to_string(first + k + 1) + ")"};
      }
    }
    if (ncols < 2) return Error{name + ": only a time column, no channel"};
    layout.time_column = true;
    out.acquisition.start_time_s = t[0];
    if (n >= 2) time_rate = static_cast<double>(n - 1) / (t[n - 1] - t[0]);
  }

  // Sample rate.
  std::optional<double> header_rate;
  for (std::size_t i = 0; i < names_line; ++i) {
    if (auto r = RateFromMetadata(lines[i], dc)) {
      header_rate = r;
      break;
    }
  }
  if (options.sample_rate_hz > 0) header_rate = options.sample_rate_hz;
  double rate = 0;
  if (header_rate && time_rate) {
    if (std::abs(*header_rate - *time_rate) > 1e-6 * *header_rate) {
      return Error{name + ": the header's sample rate " + std::to_string(*header_rate) +
                   " Hz disagrees with the time column's " + std::to_string(*time_rate) + " Hz"};
    }
    rate = *header_rate;
    layout.sample_rate_from = "header and time column";
  } else if (header_rate) {
    rate = *header_rate;
    layout.sample_rate_from = options.sample_rate_hz > 0 ? "option" : "header";
  } else if (time_rate) {
    rate = *time_rate;
    layout.sample_rate_from = "time column";
  } else {
    return Error{name +
                 ": no sample rate: the header states none (e.g. \"Sample rate: 2560 Hz\") "
                 "and there is no time column"};
  }

  ContinuousAcquisition& acq = out.acquisition;
  acq.sample_rate_hz = rate;
  acq.samples_per_channel = n;
  const std::size_t c0 = layout.time_column ? 1 : 0;
  acq.samples.reserve((ncols - c0) * n);
  for (std::size_t c = c0; c < ncols; ++c) {
    ChannelInfo info;
    SplitChannelName(names[c], &info.sensor, &info.axis);
    if (info.sensor.empty()) info.sensor = "ch" + std::to_string(c + 1);
    info.unit = units[c].empty() ? "m/s^2" : units[c];
    const double scale = NormaliseAccelerationUnit(&info.unit);
    acq.channels.push_back(info);
    acq.column_names.push_back(names[c]);
    for (double v : columns[c]) acq.samples.push_back(static_cast<float>(v * scale));
  }
  return out;
}

}  // namespace gearpath
