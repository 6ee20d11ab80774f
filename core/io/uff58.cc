#include "core/io/uff58.h"

#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <optional>
#include <system_error>

namespace gearpath {
namespace {

constexpr std::size_t kHeaderLines = 11;

std::string_view Trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r'))
    s.remove_suffix(1);
  return s;
}

// Columns [begin, begin + width) of a fixed-format line, clamped to the line.
std::string_view Columns(std::string_view line, std::size_t begin, std::size_t width) {
  if (begin >= line.size()) return {};
  return line.substr(begin, width);
}

std::optional<int> ParseInt(std::string_view field) {
  field = Trim(field);
  if (field.empty()) return 0;  // blank integer fields read as zero, as in Fortran
  if (field.front() == '+') field.remove_prefix(1);
  int value = 0;
  auto [end, ec] = std::from_chars(field.data(), field.data() + field.size(), value);
  if (ec != std::errc() || end != field.data() + field.size()) return std::nullopt;
  return value;
}

// Reads the numbers of a line in order. Works for fixed-width fields (even when they touch:
// "-1.00000E+00-2.00000E+00"), free format and Fortran D exponents.
class NumberScanner {
 public:
  explicit NumberScanner(std::string_view line) : text_(line) {
    std::replace(text_.begin(), text_.end(), 'D', 'E');
    std::replace(text_.begin(), text_.end(), 'd', 'e');
  }
  // False at the end of the line; sets *bad if something that is not a number is found.
  bool Next(double* value, bool* bad) {
    while (pos_ < text_.size() && (text_[pos_] == ' ' || text_[pos_] == '\t' ||
                                   text_[pos_] == '\r' || text_[pos_] == ',')) {
      ++pos_;
    }
    if (pos_ >= text_.size()) return false;
    if (text_[pos_] == '+') ++pos_;
    auto [end, ec] = std::from_chars(text_.data() + pos_, text_.data() + text_.size(), *value);
    if (ec != std::errc()) {
      *bad = true;
      return false;
    }
    pos_ = static_cast<std::size_t>(end - text_.data());
    return true;
  }

 private:
  std::string text_;
  std::size_t pos_ = 0;
};

class Cursor {
 public:
  explicit Cursor(std::string_view text) : text_(text) {}
  bool AtEnd() const { return pos_ >= text_.size(); }
  std::size_t line() const { return line_; }  // number of the last line returned (1-based)
  std::size_t pos() const { return pos_; }
  std::string_view rest() const { return text_.substr(pos_); }
  void Advance(std::size_t bytes) { pos_ += bytes; }

  bool NextLine(std::string_view* line) {
    if (AtEnd()) return false;
    const std::size_t end = text_.find('\n', pos_);
    const std::size_t stop = end == std::string_view::npos ? text_.size() : end;
    *line = text_.substr(pos_, stop - pos_);
    if (!line->empty() && line->back() == '\r') line->remove_suffix(1);
    pos_ = end == std::string_view::npos ? text_.size() : end + 1;
    ++line_;
    return true;
  }

  // Counts the lines of a raw byte range that was skipped (binary data), for messages.
  void CountLines(std::size_t from, std::size_t to) {
    line_ +=
        static_cast<std::size_t>(std::count(text_.begin() + static_cast<std::ptrdiff_t>(from),
                                            text_.begin() + static_cast<std::ptrdiff_t>(to), '\n'));
  }

 private:
  std::string_view text_;
  std::size_t pos_ = 0;
  std::size_t line_ = 0;
};

bool IsDelimiter(std::string_view line) { return Trim(line) == "-1"; }

struct Context {
  const std::string& name;
  Error At(std::size_t line, const std::string& what) const {
    return Error{name + ":" + std::to_string(line) + ": " + what};
  }
};

std::size_t ValuesPerRecord(const Uff58Record& r, std::size_t points) {
  return points * ((r.complex_ordinate ? 2 : 1) + (r.even_abscissa ? 0 : 1));
}

// Splits the flat record-12 value sequence into abscissa and ordinate.
void Distribute(const std::vector<double>& values, Uff58Record* r) {
  const std::size_t stride = (r->complex_ordinate ? 2 : 1) + (r->even_abscissa ? 0 : 1);
  const std::size_t n = values.size() / stride;
  r->ordinate.resize(n);
  if (!r->even_abscissa) r->abscissa.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double* v = &values[i * stride];
    if (!r->even_abscissa) r->abscissa[i] = *v++;
    r->ordinate[i] = {v[0], r->complex_ordinate ? v[1] : 0.0};
  }
}

