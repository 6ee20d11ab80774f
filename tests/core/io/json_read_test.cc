// Bounded JSON reading: every hostile input is a Result error naming the place, never an
// exception, an abort or a stack overflow.
#include "core/io/json_read.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <string>

#include "tests/core/io/io_test_util.h"

namespace gearpath {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

std::string Nested(std::size_t depth) { return std::string(depth, '[') + std::string(depth, ']'); }

TEST(JsonRead, ParsesAValidDocument) {
  auto j = ParseJson<json>(R"({"a": [1, 2.5, "x"], "b": {"c": null}})", "t.json");
  ASSERT_TRUE(j.ok()) << j.error();
  EXPECT_EQ((*j)["a"][1], 2.5);
}

TEST(JsonRead, RejectsANumberThatOverflowsADoubleNamingLineAndColumn) {
  auto j = ParseJson<json>("{\n  \"x\": 1e999\n}", "cfg.json");
  ASSERT_FALSE(j.ok());
  EXPECT_EQ(j.error(),
            "cfg.json: not valid JSON: line 2, column 12: number overflow parsing '1e999' "
            "(too large for a double)");
}

TEST(JsonRead, RejectsOverflowInAnOrderedJsonToo) {
  auto j = ParseJson<nlohmann::ordered_json>("[-1e400]", "m.json");
  ASSERT_FALSE(j.ok());
  EXPECT_TRUE(Contains(j.error(), "m.json: not valid JSON: line 1, column"));
  EXPECT_TRUE(Contains(j.error(), "number overflow parsing '-1e400'"));
}

TEST(JsonRead, AcceptsNestingUpToTheLimitAndRejectsOneLevelMore) {
  EXPECT_TRUE(ParseJson<json>(Nested(kMaxJsonDepth), "t.json").ok());
  auto j = ParseJson<json>(Nested(kMaxJsonDepth + 1), "t.json");
  ASSERT_FALSE(j.ok());
  EXPECT_EQ(j.error(),
            "t.json: not valid JSON: line 1, column 65: nested deeper than 64 levels of arrays "
            "and objects (gearpath's limit for its files)");
}

TEST(JsonRead, RejectsAHundredThousandLevelsWithoutOverflowingTheStack) {
  for (std::size_t depth : {50'000u, 100'000u}) {
    auto j = ParseJson<nlohmann::ordered_json>(Nested(depth), "deep.json");
    ASSERT_FALSE(j.ok());
    EXPECT_TRUE(Contains(j.error(), "nested deeper than 64 levels"));
  }
}

TEST(JsonRead, BracketsInsideStringsAndEscapesDoNotCountAsNesting) {
  const std::string text = "{\"k\": \"" + std::string(200, '[') + "\\\"" + std::string(200, '{') +
                           "\", \"e\": \"\\\\\", \"z\": [1]}";
  auto j = ParseJson<json>(text, "t.json");
  ASSERT_TRUE(j.ok()) << j.error();
  EXPECT_EQ((*j)["z"][0], 1);
}

TEST(JsonRead, RejectsNonUtf8InputNamingItsPosition) {
  auto j = ParseJson<json>("{\"name\": \"A\xE9\"}", "t.json");
  ASSERT_FALSE(j.ok());
  EXPECT_TRUE(Contains(j.error(), "t.json: not valid JSON: line 1, column"));
  EXPECT_TRUE(Contains(j.error(), "UTF-8"));
}

TEST(JsonRead, RejectsTruncatedAndEmptyInput) {
  EXPECT_TRUE(Contains(ParseJson<json>("{\"a\": ", "t.json").error(), "t.json: not valid JSON"));
  EXPECT_TRUE(Contains(ParseJson<json>("", "t.json").error(), "t.json: not valid JSON"));
}

TEST(JsonRead, RejectsTextOverTheSizeCap) {
  auto j = ParseJson<json>("[1, 2, 3]", "t.json", {kMaxJsonDepth, 4});
  ASSERT_FALSE(j.ok());
  EXPECT_EQ(j.error(), "t.json: not valid JSON: 9 bytes, over the limit of 4 for this file");
}

TEST(JsonRead, ReadsAFileAndCapsItsSize) {
  const fs::path file =
      fs::temp_directory_path() / ("gearpath_json_read_" + std::to_string(::getpid()) + ".json");
  WriteFileBytes(file, "{\"a\": 1}");
  auto j = ReadJsonFile<json>(file);
  ASSERT_TRUE(j.ok()) << j.error();
  EXPECT_EQ((*j)["a"], 1);
  auto capped = ReadJsonFile<json>(file, {kMaxJsonDepth, 3});
  ASSERT_FALSE(capped.ok());
  EXPECT_EQ(capped.error(), file.string() + ": larger than 3 bytes, the limit for this file");
  fs::remove(file);
  EXPECT_TRUE(Contains(ReadJsonFile<json>(file).error(), file.string() + ": cannot open"));
}

TEST(JsonRead, DumpOfANonUtf8StringIsAnErrorNamingTheByte) {
  json j = {{"name", "A\xFF-X"}};
  auto text = DumpJson(j, 2, "report");
  ASSERT_FALSE(text.ok());
  EXPECT_EQ(text.error(), "report: invalid UTF-8 byte at index 1: 0xFF (text must be UTF-8)");
  j["name"] = "A1-X";
  ASSERT_TRUE(DumpJson(j, -1, "report").ok());
  EXPECT_EQ(*DumpJson(j, -1, "report"), "{\"name\":\"A1-X\"}");
}

TEST(JsonRead, Utf8ProblemNamesTheFirstBadByte) {
  EXPECT_FALSE(Utf8Problem("Beschleunigung \xC3\xA4 \xE5\x8A\xA0").has_value());
  EXPECT_EQ(Utf8Problem("ab\xFF").value_or(""), "invalid UTF-8 byte at index 2: 0xFF");
}

}  // namespace
}  // namespace gearpath
