// Bad input: every kind exits 2, prints exactly one line "glintlab: error: <message>" naming the
// parameter (and, for CSV input, the file and 1-based data row) and its valid range, and leaves
// no output file and no temporary file behind.
#include <gtest/gtest-spi.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "cli/cli_test_util.h"

namespace glintlab::cli_test {
namespace {

const std::string kHeader = "ndf,alpha_x,alpha_y,wi_x,wi_y,wi_z,wo_x,wo_y,wo_z\n";
const std::string kGoodRow = "ggx,0.3,0.3,0,0.6,0.8,0.6,0,0.8\n";

using ErrorTest = CliTest;

// --- The leftover-file check itself can fail ----------------------------------------------------

TEST_F(ErrorTest, LeftoverCheckDetectsAPartialOrTemporaryFile) {
  write_text(path("q.csv"), kHeader);
  EXPECT_EQ(unexpected_files(work(), {"q.csv"}), std::vector<std::string>{});
  // Leftovers a broken implementation could leave: a temporary file and a partial output.
  write_text(path("r.csv.tmp.12345"), "ndf,alpha_x");
  write_text(path("r.csv"), "ndf,alpha_x");
  EXPECT_EQ(unexpected_files(work(), {"q.csv"}),
            (std::vector<std::string>{"r.csv", "r.csv.tmp.12345"}));
  // And expect_input_error reports them as a failure.
  RunResult fake;
  fake.exit_code = 2;
  fake.err = "glintlab: error: --in something\n";
  EXPECT_NONFATAL_FAILURE(expect_input_error(fake, {"--in"}, {"q.csv"}),
                          "a failed run left files behind");
}

TEST_F(ErrorTest, LeftoverCheckDetectsTheOutputOfARealRun) {
  write_text(path("q.csv"), kHeader + kGoodRow);
  ASSERT_EQ(run({"eval", "--in", "q.csv", "--out", "r.csv"}).exit_code, 0);
  EXPECT_EQ(unexpected_files(work(), {"q.csv"}), std::vector<std::string>{"r.csv"});
}

TEST_F(ErrorTest, LeftoverCheckFlagsWrongExitCodeAndMissingName) {
  write_text(path("q.csv"), kHeader);
  RunResult fake;
  fake.exit_code = 1;
  fake.err = "glintlab: error: --in something\n";
  EXPECT_NONFATAL_FAILURE(expect_input_error(fake, {"--in"}, {"q.csv"}), "exit_code");
  fake.exit_code = 2;
  EXPECT_NONFATAL_FAILURE(expect_input_error(fake, {"--out"}, {"q.csv"}), "message lacks");
}

// --- eval: CSV content
// ----------------------------------------------------------------------------

struct BadRow {
  std::string name;
  std::string row;                   // data row 2 of the file (row 1 is good)
  std::vector<std::string> needles;  // expected in the message, besides file and row
};

TEST_F(ErrorTest, EvalBadRowsNameColumnRowFileAndRange) {
  const std::vector<BadRow> bad = {
      {"unknown ndf", "phong,0.3,0.3,0,0,1,0,0,1\n", {"column ndf", "'phong'", "ggx, beckmann"}},
      {"alpha_x zero", "ggx,0,0.3,0,0,1,0,0,1\n", {"column alpha_x", "finite and > 0"}},
      {"alpha_y negative",
       "beckmann,0.3,-0.2,0,0,1,0,0,1\n",
       {"column alpha_y", "-0.2", "finite and > 0"}},
      {"alpha inf", "ggx,inf,0.3,0,0,1,0,0,1\n", {"column alpha_x", "'inf' is not finite"}},
      {"alpha nan", "ggx,0.3,nan,0,0,1,0,0,1\n", {"column alpha_y", "'nan' is not finite"}},
      {"alpha overflow",
       "ggx,1e400,0.3,0,0,1,0,0,1\n",
       {"column alpha_x", "'1e400' is outside the range of a double"}},
      {"wi not unit", "ggx,0.3,0.3,0,0.6,0.9,0,0,1\n", {"wi_x,wi_y,wi_z", "length 1.0816", "1e-6"}},
      {"wo not unit", "ggx,0.3,0.3,0,0,1,0,0,1.00001\n", {"wo_x,wo_y,wo_z", "length 1.00001"}},
      {"wo zero", "ggx,0.3,0.3,0,0,1,0,0,0\n", {"wo_x,wo_y,wo_z", "length 0"}},
      {"too few fields", "ggx,0.3,0.3,0,0,1,0,0\n", {"8 fields", "expected 9"}},
      {"too many fields", "ggx,0.3,0.3,0,0,1,0,0,1,5\n", {"10 fields", "expected 9"}},
      {"unparsable", "ggx,0.3,0.3,0,0,1,0,zero,1\n", {"column wo_y", "'zero'", "not a number"}},
      {"trailing junk", "ggx,0.3,0.3x,0,0,1,0,0,1\n", {"column alpha_y", "'0.3x'"}},
      {"empty field", "ggx,0.3,,0,0,1,0,0,1\n", {"column alpha_y", "empty field"}},
      {"blank line", "\n" + kGoodRow, {"1 field", "expected 9"}},
      {"quoted", "\"ggx\",0.3,0.3,0,0,1,0,0,1\n", {"quote"}},
  };
  for (const BadRow& b : bad) {
    SCOPED_TRACE(b.name);
    write_text(path("q.csv"), kHeader + kGoodRow + b.row);
    const RunResult r = run({"eval", "--in", "q.csv", "--out", "r.csv"});
    std::vector<std::string> needles = b.needles;
    needles.push_back("--in");
    needles.push_back("'q.csv' data row 2");
    expect_input_error(r, needles, {"q.csv"});
  }
}

TEST_F(ErrorTest, EvalBadRowAfterManyGoodRowsWritesNothing) {
  std::string text = kHeader;
  for (int i = 0; i < 1000; ++i) text += kGoodRow;
  text += "ggx,0.3,0.3,0,0,1,0,0,2\n";
  write_text(path("q.csv"), text);
  const RunResult r = run({"eval", "--in", "q.csv", "--out", "r.csv"});
  expect_input_error(r, {"--in", "'q.csv' data row 1001", "wo", "length 2"}, {"q.csv"});
}

TEST_F(ErrorTest, EvalFailureKeepsAnExistingOutputFileUntouched) {
  write_text(path("q.csv"), kHeader + "ggx,-1,0.3,0,0,1,0,0,1\n");
  write_text(path("r.csv"), "previous results\n");
  const RunResult r = run({"eval", "--in", "q.csv", "--out", "r.csv"});
  expect_input_error(r, {"column alpha_x", "data row 1"}, {"q.csv", "r.csv"});
  EXPECT_EQ(read_text(path("r.csv")), "previous results\n");
}

TEST_F(ErrorTest, EvalHeaderProblems) {
  struct Case {
    std::string name, header;
    std::vector<std::string> needles;
  };
  const std::vector<Case> cases = {
      {"extra column",
       "ndf,alpha_x,alpha_y,wi_x,wi_y,wi_z,wo_x,wo_y,wo_z,eta\n",
       {"header row", "unknown column(s) 'eta'", "valid: exactly the columns"}},
      {"missing column",
       "ndf,alpha_x,wi_x,wi_y,wi_z,wo_x,wo_y,wo_z\n",
       {"header row", "missing column(s) alpha_y"}},
      {"duplicate column",
       "ndf,alpha_x,alpha_y,wi_x,wi_y,wi_z,wo_x,wo_y,wo_z,wo_z\n",
       {"header row", "'wo_z' appears more than once"}},
      {"empty file", "", {"empty", "header"}},
      {"empty column name",
       "ndf,alpha_x,,alpha_y,wi_x,wi_y,wi_z,wo_x,wo_y,wo_z\n",
       {"header row", "column 3 has an empty name"}},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    write_text(path("q.csv"), c.header);
    const RunResult r = run({"eval", "--in", "q.csv", "--out", "r.csv"});
    std::vector<std::string> needles = c.needles;
    needles.push_back("--in 'q.csv'");
    expect_input_error(r, needles, {"q.csv"});
  }
}

TEST_F(ErrorTest, EvalMissingInputFile) {
  const RunResult r = run({"eval", "--in", "missing.csv", "--out", "r.csv"});
  expect_input_error(r, {"--in", "'missing.csv'", "No such file"}, {});
}

TEST_F(ErrorTest, EvalInputIsADirectory) {
  std::filesystem::create_directory(path("dir"));
  const RunResult r = run({"eval", "--in", "dir", "--out", "r.csv"});
  expect_input_error(r, {"--in", "'dir'", "directory"}, {"dir"});
}

TEST_F(ErrorTest, EvalMissingRequiredOption) {
  write_text(path("q.csv"), kHeader + kGoodRow);
  expect_input_error(run({"eval", "--in", "q.csv"}), {"--out", "required"}, {"q.csv"});
  expect_input_error(run({"eval", "--out", "r.csv"}), {"--in", "required"}, {"q.csv"});
}

TEST_F(ErrorTest, EvalUnwritableOutput) {
  write_text(path("q.csv"), kHeader + kGoodRow);
  // A directory that does not exist: the temporary file cannot even be opened.
  expect_input_error(run({"eval", "--in", "q.csv", "--out", "nodir/r.csv"}),
                     {"--out", "nodir/r.csv"}, {"q.csv"});
  // An existing directory: the temporary file is written, then the rename fails and the
  // temporary file must be removed.
  std::filesystem::create_directory(path("outdir"));
  expect_input_error(run({"eval", "--in", "q.csv", "--out", "outdir"}), {"--out", "outdir"},
                     {"q.csv", "outdir"});
}

// --- sample: arguments
// ----------------------------------------------------------------------------

struct BadArgs {
  std::string name;
  std::vector<std::string> args;  // replacements for the defaults below
  std::vector<std::string> needles;
};

std::vector<std::string> sample_args(const std::vector<std::string>& overrides) {
  // Defaults: a valid run. Each override "--opt=value" replaces "--opt"; "--opt" alone drops it.
  std::vector<std::pair<std::string, std::string>> opts = {
      {"--ndf", "ggx"}, {"--alpha", "0.3"}, {"--wi", "0,0.6,0.8"}, {"--sampler", "vndf"},
      {"--n", "10"},    {"--seed", "1"},    {"--out", "s.csv"}};
  std::vector<std::pair<std::string, std::string>> extra;
  for (const std::string& o : overrides) {
    const std::size_t eq = o.find('=');
    const std::string key = o.substr(0, eq);
    bool found = false;
    for (auto it = opts.begin(); it != opts.end(); ++it) {
      if (it->first == key) {
        found = true;
        if (eq == std::string::npos) {
          opts.erase(it);
        } else {
          it->second = o.substr(eq + 1);
        }
        break;
      }
    }
    if (!found) extra.emplace_back(key, eq == std::string::npos ? "" : o.substr(eq + 1));
  }
  std::vector<std::string> args = {"sample"};
  for (const auto& [k, v] : opts) args.push_back(k + "=" + v);
  for (const auto& [k, v] : extra) args.push_back(v.empty() ? k : k + "=" + v);
  return args;
}

TEST_F(ErrorTest, SampleDefaultsAreValid) {
  const RunResult r = run(sample_args({}));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(unexpected_files(work(), {"s.csv"}), std::vector<std::string>{});
}

TEST_F(ErrorTest, SampleBadArguments) {
  const std::vector<BadArgs> bad = {
      {"unknown ndf", {"--ndf=phong"}, {"--ndf", "'phong'", "valid: ggx, beckmann"}},
      {"unknown sampler",
       {"--sampler=importance"},
       {"--sampler", "'importance'", "valid: ndf, vndf, spherical_caps, bounded_caps"}},
      {"spherical_caps on beckmann",
       {"--ndf=beckmann", "--sampler=spherical_caps"},
       {"--sampler", "'spherical_caps'", "only --ndf ggx", "valid for --ndf beckmann: ndf, vndf"}},
      {"bounded_caps on beckmann",
       {"--ndf=beckmann", "--sampler=bounded_caps"},
       {"--sampler", "'bounded_caps'", "valid for --ndf beckmann: ndf, vndf"}},
      {"alpha zero", {"--alpha=0"}, {"--alpha", "finite and > 0"}},
      {"alpha_y negative", {"--alpha=0.3,-0.1"}, {"--alpha (alpha_y)", "-0.1", "finite and > 0"}},
      {"alpha inf", {"--alpha=inf"}, {"--alpha", "'inf'", "finite"}},
      {"alpha three values", {"--alpha=0.1,0.2,0.3"}, {"--alpha", "3 values"}},
      {"alpha not a number", {"--alpha=rough"}, {"--alpha", "'rough'", "not a number"}},
      {"alpha empty item", {"--alpha=0.3,"}, {"--alpha", "not a number"}},
      {"wi not unit", {"--wi=0,0.6,0.7"}, {"--wi", "length 0.92195", "1e-6"}},
      {"wi two values", {"--wi=0.6,0.8"}, {"--wi", "2 values", "x,y,z"}},
      {"wi not a number", {"--wi=0,0.6,z"}, {"--wi", "'z'"}},
      {"wi below for vndf", {"--wi=0,0.6,-0.8"}, {"--wi", "wi.z = -0.8", "vndf", "wi.z > 0"}},
      {"wi below for ndf", {"--wi=0.6,0,-0.8", "--sampler=ndf"}, {"--wi", "ndf", "wi.z > 0"}},
      {"wi grazing for ndf", {"--wi=1,0,0", "--sampler=ndf"}, {"--wi", "wi.z = 0", "wi.z > 0"}},
      {"wi below beckmann vndf", {"--ndf=beckmann", "--wi=0,0.6,-0.8"}, {"--wi", "wi.z > 0"}},
      {"n zero", {"--n=0"}, {"--n", "'0'", "out of range", "[1, 1000000000]"}},
      {"n negative", {"--n=-5"}, {"--n", "'-5'", "[1, 1000000000]"}},
      {"n too large", {"--n=1000000001"}, {"--n", "out of range", "[1, 1000000000]"}},
      {"n huge", {"--n=99999999999999999999999"}, {"--n", "out of range"}},
      {"n not integer", {"--n=1e3"}, {"--n", "'1e3'", "not an integer"}},
      {"n fractional", {"--n=2.5"}, {"--n", "not an integer"}},
      {"seed not integer", {"--seed=abc"}, {"--seed", "'abc'", "not an integer"}},
      {"seed negative", {"--seed=-1"}, {"--seed", "out of range"}},
      {"unknown bound",
       {"--sampler=bounded_caps", "--bound=loose"},
       {"--bound", "'loose'", "valid: listing1, exact_isotropic"}},
      {"bound without bounded_caps", {"--bound=listing1"}, {"--bound", "--sampler bounded_caps"}},
      {"missing ndf", {"--ndf"}, {"--ndf", "required"}},
      {"missing n", {"--n"}, {"--n", "required"}},
      {"unknown option", {"--bogus=1"}, {"--bogus"}},
      {"unwritable out", {"--out=nodir/s.csv"}, {"--out", "nodir/s.csv"}},
  };
  for (const BadArgs& b : bad) {
    SCOPED_TRACE(b.name);
    expect_input_error(run(sample_args(b.args)), b.needles, {});
  }
}

TEST_F(ErrorTest, SampleOutputIsADirectoryLeavesNoTemporaryFile) {
  std::filesystem::create_directory(path("outdir"));
  expect_input_error(run(sample_args({"--out=outdir"})), {"--out", "outdir"}, {"outdir"});
}

TEST_F(ErrorTest, SampleBelowSurfaceIsValidForCapsAndBounded) {
  for (const std::string sampler : {"spherical_caps", "bounded_caps"}) {
    SCOPED_TRACE(sampler);
    const RunResult r = run(sample_args({"--sampler=" + sampler, "--wi=0,0.6,-0.8"}));
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(lines_of(read_text(path("s.csv"))).size(), 11u);
  }
}

// --- main
// ------------------------------------------------------------------------------------------

TEST_F(ErrorTest, UnknownSubcommand) {
  expect_input_error(run({"render"}), {"unknown subcommand 'render'", "eval, sample, verify"}, {});
}

TEST_F(ErrorTest, NoSubcommand) {
  expect_input_error(run({}), {"subcommand is required", "eval, sample, verify"}, {});
}

// An option a subcommand does not have is named as such, with the words after it kept in the
// order given (CLI11 lists leftover words last first); plain leftover words are named in order.
TEST_F(ErrorTest, UnknownOptionIsNamedAndLeftoverWordsKeepTheirOrder) {
  const RunResult o = run({"verify", "--partition", "1/3"});
  expect_input_error(o, {"verify: unknown option '--partition'", "--claims"}, {});
  EXPECT_EQ(o.err.find("1/3 --partition"), std::string::npos) << o.err;
  expect_input_error(run({"verify", "x", "y"}), {"verify: unexpected argument 'x y'"}, {});
  expect_input_error(run({"models", "extra"}), {"models: unexpected argument 'extra'",
                                                "no arguments"}, {});
}

TEST_F(ErrorTest, UnknownTopLevelOption) {
  expect_input_error(run({"--frobnicate"}), {"--frobnicate"}, {});
}

// --plugin is glintlab's, not the subcommand's: after the subcommand the error names it and its
// place, whatever the path (it is not loaded).
TEST_F(ErrorTest, PluginAfterTheSubcommandIsNamed) {
  expect_input_error(run({"models", "--plugin", "x.so"}),
                     {"--plugin goes before the subcommand", "glintlab --plugin x.so models"}, {});
  expect_input_error(run({"eval", "--model", "smooth_ggx", "--plugin=y.so"}),
                     {"--plugin goes before the subcommand", "glintlab --plugin y.so eval"}, {});
  const RunResult r = run({"models", "--plugin"});
  expect_input_error(r, {"--plugin goes before the subcommand", "glintlab --plugin PATH models"},
                     {});
  EXPECT_EQ(r.err.find("unexpected argument"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace glintlab::cli_test