std::optional<std::string> ParseAxisLine(std::string_view line, UffAxis* axis) {
  const auto type = ParseInt(Columns(line, 0, 10));
  const auto length = ParseInt(Columns(line, 10, 5));
  const auto force = ParseInt(Columns(line, 15, 5));
  const auto temperature = ParseInt(Columns(line, 20, 5));
  if (!type) return "specific data type (columns 1-10)";
  if (!length || !force || !temperature) return "unit exponents (columns 11-25)";
  axis->specific_data_type = *type;
  axis->length_exponent = *length;
  axis->force_exponent = *force;
  axis->temperature_exponent = *temperature;
  axis->label = std::string(Trim(Columns(line, 25, 21)));
  axis->unit_label = std::string(Trim(Columns(line, 46, 21)));
  return std::nullopt;
}

// Record 6, fixed columns (2(I5,I10),2(1X,10A1,I10,I4)); free format as a fallback.
bool ParseDofLine(std::string_view line, Uff58Record* r) {
  auto ft = ParseInt(Columns(line, 0, 5)), fid = ParseInt(Columns(line, 5, 10)),
       ver = ParseInt(Columns(line, 15, 5)), lc = ParseInt(Columns(line, 20, 10)),
       rn = ParseInt(Columns(line, 41, 10)), rd = ParseInt(Columns(line, 51, 4)),
       fn = ParseInt(Columns(line, 66, 10)), fd = ParseInt(Columns(line, 76, 4));
  if (ft && fid && ver && lc && rn && rd && fn && fd && !Trim(Columns(line, 0, 5)).empty()) {
    r->function_type = *ft;
    r->function_id = *fid;
    r->version = *ver;
    r->load_case = *lc;
    r->response_entity = std::string(Trim(Columns(line, 30, 11)));
    r->response_node = *rn;
    r->response_direction = *rd;
    r->reference_entity = std::string(Trim(Columns(line, 55, 11)));
    r->reference_node = *fn;
    r->reference_direction = *fd;
    return true;
  }
  std::vector<std::string_view> tokens;
  std::size_t pos = 0;
  while (pos < line.size()) {
    while (pos < line.size() && line[pos] == ' ') ++pos;
    const std::size_t start = pos;
    while (pos < line.size() && line[pos] != ' ') ++pos;
    if (pos > start) tokens.push_back(line.substr(start, pos - start));
  }
  if (tokens.size() != 10) return false;
  const int int_fields[] = {0, 1, 2, 3, 5, 6, 8, 9};
  int values[10] = {};
  for (int i : int_fields) {
    auto v = ParseInt(tokens[static_cast<std::size_t>(i)]);
    if (!v) return false;
    values[i] = *v;
  }
  r->function_type = values[0];
  r->function_id = values[1];
  r->version = values[2];
  r->load_case = values[3];
  r->response_entity = std::string(tokens[4]);
  r->response_node = values[5];
  r->response_direction = values[6];
  r->reference_entity = std::string(tokens[7]);
  r->reference_node = values[8];
  r->reference_direction = values[9];
  return true;
}

template <typename T>
T LoadSwapped(const char* p, bool swap) {
  using U = std::conditional_t<sizeof(T) == 4, std::uint32_t, std::uint64_t>;
  U bits;
  std::memcpy(&bits, p, sizeof bits);
  if (swap) {
    U out = 0;
    for (std::size_t i = 0; i < sizeof(U); ++i) out = (out << 8) | ((bits >> (8 * i)) & 0xff);
    bits = out;
  }
  return std::bit_cast<T>(bits);
}

