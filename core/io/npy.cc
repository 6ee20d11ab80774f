#include "core/io/npy.h"

#include <bit>
#include <cstring>
#include <fstream>
#include <limits>
#include <string_view>
#include <system_error>

namespace gearpath {
namespace {

static_assert(std::endian::native == std::endian::little,
              "the .npy reader assumes a little-endian host");

constexpr char kMagic[] = "\x93NUMPY";
constexpr std::size_t kMagicSize = 6;
constexpr std::size_t kAlignment = 64;

template <typename T>
struct DtypeOf;
template <>
struct DtypeOf<std::complex<double>> {
  static constexpr NpyDtype kValue = NpyDtype::kComplex128;
};
template <>
struct DtypeOf<double> {
  static constexpr NpyDtype kValue = NpyDtype::kFloat64;
};
template <>
struct DtypeOf<float> {
  static constexpr NpyDtype kValue = NpyDtype::kFloat32;
};
template <>
struct DtypeOf<std::int16_t> {
  static constexpr NpyDtype kValue = NpyDtype::kInt16;
};
template <>
struct DtypeOf<std::int32_t> {
  static constexpr NpyDtype kValue = NpyDtype::kInt32;
};

// The canonical little-endian descr NumPy writes for each dtype.
const char* CanonicalDescr(NpyDtype dtype) {
  switch (dtype) {
    case NpyDtype::kComplex128:
      return "<c16";
    case NpyDtype::kFloat64:
      return "<f8";
    case NpyDtype::kFloat32:
      return "<f4";
    case NpyDtype::kInt16:
      return "<i2";
    case NpyDtype::kInt32:
      return "<i4";
  }
  return "?";
}

// True if `descr` denotes `dtype` in little-endian (or native, on this little-endian host) order.
bool DescrMatches(std::string_view descr, NpyDtype dtype) {
  if (descr.size() < 2) return false;
  const char order = descr.front();
  if (order != '<' && order != '=' && order != '|') return false;
  return descr.substr(1) == std::string_view(CanonicalDescr(dtype)).substr(1);
}

Error FileError(const std::filesystem::path& file, const std::string& what) {
  return Error{file.string() + ": " + what};
}

// Parser for the header dict, a Python literal of a fixed, small grammar.
class HeaderParser {
 public:
  explicit HeaderParser(std::string_view text) : text_(text) {}

  // On failure returns false and sets *why.
  bool Parse(NpyHeader* header, std::string* why) {
    bool have_descr = false, have_order = false, have_shape = false;
    SkipSpace();
    if (!Consume('{')) return Fail("header is not a dict (expected '{')", why);
    while (true) {
      SkipSpace();
      if (Consume('}')) break;
      std::string key;
      if (!ParseString(&key)) return Fail("expected a quoted key in the header dict", why);
      SkipSpace();
      if (!Consume(':')) return Fail("expected ':' after key '" + key + "'", why);
      SkipSpace();
      if (key == "descr") {
        if (!ParseString(&header->descr)) return Fail("'descr' must be a quoted string", why);
        have_descr = true;
      } else if (key == "fortran_order") {
        if (ConsumeWord("True")) {
          header->fortran_order = true;
        } else if (ConsumeWord("False")) {
          header->fortran_order = false;
        } else {
          return Fail("'fortran_order' must be True or False", why);
        }
        have_order = true;
      } else if (key == "shape") {
        if (!ParseShape(&header->shape)) return Fail("'shape' must be a tuple of integers", why);
        have_shape = true;
      } else {
        return Fail("unexpected key '" + key + "' in the header dict", why);
      }
      SkipSpace();
      if (Consume(',')) continue;
      SkipSpace();
      if (Consume('}')) break;
      return Fail("expected ',' or '}' in the header dict", why);
    }
    if (!have_descr) return Fail("header dict lacks 'descr'", why);
    if (!have_order) return Fail("header dict lacks 'fortran_order'", why);
    if (!have_shape) return Fail("header dict lacks 'shape'", why);
    return true;
  }

