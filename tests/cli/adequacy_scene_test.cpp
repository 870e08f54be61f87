// `glintlab figure adequacy-scene --budget quick`: the labelled sheet, the montage and its panel
// labels, one EXR per validation scene with every per-pixel quantity at 128 pixels, the per-scene
// CSV whose counts are the EXRs' pixels, and summary.md with the claim's decision.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <set>
#include <string>

#include "cli/cli_test_util.h"
#include "core/io/csv.h"
#include "core/io/exr.h"

namespace glintlab::cli_test {
namespace {

namespace fs = std::filesystem;
using AdequacySceneFigureTest = CliTest;

void expect_png(const fs::path& p) {
  const std::string bytes = read_text(p);
  ASSERT_GT(bytes.size(), 8u);
  EXPECT_EQ(bytes.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
}

TEST_F(AdequacySceneFigureTest, QuickWritesSheetExrCsvAndSummary) {
  // Benchmark costs with the exact count cheaper than both approximations (as on CPUs).
  std::filesystem::create_directories(path("bench"));
  write_text(path("bench/glints.json"),
             level_costs_json({"deliot_belcour", "kneiphof_klein"}, {10, 200, 300, 100}));
  const RunResult r = run({"figure", "adequacy-scene", "--budget", "quick", "--out", "out",
                           "--bench-from", "bench"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const fs::path d = path("out/adequacy-scene");
  expect_png(d / "adequacy-scene.png");
  expect_png(d / "panels.png");
  EXPECT_NE(read_text(d / "panels.panels.json").find("difference / TAU"), std::string::npos);
  const io::CsvTable t = io::read_csv(d / "adequacy-scene.csv");
  ASSERT_EQ(t.num_rows(), 6u);
  std::set<int> levels;
  for (std::size_t i = 0; i < t.num_rows(); ++i) {
    const std::string name(t.text(i, t.column("scene")));
    const Image im = io::read_exr(d / (name + ".exr")).image;
    EXPECT_EQ(im.width, 128);
    EXPECT_EQ(im.height, 128);
    const std::size_t level = im.channel("level"), lit = im.channel("lit"),
                      exceeds = im.channel("exceeds");
    double n_lit = 0, n_exceeds = 0, n_cheaper = 0;
    for (int y = 0; y < im.height; ++y)
      for (int x = 0; x < im.width; ++x) {
        if (im.at(x, y, lit) == 0) continue;
        ++n_lit;
        n_exceeds += im.at(x, y, exceeds);
        n_cheaper += im.at(x, y, level) < 3 ? 1 : 0;
        levels.insert(int(im.at(x, y, level)));
      }
    EXPECT_EQ(n_lit, t.number(i, t.column("lit"))) << name;
    EXPECT_EQ(n_exceeds, t.number(i, t.column("exceeds"))) << name;
    EXPECT_EQ(n_cheaper, t.number(i, t.column("cheaper"))) << name;
    EXPECT_GT(n_lit, 500) << name;
  }
  // The scenes reach every level of the family.
  EXPECT_EQ(levels, (std::set<int>{0, 1, 2, 3}));
  const std::string md = read_text(d / "summary.md");
  EXPECT_NE(md.find("lit pixels exceed TAU"), std::string::npos);
  EXPECT_NE(md.find("binomial family"), std::string::npos);
  // Each scene's time: exact everywhere = 100 ns per surface pixel; the chooser for these costs
  // never costs more than exact counting (it takes smooth where adequate, else exact).
  EXPECT_NE(md.find("## Time per evaluation"), std::string::npos);
  const io::CsvTable c = io::read_csv(d / "adequacy-scene-cost.csv");
  ASSERT_EQ(c.num_rows(), 6u);
  for (std::size_t i = 0; i < c.num_rows(); ++i) {
    const std::string name(c.text(i, c.column("scene")));
    const Image im = io::read_exr(d / (name + ".exr")).image;
    double surface = 0;
    for (int y = 0; y < im.height; ++y)
      for (int x = 0; x < im.width; ++x) surface += im.at(x, y, im.channel("level")) >= 0 ? 1 : 0;
    EXPECT_DOUBLE_EQ(c.number(i, c.column("surface_pixels_exact_ns")), 100 * surface) << name;
    EXPECT_GE(c.number(i, c.column("by_cost_saved_fraction")), 0) << name;
  }
}

}  // namespace
}  // namespace glintlab::cli_test
