// Chermain et al. 2021 from the command line: `glintlab chermain-dictionary` (deterministic EXR,
// one-line errors, no partial output), `eval --model chermain` (intermediates, bad ρ), and each
// chermain2021-* figure with --quick (EXR read back, PNG signature, CSV with the paper's numbers;
// the maps of Figs. 3 and 10 drawn by matplotlib, their labels read back from the PNG).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "cli/chart_png.h"
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

// A chart's axes read back from its PNG: the first `maps` are heat maps whose colour bar is
// `value`, the others line panels with a legend.
void expect_maps_then_lines(const fs::path& png, std::size_t axes, std::size_t maps,
                            const std::string& value) {
  expect_labelled_chart(png, axes);
  const nlohmann::json m = chart_manifest(png);
  ASSERT_EQ(m["axes"].size(), axes);
  for (std::size_t i = 0; i < axes; ++i) {
    const nlohmann::json& a = m["axes"][i];
    EXPECT_EQ(a.value("map", false), i < maps) << png << " " << i;
    if (i < maps)
      EXPECT_EQ(a.value("colorbar_label", ""), value) << png << " " << i;
    else
      EXPECT_TRUE(a.value("legend", false)) << png << " " << i;
  }
}

TEST_F(ChermainCli, Fig3Quick) {
  expect_figure("chermain2021-fig3", "fig3_convergence.csv", 16, {"dictionary.exr"});
  // Per distribution a heat map of every level and the curves of four levels with the Gaussian,
  // from fig3_marginals.csv (4 distributions x 16 levels x 128 slopes).
  const fs::path d = path("out/chermain2021-fig3");
  expect_maps_then_lines(d / "fig3.png", 8, 4, "density [1] (log scale)");
  EXPECT_EQ(io::read_csv(d / "fig3_marginals.csv").num_rows(), 4u * 16u * 128u);
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
  // The six patch-SDF maps drawn from fig10_sdf.csv, whose cells at quick are the EXR's pixels
  // (row by row from the top, panels in the EXRs' order: e^15 then e^50, rho 0, 0.5, 0.99).
  const fs::path d = path("out/chermain2021-fig10");
  expect_maps_then_lines(d / "fig10.png", 6, 6, "patch-SDF density [1/slope^2]");
  EXPECT_FALSE(fs::exists(d / "fig10.panels.json"));
  const io::CsvTable t = io::read_csv(d / "fig10_sdf.csv");
  ASSERT_EQ(t.num_rows(), 6u * 128u * 128u);
  const std::size_t last = 5u * 128u * 128u;
  for (const auto& [x, y] : {std::pair{0, 0}, std::pair{64, 64}, std::pair{127, 3}}) {
    const std::size_t row = last + std::size_t(y) * 128u + std::size_t(x);
    EXPECT_EQ(t.number(row, t.column("rho")), 0.99);
    // The EXR holds 32-bit floats.
    EXPECT_EQ(float(t.number(row, t.column("density"))), float(f.image.at(x, y, 0)))
        << x << " " << y;
  }
}

}  // namespace
}  // namespace glintlab::cli_test