Result<Uff58Record> ParseRecord(Cursor& cur, const Context& ctx, std::string_view type_line) {
  const std::size_t start_line = cur.line();
  Uff58Record r;
  bool binary = false;
  bool swap = false;
  std::size_t binary_bytes = 0;
  if (type_line.size() > 6 && (type_line[6] == 'b' || type_line[6] == 'B')) {
    binary = true;
    const auto order = ParseInt(Columns(type_line, 7, 6));
    const auto fp = ParseInt(Columns(type_line, 13, 6));
    const auto lines = ParseInt(Columns(type_line, 19, 12));
    const auto bytes = ParseInt(Columns(type_line, 31, 12));
    if (!order || (*order != 1 && *order != 2)) {
      return ctx.At(start_line,
                    "dataset 58b: byte ordering flag must be 1 (LSB first) or 2 "
                    "(MSB first), got '" +
                        std::string(Trim(Columns(type_line, 7, 6))) + "'");
    }
    if (!fp || *fp != 2) {
      return ctx.At(start_line, "dataset 58b: floating-point format '" +
                                    std::string(Trim(Columns(type_line, 13, 6))) +
                                    "' is not supported (only 2, IEEE 754)");
    }
    if (!lines || *lines != static_cast<int>(kHeaderLines)) {
      return ctx.At(start_line, "dataset 58b: expected 11 ASCII header lines, header says '" +
                                    std::string(Trim(Columns(type_line, 19, 12))) + "'");
    }
    if (!bytes || *bytes < 0) {
      return ctx.At(start_line, "dataset 58b: bad binary byte count '" +
                                    std::string(Trim(Columns(type_line, 31, 12))) + "'");
    }
    swap = (*order == 2) != (std::endian::native == std::endian::big);
    binary_bytes = static_cast<std::size_t>(*bytes);
  }
  std::string_view h[kHeaderLines];
  for (std::size_t i = 0; i < kHeaderLines; ++i) {
    if (!cur.NextLine(&h[i]) || IsDelimiter(h[i])) {
      return ctx.At(cur.line(), "dataset 58 starting at line " + std::to_string(start_line) +
                                    " ends inside its header (record " + std::to_string(i + 1) +
                                    " of 11 missing)");
    }
  }
  const std::size_t first = start_line + 1;  // line number of record 1
  for (std::size_t i = 0; i < 5; ++i) r.id_lines[i] = std::string(Trim(h[i]));
  if (!ParseDofLine(h[5], &r)) {
    return ctx.At(first + 5,
                  "record 6 (DOF identification): cannot read function type, "
                  "nodes and directions from '" +
                      std::string(h[5]) + "'");
  }
  const auto data_type = ParseInt(Columns(h[6], 0, 10));
  const auto points = ParseInt(Columns(h[6], 10, 10));
  const auto spacing = ParseInt(Columns(h[6], 20, 10));
  if (!data_type || (*data_type != 2 && *data_type != 4 && *data_type != 5 && *data_type != 6)) {
    return ctx.At(first + 6, "record 7: ordinate data type '" +
                                 std::string(Trim(Columns(h[6], 0, 10))) +
                                 "' is not supported (2 real single, 4 real double, 5 complex "
                                 "single, 6 complex double)");
  }
  if (!points || *points < 0) {
    return ctx.At(first + 6, "record 7: bad number of points '" +
                                 std::string(Trim(Columns(h[6], 10, 10))) + "'");
  }
  if (!spacing || (*spacing != 0 && *spacing != 1)) {
    return ctx.At(first + 6, "record 7: abscissa spacing must be 0 (uneven) or 1 (even), got '" +
                                 std::string(Trim(Columns(h[6], 20, 10))) + "'");
  }
  r.double_precision = *data_type == 4 || *data_type == 6;
  r.complex_ordinate = *data_type == 5 || *data_type == 6;
  r.even_abscissa = *spacing == 1;
  {
    NumberScanner scan(Columns(h[6], 30, std::string_view::npos));
    double v[3] = {0, 0, 0};
    bool bad = false;
    int n = 0;
    while (n < 3 && scan.Next(&v[n], &bad)) ++n;
    if (bad || n < 2) {
      return ctx.At(first + 6, "record 7: cannot read abscissa minimum and increment from '" +
                                   std::string(h[6]) + "'");
    }
    r.abscissa_start = v[0];
    r.abscissa_increment = v[1];
    r.z_axis_value = v[2];
  }
  UffAxis* axes[4] = {&r.abscissa_axis, &r.ordinate_axis, &r.denominator_axis, &r.z_axis};
  for (std::size_t i = 0; i < 4; ++i) {
    if (auto field = ParseAxisLine(h[7 + i], axes[i])) {
      return ctx.At(first + 7 + i, "record " + std::to_string(8 + i) + ": cannot read the " +
                                       *field + " from '" + std::string(h[7 + i]) + "'");
    }
  }

  const auto n = static_cast<std::size_t>(*points);
  const std::size_t count = ValuesPerRecord(r, n);
  // Every value takes at least one byte, so a count beyond the bytes left is a corrupt header
  // (checked before allocating for it).
  if (count > cur.rest().size()) {
    return ctx.At(first + 6, "record 7 announces " + std::to_string(n) + " points (" +
                                 std::to_string(count) + " values) but only " +
                                 std::to_string(cur.rest().size()) + " bytes follow");
  }
  std::vector<double> values;
  values.reserve(count);
  if (binary) {
    const std::size_t size = r.double_precision ? 8 : 4;
    if (binary_bytes != count * size) {
      return ctx.At(start_line, "dataset 58b: header announces " + std::to_string(binary_bytes) +
                                    " data bytes but record 7 (" + std::to_string(n) +
                                    " points, data type " + std::to_string(*data_type) +
                                    ") needs " + std::to_string(count * size));
    }
    const std::string_view rest = cur.rest();
    if (rest.size() < binary_bytes) {
      return ctx.At(cur.line(), "dataset 58b: truncated binary data: expected " +
                                    std::to_string(binary_bytes) + " bytes, got " +
                                    std::to_string(rest.size()));
    }
    for (std::size_t i = 0; i < count; ++i) {
      const char* p = rest.data() + i * size;
      values.push_back(r.double_precision ? LoadSwapped<double>(p, swap)
                                          : static_cast<double>(LoadSwapped<float>(p, swap)));
    }
    cur.CountLines(cur.pos(), cur.pos() + binary_bytes);
    cur.Advance(binary_bytes);
    // The closing delimiter may follow the data directly or after a line break.
    std::string_view tail;
    bool closed = false;
    while (cur.NextLine(&tail)) {
      if (Trim(tail).empty()) continue;
      closed = IsDelimiter(tail);
      break;
    }
    if (!closed) {
      return ctx.At(cur.line(), "dataset 58b starting at line " + std::to_string(start_line) +
                                    ": expected the closing '    -1' after " +
                                    std::to_string(binary_bytes) + " data bytes");
    }
  } else {
    std::string_view line;
    while (values.size() < count) {
      if (!cur.NextLine(&line) || IsDelimiter(line)) {
        return ctx.At(cur.line(), "dataset 58 starting at line " + std::to_string(start_line) +
                                      ": truncated data: expected " + std::to_string(count) +
                                      " values, got " + std::to_string(values.size()));
      }
      NumberScanner scan(line);
      double v = 0;
      bool bad = false;
      while (scan.Next(&v, &bad)) values.push_back(v);
      if (bad) {
        return ctx.At(cur.line(), "record 12: cannot read a number in '" + std::string(line) + "'");
      }
    }
    if (values.size() > count) {
      return ctx.At(cur.line(), "record 12: " + std::to_string(values.size()) +
                                    " values where record 7 announces " + std::to_string(count));
    }
    bool closed = false;
    while (cur.NextLine(&line)) {
      if (Trim(line).empty()) continue;
      closed = IsDelimiter(line);
      break;
    }
    if (!closed) {
      return ctx.At(cur.line(), "record 12: more data than the " + std::to_string(count) +
                                    " values record 7 announces (or missing closing '    -1')");
    }
  }
  Distribute(values, &r);
  return r;
}

