// Chermain et al. 2021 from the command line: `glintlab chermain-dictionary` (deterministic EXR,
// one-line errors, no partial output), `eval --model chermain` (intermediates, bad ρ), and each
// chermain2021-* figure with --quick (EXR read back, PNG signature, CSV with the paper's numbers).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <tuple>
#include <vector>

#include "cli/cli_test_util.h"
#include "core/io/csv.h"
#include "core/io/exr.h"

namespace glintlab::cli_test {
namespace {

namespace fs = std::filesystem;
class ChermainCli : public CliTest {
 protected:
  void expect_figure(const std::string& id, const std::string& csv, std::size_t rows,
                     const std::vector<std::string>& exrs) const;
};

TEST_F(ChermainCli, DictionaryRegeneratesIdentically) {
  const std::vector<std::string> args = {
      "chermain-dictionary", "--distributions", "12", "--levels", "6", "--seed", "9"};
  auto a = args, b = args;
  a.insert(a.end(), {"--out", "a.exr"});
  b.insert(b.end(), {"--out", "b.exr"});
  ASSERT_EQ(run(a).exit_code, 0);
  ASSERT_EQ(run(b).exit_code, 0);
  EXPECT_EQ(read_text(path("a.exr")), read_text(path("b.exr")));
  const io::ExrFile f = io::read_exr(path("a.exr"));
  EXPECT_EQ(f.image.width, 64);
  EXPECT_EQ(f.image.height, 12 / 3 * 6);
  EXPECT_EQ(f.attributes.at("glintlab.chermain.seed"), "9");
}

TEST_F(ChermainCli, DictionaryBadParametersOneLineNoOutput) {
  for (const auto& [opt, value, name] :
       {std::tuple{"--distributions", "10", "distributions"},
        std::tuple{"--levels", "21", "levels"}, std::tuple{"--resolution", "48", "resolution"},
        std::tuple{"--lobe-std", "0.5", "lobe_std"}}) {
    const RunResult r = run({"chermain-dictionary", "--out", "x.exr", opt, value});
    EXPECT_EQ(r.exit_code, 2) << opt;
    EXPECT_EQ(r.err.rfind("glintlab: error: ", 0), 0u) << r.err;
    EXPECT_NE(r.err.find(name), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_FALSE(fs::exists(path("x.exr")));
  }
}

TEST_F(ChermainCli, EvalModelRejectsRhoOne) {
  const RunResult r =
      run({"eval", "--model", "chermain", "--param", "rho=1", "--in", "q.csv", "--out", "o.csv"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("rho"), std::string::npos) << r.err;
}

void ChermainCli::expect_figure(const std::string& id, const std::string& csv, std::size_t rows,
                                const std::vector<std::string>& exrs) const {
  const RunResult r = run({"figure", id, "--budget", "quick", "--out", "out", "--threads", "2"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const fs::path d = path("out/" + id);
  for (const std::string& e : exrs) {
    const io::ExrFile f = io::read_exr(d / e);
    EXPECT_EQ(f.attributes.at("glintlab.figure"), id);
  }
  const io::CsvTable table = io::read_csv(d / csv);
  EXPECT_EQ(table.num_rows(), rows);
  EXPECT_TRUE(fs::exists(d / "summary.md"));
  bool png = false;
  for (const auto& e : fs::directory_iterator(d)) png = png || e.path().extension() == ".png";
  EXPECT_TRUE(png);
}

TEST_F(ChermainCli, Fig3Quick) {
  expect_figure("chermain2021-fig3", "fig3_convergence.csv", 16, {"dictionary.exr"});
}
TEST_F(ChermainCli, Fig7Quick) {
  expect_figure("chermain2021-fig7", "fig7.csv", 3,
                {"no_lean.exr", "lean_rho0.exr", "lean_rho.exr", "reference.exr"});
}
TEST_F(ChermainCli, Fig8Quick) {
  expect_figure("chermain2021-fig8", "fig8.csv", 2,
                {"without_ggaa.exr", "with_ggaa.exr", "reference.exr"});
}
TEST_F(ChermainCli, Fig9Quick) {
  expect_figure("chermain2021-fig9", "fig9.csv", 5,
                {"without_ggaa.exr", "projected_half_sk0.5.exr", "half_slope_sk1.exr"});
}
TEST_F(ChermainCli, Fig10Quick) {
  expect_figure("chermain2021-fig10", "fig10.csv", 6, {"sdf_rho0.99_lnD50.exr"});
  const io::ExrFile f = io::read_exr(path("out/chermain2021-fig10/sdf_rho0.99_lnD50.exr"));
  EXPECT_GE(f.image.width, 128);  // a panel a person can see
  EXPECT_GE(f.image.height, 128);
}

}  // namespace
}  // namespace glintlab::cli_test
