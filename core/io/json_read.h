// Bounded JSON reading and non-throwing JSON writing: the one place where gearpath turns text
// into nlohmann::json (daemon configuration, FRF set and recording manifests) and back.
//
// Why: nlohmann::json throws on bad input (parse_error, out_of_range 406 for a number that
// overflows a double such as 1e999, type_error 316 when dumping a string that is not UTF-8),
// and although its parser is iterative, copying, comparing and dumping a parsed value recurse
// once per nesting level, so a value nested ~100 000 deep overflows the stack later on. Every
// reader therefore goes through ParseJson / ReadJsonFile, which
//   - caps the text size (ReadJsonFile reads at most max_bytes),
//   - bounds the nesting depth with a linear scan that skips strings and escapes, before
//     nlohmann sees the text (kMaxJsonDepth = 64 levels by default; gearpath's deepest
//     document, the daemon configuration, nests 6),
//   - parses without exceptions and reports any error as
//     "<origin>: not valid JSON: line L, column C: why".
// DumpJson is the matching writer: a string that is not valid UTF-8 gives an error naming the
// offending byte instead of an exception.
//
// Configuration-time code: allocates, never throws a json exception.
#pragma once

#include <cstddef>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>

#include "core/common/result.h"

namespace gearpath {

// Deepest nesting (arrays and objects) a configuration or manifest may use.
inline constexpr std::size_t kMaxJsonDepth = 64;
// Largest configuration or FRF set manifest read (far above any real one: a few kB).
inline constexpr std::size_t kMaxJsonFileBytes = std::size_t{16} << 20;

struct JsonReadLimits {
  std::size_t max_depth = kMaxJsonDepth;
  std::size_t max_bytes = kMaxJsonFileBytes;
};

// Byte offset at which `text` first nests deeper than `max_depth` arrays/objects, if it does.
// Linear, allocation-free; brackets inside strings (escapes included) do not count.
std::optional<std::size_t> JsonDepthExceededAt(std::string_view text,
                                               std::size_t max_depth) noexcept;

// "line L, column C" (1-based) of byte `offset` in `text`.
std::string TextPosition(std::string_view text, std::size_t offset);

// Parses `text` (nlohmann::json or nlohmann::ordered_json). Errors read
// "<origin>: not valid JSON: line L, column C: <why>" and never escape as exceptions.
template <typename Json = nlohmann::json>
Result<Json> ParseJson(std::string_view text, std::string_view origin,
                       const JsonReadLimits& limits = {});

// Reads the file at `path` (at most limits.max_bytes) and parses it; `origin` in messages is
// the path.
Result<std::string> ReadTextFile(const std::filesystem::path& path, std::size_t max_bytes);
template <typename Json = nlohmann::json>
Result<Json> ReadJsonFile(const std::filesystem::path& path, const JsonReadLimits& limits = {});

// value.dump(indent) without exceptions: a string that is not UTF-8 gives an error naming the
// byte, prefixed with `what`.
template <typename Json = nlohmann::json>
Result<std::string> DumpJson(const Json& value, int indent, std::string_view what);

// Why `text` is not valid UTF-8 ("invalid UTF-8 byte at index 3: 0xE9"), or nothing.
std::optional<std::string> Utf8Problem(std::string_view text);

}  // namespace gearpath