std::string Fixed(const char* format, auto... args) {
  char buffer[160];
  std::snprintf(buffer, sizeof buffer, format, args...);
  return buffer;
}

std::string Pad80(const std::string& s) {
  std::string line = s.substr(0, 80);
  return line + std::string(80 - line.size(), ' ') + "\n";
}

std::string AxisLine(const UffAxis& a) {
  return Fixed("%10d%5d%5d%5d %-20.20s %-20.20s\n", a.specific_data_type, a.length_exponent,
               a.force_exponent, a.temperature_exponent, a.label.c_str(), a.unit_label.c_str());
}

// The flat record-12 value sequence, in the record's precision.
std::vector<double> Flatten(const Uff58Record& r) {
  std::vector<double> values;
  values.reserve(ValuesPerRecord(r, r.ordinate.size()));
  for (std::size_t i = 0; i < r.ordinate.size(); ++i) {
    if (!r.even_abscissa) values.push_back(r.abscissa[i]);
    values.push_back(r.ordinate[i].real());
    if (r.complex_ordinate) values.push_back(r.ordinate[i].imag());
  }
  return values;
}

std::string AsciiData(const Uff58Record& r, const std::vector<double>& values) {
  std::string out;
  auto put = [&](const char* format, double v) { out += Fixed(format, v); };
  if (!r.double_precision) {  // 6E13.5
    for (std::size_t i = 0; i < values.size(); ++i) {
      put("%13.5E", values[i]);
      if (i % 6 == 5 || i + 1 == values.size()) out += "\n";
    }
  } else if (r.even_abscissa) {  // 4E20.12
    for (std::size_t i = 0; i < values.size(); ++i) {
      put("%20.12E", values[i]);
      if (i % 4 == 3 || i + 1 == values.size()) out += "\n";
    }
  } else if (!r.complex_ordinate) {  // 2(E13.5,E20.12)
    for (std::size_t i = 0; i < values.size(); ++i) {
      put(i % 2 == 0 ? "%13.5E" : "%20.12E", values[i]);
      if (i % 4 == 3 || i + 1 == values.size()) out += "\n";
    }
  } else {  // E13.5,2E20.12
    for (std::size_t i = 0; i < values.size(); ++i) {
      put(i % 3 == 0 ? "%13.5E" : "%20.12E", values[i]);
      if (i % 3 == 2 || i + 1 == values.size()) out += "\n";
    }
  }
  return out;
}

}  // namespace

