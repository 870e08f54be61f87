// `glintlab figure adequacy-maps --budget quick`: the labelled sheet and one PNG per model × light
// × incidence of the quick grids of the binomial and area families, and per GGAA derivative ×
// incidence of the Chermain family (drawn by matplotlib), its EXR, the CSVs of every cell, whose
// chosen levels are the EXRs' pixels, and summary.md naming the family not drawn.
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
  // Drawn by matplotlib: the sheet's 22 maps and each map alone, labelled, with the levels as
  // their colour scale; drawn from the maps' cells (one row per cell).
  expect_labelled_chart(d / "adequacy-maps.png", 22);
  EXPECT_EQ(io::read_csv(d / "adequacy-maps-levels.csv").num_rows(), 972u + 264u);
  const io::CsvTable t = io::read_csv(d / "adequacy-maps.csv");
  // Quick grid: 3 models × 3 lights × 2 incidences × 2 α × 3 θ_h × 9 footprints (the area
  // family's lights: squares of the cones' solid angles, 0.26°, 1° and 10°).
  ASSERT_EQ(t.num_rows(), 972u);
  int maps = 0;
  for (const std::string model : {"deliot_belcour", "kneiphof_klein", "kneiphof_klein_area"})
    for (const char* light : {model == "kneiphof_klein_area" ? "0.26" : "0", "1", "10"})
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
  EXPECT_EQ(maps, 18);
  // The first map's bottom row is the CSV's first 9 cells (α = 0.05, θ_h = 0), N_P ascending.
  const Image first = io::read_exr(d / "adequacy_deliot_belcour_light0_theta0.exr").image;
  const std::string names[] = {"smooth", "realtime", "small_count", "exact"};
  for (int k = 0; k < 9; ++k)
    EXPECT_EQ(names[int(first.at(k, 0, first.channel("chosen")))],
              std::string(t.text(std::size_t(k), t.column("chosen"))))
        << k;
  // The area family's first map is its first CSV rows (after the binomial family's 648): a level
  // map read from the wrong family's rows (the binomial ones) does not match it.
  const Image area = io::read_exr(d / "adequacy_kneiphof_klein_area_light0.26_theta0.exr").image;
  int mismatches_as_binomial = 0;
  for (int k = 0; k < 9; ++k) {
    EXPECT_EQ(t.text(648 + std::size_t(k), t.column("model")), "kneiphof_klein_area");
    EXPECT_EQ(names[int(area.at(k, 0, area.channel("chosen")))],
              std::string(t.text(648 + std::size_t(k), t.column("chosen"))))
        << k;
  }
  for (int y = 0; y < 6; ++y)
    for (int k = 0; k < 9; ++k)
      mismatches_as_binomial +=
          names[int(area.at(k, y, area.channel("chosen")))] !=
                  std::string(t.text(324 + std::size_t(y * 9 + k), t.column("chosen")))
              ? 1
              : 0;
  EXPECT_GT(mismatches_as_binomial, 0);
  // The Chermain family: 11 footprints × 2 α × 2 θ_i × 3 θ_h × 2 GGAA derivatives, one map per
  // derivative and incidence, its first map's bottom row the first 11 cells of its CSV.
  const io::CsvTable ch = io::read_csv(d / "adequacy-maps-chermain.csv");
  ASSERT_EQ(ch.num_rows(), 264u);
  for (const char* dh : {"0", "0.02"})
    for (const char* theta : {"0", "60"}) {
      const std::string stem = fmt::format("adequacy_chermain_dh{}_theta{}", dh, theta);
      expect_labelled_chart(d / (stem + ".png"), 1);
      const Image im = io::read_exr(d / (stem + ".exr")).image;
      EXPECT_EQ(im.width, 11);
      EXPECT_EQ(im.height, 6);
    }
  const Image cfirst = io::read_exr(d / "adequacy_chermain_dh0_theta0.exr").image;
  const std::string chermain_names[] = {"smooth", "dict4",  "dict4_ggaa",  "dict8",      "dict8_ggaa",
                                        "dict12", "dict12_ggaa", "dict16", "dict16_ggaa"};
  for (int k = 0; k < 11; ++k) {
    EXPECT_EQ(chermain_names[int(cfirst.at(k, 0, cfirst.channel("chosen")))],
              std::string(ch.text(std::size_t(k), ch.column("chosen"))))
        << k;
    EXPECT_EQ(std::string(ch.text(std::size_t(k), ch.column("chooser_refuted"))), "0");
  }
  const std::string md = read_text(d / "summary.md");
  EXPECT_NE(md.find("The Chermain family"), std::string::npos);
  EXPECT_NE(md.find("refuted in 0"), std::string::npos);
  EXPECT_NE(md.find("| kneiphof_klein | 324 |"), std::string::npos);
  EXPECT_NE(md.find("| kneiphof_klein_area | 324 |"), std::string::npos);
}

}  // namespace
}  // namespace glintlab::cli_test
