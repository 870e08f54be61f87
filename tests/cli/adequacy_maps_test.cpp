// `glintlab figure adequacy-maps --budget quick`: the labelled sheet and one PNG per model × light
// × incidence of the quick grid (drawn by matplotlib), its EXR, the CSV of every cell, whose chosen
// levels are the EXRs' pixels, and summary.md naming the families not measured.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "cli/chart_png.h"
#include "cli/cli_test_util.h"
#include "core/io/csv.h"
#include "core/io/exr.h"

namespace glintlab::cli_test {
namespace {

namespace fs = std::filesystem;
using AdequacyMapsFigureTest = CliTest;

void expect_png(const fs::path& p) {
  const std::string bytes = read_text(p);
  ASSERT_GT(bytes.size(), 8u);
  EXPECT_EQ(bytes.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
}

TEST_F(AdequacyMapsFigureTest, QuickWritesSheetMapsCsvAndSummary) {
  const RunResult r = run({"figure", "adequacy-maps", "--budget", "quick", "--out", "out"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const fs::path d = path("out/adequacy-maps");
  expect_png(d / "adequacy-maps.png");
  // Drawn by matplotlib: the sheet's twelve maps and each map alone, labelled, with the levels as
  // their colour scale; drawn from the maps' cells (one row per cell).
  expect_labelled_chart(d / "adequacy-maps.png", 12);
  EXPECT_EQ(io::read_csv(d / "adequacy-maps-levels.csv").num_rows(), 648u);
  const io::CsvTable t = io::read_csv(d / "adequacy-maps.csv");
  // Quick grid: 2 models × 3 lights × 2 incidences × 2 α × 3 θ_h × 9 footprints.
  ASSERT_EQ(t.num_rows(), 648u);
  int maps = 0;
  for (const char* model : {"deliot_belcour", "kneiphof_klein"})
    for (const char* light : {"0", "1", "10"})
      for (const char* theta : {"0", "60"}) {
        const std::string stem = fmt::format("adequacy_{}_light{}_theta{}", model, light, theta);
        expect_png(d / (stem + ".png"));
        expect_labelled_chart(d / (stem + ".png"), 1);
        const Image im = io::read_exr(d / (stem + ".exr")).image;
        EXPECT_EQ(im.width, 9);
        EXPECT_EQ(im.height, 6);
        im.channel("chosen");
        ++maps;
      }
  EXPECT_EQ(maps, 12);
  // The first map's bottom row is the CSV's first 9 cells (α = 0.05, θ_h = 0), N_P ascending.
  const Image first = io::read_exr(d / "adequacy_deliot_belcour_light0_theta0.exr").image;
  const std::string names[] = {"smooth", "realtime", "small_count", "exact"};
  for (int k = 0; k < 9; ++k)
    EXPECT_EQ(names[int(first.at(k, 0, first.channel("chosen")))],
              std::string(t.text(std::size_t(k), t.column("chosen"))))
        << k;
  const std::string md = read_text(d / "summary.md");
  EXPECT_NE(md.find("no measured levels yet"), std::string::npos);
  EXPECT_NE(md.find("| kneiphof_klein | 324 |"), std::string::npos);
}

}  // namespace
}  // namespace glintlab::cli_test