std::string UffFunctionTypeName(int function_type) {
  static constexpr const char* kNames[] = {"general or unknown",
                                           "time response",
                                           "auto spectrum",
                                           "cross spectrum",
                                           "frequency response function",
                                           "transmissibility",
                                           "coherence",
                                           "auto correlation",
                                           "cross correlation",
                                           "power spectral density",
                                           "energy spectral density",
                                           "probability density function",
                                           "spectrum",
                                           "cumulative frequency distribution",
                                           "peaks valley",
                                           "stress/cycles",
                                           "strain/cycles",
                                           "orbit",
                                           "mode indicator function",
                                           "force pattern",
                                           "partial power",
                                           "partial coherence",
                                           "eigenvalue",
                                           "eigenvector",
                                           "shock response spectrum",
                                           "finite impulse response filter",
                                           "multiple coherence",
                                           "order function"};
  if (function_type >= 0 && function_type < static_cast<int>(std::size(kNames))) {
    return kNames[function_type];
  }
  return "unknown function type";
}

std::string UffDirectionName(int direction) {
  if (direction == 0) return "scalar";
  const int magnitude = direction < 0 ? -direction : direction;
  static constexpr const char* kAxes[] = {"X", "Y", "Z", "RX", "RY", "RZ"};
  if (magnitude > 6) return "direction " + std::to_string(direction);
  return std::string(direction < 0 ? "-" : "+") + kAxes[magnitude - 1];
}

int Uff58Record::ordinate_data_type() const {
  if (complex_ordinate) return double_precision ? 6 : 5;
  return double_precision ? 4 : 2;
}

double Uff58Record::AbscissaAt(std::size_t i) const {
  if (!even_abscissa) return abscissa[i];
  return abscissa_start + static_cast<double>(i) * abscissa_increment;
}

Result<std::vector<Uff58Record>> ParseUff58(std::string_view contents, const std::string& name) {
  const Context ctx{name};
  Cursor cur(contents);
  std::vector<Uff58Record> records;
  std::string_view line;
  while (cur.NextLine(&line)) {
    if (Trim(line).empty()) continue;
    if (!IsDelimiter(line)) {
      return ctx.At(cur.line(),
                    "expected a dataset delimiter '    -1', got '" + std::string(Trim(line)) + "'");
    }
    std::string_view type_line;
    if (!cur.NextLine(&type_line)) {
      return ctx.At(cur.line(), "file ends after a dataset delimiter");
    }
    const std::string_view type_field = Trim(Columns(type_line, 0, 6));
    const auto type = ParseInt(type_field);
    if (!type || type_field.empty()) {
      return ctx.At(cur.line(),
                    "expected a dataset number, got '" + std::string(Trim(type_line)) + "'");
    }
    if (*type != 58) {  // not ours: skip to its closing delimiter
      bool closed = false;
      while (cur.NextLine(&line)) {
        if (IsDelimiter(line)) {
          closed = true;
          break;
        }
      }
      if (!closed)
        return ctx.At(cur.line(),
                      "dataset " + std::to_string(*type) + " is not closed by '    -1'");
      continue;
    }
    auto record = ParseRecord(cur, ctx, type_line);
    if (!record) return Error{record.error()};
    records.push_back(std::move(record.value()));
  }
  return records;
}

