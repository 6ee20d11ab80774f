// The `gearpath` command line itself: --version, and command-line errors named by their
// subcommand with exit code 2 (issue 12: CLI11's own messages had no prefix, and a range check
// printed DBL_MAX in full).
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "tests/tools/tool_process.h"

namespace gearpath::tools::testing {
namespace {

class GearpathCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ =
        std::filesystem::temp_directory_path() / ("gearpath_cli_test_" + std::to_string(getpid()));
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::filesystem::path dir_;
};

TEST_F(GearpathCli, VersionPrintsTheProjectVersionAndExitsZero) {
  std::string out;
  ASSERT_EQ(RunTool({"--version"}, dir_, "version", &out), 0);
  EXPECT_EQ(out, std::string("gearpath ") + GEARPATH_VERSION + "\n");
}

TEST_F(GearpathCli, CommandLineErrorsNameTheSubcommandAndExitTwo) {
  struct Case {
    std::vector<std::string> args;
    std::string first_line;
  };
  const Case cases[] = {
      {{"evaluate", "--threads", "abc"},
       "gearpath evaluate: --threads: expected a number >= 0, got 'abc'"},
      {{"evaluate", "--sample", "0"},
       "gearpath evaluate: --sample: expected a number > 0, got '0'"},
      {{"sim", "--noise", "-0.1"}, "gearpath sim: --noise: expected a number >= 0, got '-0.1'"},
      {{"evaluate", "--bogus"},
       "gearpath evaluate: The following argument was not expected: --bogus"},
      {{}, "gearpath: A subcommand is required"},
  };
  int i = 0;
  for (const Case& c : cases) {
    std::string err;
    EXPECT_EQ(RunTool(c.args, dir_, "case" + std::to_string(i++), nullptr, &err), 2) << err;
    EXPECT_EQ(err.substr(0, err.find('\n')), c.first_line);
    EXPECT_NE(err.find("--help' for more information."), std::string::npos) << err;
  }
}

}  // namespace
}  // namespace gearpath::tools::testing
