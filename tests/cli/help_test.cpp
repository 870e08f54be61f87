// --help on the executable and on every subcommand exits 0 and documents the options and columns.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "cli/build_paths.h"
#include "cli/cli_test_util.h"

namespace glintlab::cli_test {
namespace {

using HelpTest = CliTest;

void expect_contains(const std::string& text, const std::vector<std::string>& needles) {
  for (const std::string& n : needles) {
    EXPECT_NE(text.find(n), std::string::npos) << "help lacks '" << n << "'";
  }
}

TEST_F(HelpTest, TopLevelListsSubcommands) {
  for (const std::string flag : {"--help", "-h"}) {
    const RunResult r = run({flag});
    EXPECT_EQ(r.exit_code, 0);
    EXPECT_EQ(r.err, "");
    expect_contains(r.out, {"Usage: glintlab", "eval", "sample", "verify", "exit with code 2"});
  }
}

TEST_F(HelpTest, EvalDocumentsEveryColumn) {
  const RunResult r = run({"eval", "--help"});
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_EQ(r.err, "");
  expect_contains(r.out, {"--in",
                          "--out",
                          "ndf",
                          "alpha_x, alpha_y",
                          "wi_x, wi_y, wi_z",
                          "wo_x, wo_y, wo_z",
                          "h_x, h_y, h_z",
                          "lambda_wi",
                          "G1_wi, G1_wo",
                          "G2",
                          "vndf_h",
                          "pdf_ndf",
                          "pdf_vndf",
                          "pdf_spherical_caps",
                          "pdf_bounded_caps_listing1",
                          "pdf_bounded_caps_exact_isotropic",
                          "brdf",
                          "DH",
                          "T_x, T_y",
                          "JT_paper",
                          "JT_true",
                          "17 significant digits",
                          "below the surface"});
}

TEST_F(HelpTest, SampleDocumentsOptionsAndColumns) {
  const RunResult r = run({"sample", "--help"});
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_EQ(r.err, "");
  expect_contains(r.out, {"--ndf", "--alpha", "--wi", "--sampler", "--bound", "--n", "--seed",
                          "--out", "wo_x, wo_y, wo_z", "h_x, h_y, h_z", "pdf", "weight", "rejected",
                          "wi.z > 0", "spherical_caps", "bounded_caps", "exact_isotropic"});
}

TEST_F(HelpTest, VerifyHasHelp) {
  const RunResult r = run({"verify", "--help"});
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_EQ(r.err, "");
  expect_contains(r.out, {"verify"});
}

TEST_F(HelpTest, HelpWinsOverOtherArguments) {
  // --help with otherwise missing or invalid options still prints help and succeeds, and
  // writes nothing.
  const RunResult r = run({"sample", "--ndf", "phong", "--help"});
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_EQ(unexpected_files(work(), {}), std::vector<std::string>{});
}

// One vocabulary: every subcommand's --help shows a default as TYPE=DEFAULT in the option column
// (never again in the description), --threads wherever work is parallel, and --budget quick|full
// wherever there are budgets.
TEST_F(HelpTest, DefaultsThreadsAndBudgetsShownTheSameWayEverywhere) {
  struct Sub {
    std::string name;
    bool threads, budget;
  };
  const std::vector<Sub> subs = {
      {"eval", true, false},  {"sample", true, false},  {"verify", true, true},
      {"figure", true, true}, {"models", false, false}, {"sweep", true, true},
      {"report", true, true}, {"ltc-fit", true, false}, {"chermain-dictionary", true, false}};
  for (const Sub& s : subs) {
    const RunResult r = run({s.name, "--help"});
    ASSERT_EQ(r.exit_code, 0) << s.name;
    bool threads = false, budget = false;
    for (const std::string& line : lines_of(r.out)) {
      if (line.rfind("  --", 0) != 0) continue;  // option lines only, not the footers
      EXPECT_EQ(line.find("(default"), std::string::npos) << s.name << ": " << line;
      EXPECT_EQ(line.find("default "), std::string::npos) << s.name << ": " << line;
      if (line.rfind("  --threads ", 0) == 0) {
        threads = true;
        EXPECT_NE(line.find("INT=0"), std::string::npos) << s.name << ": " << line;
      }
      if (line.rfind("  --budget ", 0) == 0) {
        budget = true;
        EXPECT_NE(line.find("NAME="), std::string::npos) << s.name << ": " << line;
        EXPECT_NE(line.find("quick or full"), std::string::npos) << s.name << ": " << line;
      }
    }
    EXPECT_EQ(threads, s.threads) << s.name << " --threads";
    EXPECT_EQ(budget, s.budget) << s.name << " --budget";
  }
}

// Help points only inside the repository: every repository file a help text names (a path with a
// folder and a source or document extension; outputs such as out/… and <out>/… aside) exists in
// this source tree.
TEST_F(HelpTest, EveryFileNamedIsInTheRepository) {
  // kReportFixtures is <source>/tests/reports/fixtures.
  const std::filesystem::path source =
      std::filesystem::path(kReportFixtures).parent_path().parent_path().parent_path();
  const std::vector<std::string> extensions = {".md", ".h", ".cpp", ".py", ".sh", ".cmake"};
  int named = 0;
  for (const std::string sub :
       {"", "eval", "sample", "verify", "figure", "models", "sweep", "report", "ltc-fit",
        "chermain-dictionary", "adequacy", "compare"}) {
    const RunResult r = sub.empty() ? run({"--help"}) : run({sub, "--help"});
    ASSERT_EQ(r.exit_code, 0) << sub;
    std::string token;
    const auto check = [&] {
      std::string path = token.substr(0, token.find('#'));
      token.clear();
      while (!path.empty() && path.back() == '.') path.pop_back();  // a sentence's full stop
      const bool file =
          std::any_of(extensions.begin(), extensions.end(), [&](const std::string& e) {
            return path.size() > e.size() && path.compare(path.size() - e.size(), e.size(), e) == 0;
          });
      if (!file || path.find('/') == std::string::npos || path.find('<') != std::string::npos ||
          path.rfind("out/", 0) == 0)
        return;
      ++named;
      EXPECT_TRUE(std::filesystem::exists(source / path))
          << "glintlab " << sub << " --help names " << path << ", which is not in the repository";
    };
    for (char c : r.out + " ") {
      if (std::isalnum(static_cast<unsigned char>(c)) ||
          std::string_view("_./-<>#").find(c) != std::string_view::npos)
        token += c;
      else
        check();
    }
  }
  EXPECT_GT(named, 0);  // the scan found the paths the help texts do name
}

// The old flag --quick still works, as --budget quick, with one note naming the new spelling.
TEST_F(HelpTest, QuickIsAnAliasOfBudgetQuickWithANote) {
  const RunResult r = run({"verify", "--quick", "--list", "--claims", "eto.bound-is-infimum"});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, "glintlab: note: --quick is spelled --budget quick\n");
  EXPECT_NE(r.out.find("eto.bound-is-infimum"), std::string::npos);
}

}  // namespace
}  // namespace glintlab::cli_test