Result<std::vector<Uff58Record>> ReadUff58(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) return Error{file.string() + ": cannot open file"};
  std::error_code ec;
  const auto size = std::filesystem::file_size(file, ec);
  if (ec) return Error{file.string() + ": cannot stat file: " + ec.message()};
  std::string contents(size, '\0');
  in.read(contents.data(), static_cast<std::streamsize>(size));
  if (!in) return Error{file.string() + ": read error"};
  return ParseUff58(contents, file.string());
}

Status WriteUff58(const std::filesystem::path& file, std::span<const Uff58Record> records,
                  UffEncoding encoding) {
  std::string out;
  for (std::size_t k = 0; k < records.size(); ++k) {
    const Uff58Record& r = records[k];
    const std::string which = file.string() + ": record " + std::to_string(k) + ": ";
    if (!r.even_abscissa && r.abscissa.size() != r.ordinate.size()) {
      return Error{which + "uneven abscissa has " + std::to_string(r.abscissa.size()) +
                   " values for " + std::to_string(r.ordinate.size()) + " ordinate samples"};
    }
    if (!r.complex_ordinate) {
      for (std::size_t i = 0; i < r.ordinate.size(); ++i) {
        if (r.ordinate[i].imag() != 0.0) {
          return Error{which + "real ordinate has a nonzero imaginary part at sample " +
                       std::to_string(i)};
        }
      }
    }
    const std::vector<double> values = Flatten(r);
    const std::size_t size = r.double_precision ? 8 : 4;
    out += "    -1\n";
    if (encoding == UffEncoding::kBinary) {
      out += Fixed("%6d%c%6d%6d%12zu%12zu%6d%6d%12d%12d\n", 58, 'b', 1, 2, kHeaderLines,
                   values.size() * size, 0, 0, 0, 0);
    } else {
      out += "    58\n";
    }
    for (const auto& id : r.id_lines) out += Pad80(id);
    out += Fixed("%5d%10d%5d%10d %10.10s%10d%4d %10.10s%10d%4d\n", r.function_type, r.function_id,
                 r.version, r.load_case, r.response_entity.c_str(), r.response_node,
                 r.response_direction, r.reference_entity.c_str(), r.reference_node,
                 r.reference_direction);
    out += Fixed("%10d%10zu%10d%13.5E%13.5E%13.5E\n", r.ordinate_data_type(), r.ordinate.size(),
                 r.even_abscissa ? 1 : 0, r.even_abscissa ? r.abscissa_start : 0.0,
                 r.even_abscissa ? r.abscissa_increment : 0.0, r.z_axis_value);
    out += AxisLine(r.abscissa_axis) + AxisLine(r.ordinate_axis) + AxisLine(r.denominator_axis) +
           AxisLine(r.z_axis);
    if (encoding == UffEncoding::kBinary) {
      static_assert(std::endian::native == std::endian::little,
                    "the 58b writer declares little-endian data");
      for (double v : values) {
        if (r.double_precision) {
          out.append(reinterpret_cast<const char*>(&v), sizeof v);
        } else {
          const auto f = static_cast<float>(v);
          out.append(reinterpret_cast<const char*>(&f), sizeof f);
        }
      }
    } else {
      out += AsciiData(r, values);
    }
    out += "    -1\n";
  }
  std::ofstream stream(file, std::ios::binary | std::ios::trunc);
  if (!stream) return Error{file.string() + ": cannot open for writing"};
  stream.write(out.data(), static_cast<std::streamsize>(out.size()));
  stream.close();
  if (!stream) return Error{file.string() + ": write error"};
  return Status::Ok();
}

}  // namespace gearpath