 private:
  static bool Fail(const std::string& message, std::string* why) {
    *why = message;
    return false;
  }
  void SkipSpace() {
    while (pos_ < text_.size() && (text_[pos_] == ' ' || text_[pos_] == '\t' ||
                                   text_[pos_] == '\n' || text_[pos_] == '\r')) {
      ++pos_;
    }
  }
  bool Consume(char c) {
    if (pos_ < text_.size() && text_[pos_] == c) {
      ++pos_;
      return true;
    }
    return false;
  }
  bool ConsumeWord(std::string_view word) {
    if (text_.substr(pos_, word.size()) == word) {
      pos_ += word.size();
      return true;
    }
    return false;
  }
  bool ParseString(std::string* out) {
    if (pos_ >= text_.size() || (text_[pos_] != '\'' && text_[pos_] != '"')) return false;
    const char quote = text_[pos_++];
    const std::size_t end = text_.find(quote, pos_);
    if (end == std::string_view::npos) return false;
    *out = std::string(text_.substr(pos_, end - pos_));
    pos_ = end + 1;
    return true;
  }
  bool ParseShape(std::vector<std::size_t>* shape) {
    shape->clear();
    if (!Consume('(')) return false;
    while (true) {
      SkipSpace();
      if (Consume(')')) return true;
      std::size_t value = 0;
      bool any_digit = false;
      while (pos_ < text_.size() && text_[pos_] >= '0' && text_[pos_] <= '9') {
        const auto digit = static_cast<std::size_t>(text_[pos_] - '0');
        if (value > (std::numeric_limits<std::size_t>::max() - digit) / 10) return false;
        value = value * 10 + digit;
        any_digit = true;
        ++pos_;
      }
      if (!any_digit) return false;
      ConsumeWord("L");  // Python 2 long suffix, harmless to accept
      shape->push_back(value);
      SkipSpace();
      if (Consume(',')) continue;
      SkipSpace();
      if (Consume(')')) return true;
      return false;
    }
  }

  std::string_view text_;
  std::size_t pos_ = 0;
};

std::string ShapeString(const std::vector<std::size_t>& shape) {
  std::string s = "(";
  for (std::size_t i = 0; i < shape.size(); ++i) {
    s += std::to_string(shape[i]);
    if (shape.size() == 1 || i + 1 < shape.size()) s += shape.size() == 1 ? "," : ", ";
  }
  return s + ")";
}

// Reorders Fortran-order elements into C order.
template <typename T>
std::vector<T> FortranToC(const std::vector<T>& f, const std::vector<std::size_t>& shape) {
  const std::size_t n = f.size();
  const std::size_t rank = shape.size();
  if (rank < 2 || n == 0) return f;
  std::vector<std::size_t> f_stride(rank, 1);
  for (std::size_t d = 1; d < rank; ++d) f_stride[d] = f_stride[d - 1] * shape[d - 1];
  std::vector<std::size_t> index(rank, 0);
  std::vector<T> c(n);
  for (std::size_t linear = 0; linear < n; ++linear) {
    std::size_t offset = 0;
    for (std::size_t d = 0; d < rank; ++d) offset += index[d] * f_stride[d];
    c[linear] = f[offset];
    for (std::size_t d = rank; d-- > 0;) {  // advance the C-order multi-index
      if (++index[d] < shape[d]) break;
      index[d] = 0;
    }
  }
  return c;
}

}  // namespace

const char* NpyDtypeName(NpyDtype dtype) noexcept {
  switch (dtype) {
    case NpyDtype::kComplex128:
      return "complex128";
    case NpyDtype::kFloat64:
      return "float64";
    case NpyDtype::kFloat32:
      return "float32";
    case NpyDtype::kInt16:
      return "int16";
    case NpyDtype::kInt32:
      return "int32";
  }
  return "unknown";
}

std::size_t NpyHeader::element_count() const {
  std::size_t n = 1;
  for (std::size_t d : shape) n *= d;
  return n;
}

Result<NpyHeader> ReadNpyHeader(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) return FileError(file, "cannot open file");
  char prefix[kMagicSize + 2];
  in.read(prefix, sizeof prefix);
  if (in.gcount() < static_cast<std::streamsize>(sizeof prefix) ||
      std::memcmp(prefix, kMagic, kMagicSize) != 0) {
    return FileError(file, "bad magic: not a NumPy .npy file (expected \\x93NUMPY)");
  }
  NpyHeader header;
  header.major_version = static_cast<unsigned char>(prefix[6]);
  header.minor_version = static_cast<unsigned char>(prefix[7]);
  std::size_t length_bytes = 0;
  if (header.major_version == 1) {
    length_bytes = 2;
  } else if (header.major_version == 2 || header.major_version == 3) {
    length_bytes = 4;
  } else {
    return FileError(file, "unsupported .npy version " + std::to_string(header.major_version) +
                               "." + std::to_string(header.minor_version) +
                               " (supported: 1.0, 2.0, 3.0)");
  }
  unsigned char length_raw[4] = {0, 0, 0, 0};
  in.read(reinterpret_cast<char*>(length_raw), static_cast<std::streamsize>(length_bytes));
  if (in.gcount() < static_cast<std::streamsize>(length_bytes)) {
    return FileError(file, "truncated header: file ends inside the header length");
  }
  std::size_t header_length = 0;
  for (std::size_t i = length_bytes; i-- > 0;) header_length = (header_length << 8) | length_raw[i];
  std::string text(header_length, '\0');
  in.read(text.data(), static_cast<std::streamsize>(header_length));
  if (static_cast<std::size_t>(in.gcount()) < header_length) {
    return FileError(file, "truncated header: expected " + std::to_string(header_length) +
                               " header bytes, got " + std::to_string(in.gcount()));
  }
  std::string why;
  if (!HeaderParser(text).Parse(&header, &why)) return FileError(file, "bad header: " + why);
  header.data_offset = kMagicSize + 2 + length_bytes + header_length;
  return header;
}

