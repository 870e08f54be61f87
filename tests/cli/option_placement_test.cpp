// An option on the wrong side of the subcommand is named with where it goes: a subcommand's option
// placed before it (`glintlab --threads 2 verify`) says it goes after; an option no subcommand on
// the line takes is still an unknown option. (The reverse, `glintlab models --plugin X`, is
// ErrorTest.PluginAfterTheSubcommandIsNamed.)
#include <gtest/gtest.h>

#include <string>

#include "cli/cli_test_util.h"

namespace glintlab::cli_test {
namespace {

class OptionPlacementTest : public CliTest {};

TEST_F(OptionPlacementTest, SubcommandsOptionBeforeItSaysItGoesAfter) {
  expect_input_error(run({"--threads", "2", "verify", "--list"}),
                     {"--threads goes after the subcommand", "glintlab verify --threads"}, {});
  expect_input_error(run({"--threads=2", "verify", "--list"}),
                     {"--threads goes after the subcommand", "glintlab verify --threads"}, {});
  expect_input_error(run({"--model", "smooth_ggx", "eval", "--in", "q.csv", "--out", "r.csv"}),
                     {"--model goes after the subcommand", "glintlab eval --model"}, {});
  // --budget belongs to verify but not to sample: for sample it is an unknown option.
  expect_input_error(run({"--budget", "quick", "sample"}),
                     {"unknown option '--budget' before the subcommand", "--plugin PATH"}, {});
  expect_input_error(run({"--budget", "quick", "verify", "--list"}),
                     {"--budget goes after the subcommand", "glintlab verify --budget"}, {});
}

TEST_F(OptionPlacementTest, OptionNoSubcommandTakesIsUnknown) {
  for (const std::vector<std::string>& args :
       std::vector<std::vector<std::string>>{{"--bogus", "verify"}, {"--threads", "2"}, {"-x"}}) {
    const RunResult r = run(args);
    expect_input_error(r, {"unknown option '" + args[0] + "' before the subcommand"}, {});
    EXPECT_EQ(r.err.find("goes after"), std::string::npos) << r.err;
  }
}

}  // namespace
}  // namespace glintlab::cli_test
