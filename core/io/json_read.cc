#include "core/io/json_read.h"

#include <cerrno>
#include <cstring>
#include <fstream>

namespace gearpath {
namespace {

// nlohmann's messages start "[json.exception.parse_error.101] parse error at line 1, column 3: ";
// the position is given by the caller in gearpath's own form, so keep only the reason.
std::string Reason(const char* what) {
  std::string_view s(what);
  if (s.starts_with("[json.exception.")) {
    const auto end = s.find("] ");
    if (end != std::string_view::npos) s.remove_prefix(end + 2);
  }
  if (s.starts_with("parse error")) {
    const auto colon = s.find(": ");
    if (colon != std::string_view::npos) s.remove_prefix(colon + 2);
  }
  return std::string(s);
}

// The DOM builder of nlohmann::json::parse, plus the byte position and reason of the first
// error (the exception-free parse path otherwise only says "discarded").
template <typename Json>
class PositionedDomParser : public nlohmann::detail::json_sax_dom_parser<Json> {
 public:
  explicit PositionedDomParser(Json& result)
      : nlohmann::detail::json_sax_dom_parser<Json>(result, /*allow_exceptions_=*/false) {}

  template <typename Exception>
  bool parse_error(std::size_t position, const std::string& last_token, const Exception& ex) {
    if (!failed) {
      failed = true;
      error_position = position;
      error = Reason(ex.what());
      if (ex.id == 406) error += " (too large for a double)";
    }
    return nlohmann::detail::json_sax_dom_parser<Json>::parse_error(position, last_token, ex);
  }

  bool failed = false;
  std::size_t error_position = 0;
  std::string error;
};

}  // namespace

std::optional<std::size_t> JsonDepthExceededAt(std::string_view text,
                                               std::size_t max_depth) noexcept {
  std::size_t depth = 0;
  bool in_string = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      if (c == '\\') {
        ++i;  // the escaped character, '"' included, never ends the string
      } else if (c == '"') {
        in_string = false;
      }
      continue;
    }
    if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      if (++depth > max_depth) return i;
    } else if ((c == ']' || c == '}') && depth > 0) {
      --depth;
    }
  }
  return std::nullopt;
}

std::string TextPosition(std::string_view text, std::size_t offset) {
  std::size_t line = 1;
  std::size_t column = 1;
  for (std::size_t i = 0; i < offset && i < text.size(); ++i) {
    if (text[i] == '\n') {
      ++line;
      column = 1;
    } else {
      ++column;
    }
  }
  return "line " + std::to_string(line) + ", column " + std::to_string(column);
}

template <typename Json>
Result<Json> ParseJson(std::string_view text, std::string_view origin,
                       const JsonReadLimits& limits) {
  const std::string where = std::string(origin) + ": not valid JSON";
  if (text.size() > limits.max_bytes) {
    return Error{where + ": " + std::to_string(text.size()) + " bytes, over the limit of " +
                 std::to_string(limits.max_bytes) + " for this file"};
  }
  if (const auto at = JsonDepthExceededAt(text, limits.max_depth)) {
    return Error{where + ": " + TextPosition(text, *at) + ": nested deeper than " +
                 std::to_string(limits.max_depth) +
                 " levels of arrays and objects (gearpath's limit for its files)"};
  }
  Json result;
  PositionedDomParser<Json> sax(result);
  try {
    const bool ok = Json::sax_parse(text.begin(), text.end(), &sax,
                                    nlohmann::json::input_format_t::json, /*strict=*/true,
                                    /*ignore_comments=*/false);
    if (!ok || sax.failed) {
      // The lexer's position counts the bytes read, so the culprit ends just before it.
      const std::size_t at = sax.error_position > 0 ? sax.error_position - 1 : 0;
      return Error{where + ": " + TextPosition(text, at) + ": " +
                   (sax.error.empty() ? std::string("not valid JSON") : sax.error)};
    }
  } catch (const nlohmann::json::exception& e) {  // not expected with allow_exceptions off
    return Error{where + ": " + Reason(e.what())};
  } catch (const std::bad_alloc&) {
    return Error{where + ": out of memory while parsing"};
  }
  return result;
}

Result<std::string> ReadTextFile(const std::filesystem::path& path, std::size_t max_bytes) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return Error{path.string() + ": cannot open: " + std::strerror(errno)};
  // Read at most max_bytes + 1 so that a FIFO or a device cannot make us read forever.
  std::string text;
  char buffer[65536];
  while (in && text.size() <= max_bytes) {
    in.read(buffer, sizeof buffer);
    text.append(buffer, static_cast<std::size_t>(in.gcount()));
  }
  if (in.bad()) return Error{path.string() + ": read error"};
  if (text.size() > max_bytes) {
    return Error{path.string() + ": larger than " + std::to_string(max_bytes) +
                 " bytes, the limit for this file"};
  }
  return text;
}

template <typename Json>
Result<Json> ReadJsonFile(const std::filesystem::path& path, const JsonReadLimits& limits) {
  Result<std::string> text = ReadTextFile(path, limits.max_bytes);
  if (!text) return Error{text.error()};
  return ParseJson<Json>(*text, path.string(), limits);
}

template <typename Json>
Result<std::string> DumpJson(const Json& value, int indent, std::string_view what) {
  try {
    return value.dump(indent);
  } catch (const nlohmann::json::exception& e) {
    return Error{std::string(what) + ": " + Reason(e.what()) + " (text must be UTF-8)"};
  }
}

std::optional<std::string> Utf8Problem(std::string_view text) {
  // nlohmann's strict dump is the UTF-8 validator (it names the byte and its index).
  try {
    (void)nlohmann::json(std::string(text)).dump();
  } catch (const nlohmann::json::exception& e) {
    return Reason(e.what());
  }
  return std::nullopt;
}

template Result<nlohmann::json> ParseJson<nlohmann::json>(std::string_view, std::string_view,
                                                          const JsonReadLimits&);
template Result<nlohmann::ordered_json> ParseJson<nlohmann::ordered_json>(std::string_view,
                                                                          std::string_view,
                                                                          const JsonReadLimits&);
template Result<nlohmann::json> ReadJsonFile<nlohmann::json>(const std::filesystem::path&,
                                                             const JsonReadLimits&);
template Result<nlohmann::ordered_json> ReadJsonFile<nlohmann::ordered_json>(
    const std::filesystem::path&, const JsonReadLimits&);
template Result<std::string> DumpJson<nlohmann::json>(const nlohmann::json&, int, std::string_view);
template Result<std::string> DumpJson<nlohmann::ordered_json>(const nlohmann::ordered_json&, int,
                                                              std::string_view);

}  // namespace gearpath