template <typename T>
Result<NpyArray<T>> ReadNpy(const std::filesystem::path& file) {
  constexpr NpyDtype kDtype = DtypeOf<T>::kValue;
  auto header = ReadNpyHeader(file);
  if (!header) return Error{header.error()};
  if (!DescrMatches(header->descr, kDtype)) {
    return FileError(file, "unsupported dtype '" + header->descr + "' (expected " +
                               NpyDtypeName(kDtype) + ", '" + CanonicalDescr(kDtype) + "')");
  }
  // Guard the element count against overflow before trusting it.
  std::size_t count = 1;
  for (std::size_t d : header->shape) {
    if (d != 0 && count > std::numeric_limits<std::size_t>::max() / sizeof(T) / d) {
      return FileError(file, "shape " + ShapeString(header->shape) + " is too large");
    }
    count *= d;
  }
  const std::size_t expected = count * sizeof(T);
  std::error_code ec;
  const std::uintmax_t file_size = std::filesystem::file_size(file, ec);
  if (ec) return FileError(file, "cannot stat file: " + ec.message());
  const std::uintmax_t got = file_size > header->data_offset ? file_size - header->data_offset : 0;
  if (got < expected) {
    return FileError(file, "truncated data: expected " + std::to_string(expected) +
                               " bytes for shape " + ShapeString(header->shape) + ", got " +
                               std::to_string(got));
  }
  if (got > expected) {
    return FileError(file, "unexpected " + std::to_string(got - expected) +
                               " trailing bytes after the " + std::to_string(expected) +
                               " data bytes of shape " + ShapeString(header->shape));
  }
  NpyArray<T> array;
  array.shape = header->shape;
  array.data.resize(count);
  std::ifstream in(file, std::ios::binary);
  in.seekg(static_cast<std::streamoff>(header->data_offset));
  in.read(reinterpret_cast<char*>(array.data.data()), static_cast<std::streamsize>(expected));
  if (!in) return FileError(file, "read error in the data section");
  if (header->fortran_order) array.data = FortranToC(array.data, array.shape);
  return array;
}

template <typename T>
Status WriteNpy(const std::filesystem::path& file, std::span<const T> data,
                const std::vector<std::size_t>& shape) {
  constexpr NpyDtype kDtype = DtypeOf<T>::kValue;
  std::size_t count = 1;
  for (std::size_t d : shape) count *= d;
  if (count != data.size()) {
    return FileError(file, "cannot write: shape " + ShapeString(shape) + " holds " +
                               std::to_string(count) + " elements but " +
                               std::to_string(data.size()) + " were given");
  }
  std::string dict = std::string("{'descr': '") + CanonicalDescr(kDtype) +
                     "', 'fortran_order': False, 'shape': " + ShapeString(shape) + ", }";
  // Pad with spaces and a final newline so that the data starts on a 64-byte boundary.
  auto padded = [&](std::size_t prefix) {
    const std::size_t unpadded = prefix + dict.size() + 1;
    return dict + std::string((kAlignment - unpadded % kAlignment) % kAlignment, ' ') + "\n";
  };
  std::string header = padded(kMagicSize + 2 + 2);
  int major = 1;
  if (header.size() > std::numeric_limits<std::uint16_t>::max()) {
    major = 2;
    header = padded(kMagicSize + 2 + 4);
  }
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  if (!out) return FileError(file, "cannot open for writing");
  out.write(kMagic, kMagicSize);
  const char version[2] = {static_cast<char>(major), 0};
  out.write(version, 2);
  const std::size_t length_bytes = major == 1 ? 2 : 4;
  for (std::size_t i = 0; i < length_bytes; ++i) {
    out.put(static_cast<char>((header.size() >> (8 * i)) & 0xff));
  }
  out.write(header.data(), static_cast<std::streamsize>(header.size()));
  out.write(reinterpret_cast<const char*>(data.data()),
            static_cast<std::streamsize>(data.size() * sizeof(T)));
  out.close();
  if (!out) return FileError(file, "write error");
  return Status::Ok();
}

#define GEARPATH_NPY_INSTANTIATE(T)                                             \
  template Result<NpyArray<T>> ReadNpy<T>(const std::filesystem::path&);        \
  template Status WriteNpy<T>(const std::filesystem::path&, std::span<const T>, \
                              const std::vector<std::size_t>&);
GEARPATH_NPY_INSTANTIATE(std::complex<double>)
GEARPATH_NPY_INSTANTIATE(double)
GEARPATH_NPY_INSTANTIATE(float)
GEARPATH_NPY_INSTANTIATE(std::int16_t)
GEARPATH_NPY_INSTANTIATE(std::int32_t)
#undef GEARPATH_NPY_INSTANTIATE

}  // namespace gearpath
