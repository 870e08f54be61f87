// `glintlab figure adequacy-maps --budget quick`: the labelled sheet and one PNG per model × light
// × incidence of the quick grids of the binomial and area families, per model × incidence of the
// Kemppinen family and per GGAA derivative × incidence of the Chermain family (drawn by
// matplotlib), its EXR, the CSVs of every cell with its family, whose chosen levels are the EXRs'
// pixels, and summary.md naming each map's family.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

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
  // Drawn by matplotlib: the sheet's 26 maps and each map alone, labelled, with the levels as
  // their colour scale; drawn from the maps' cells (one row per cell).
  expect_labelled_chart(d / "adequacy-maps.png", 26);
  EXPECT_EQ(io::read_csv(d / "adequacy-maps-levels.csv").num_rows(), 972u + 168u + 264u);
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
  EXPECT_EQ(t.text(0, t.column("family")), "binomial");
  EXPECT_EQ(t.text(648, t.column("family")), "area");
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
  // The Kemppinen family: 7 footprints (1 … 10⁶ expected points) × 2 α × 2 θ_i × 3 θ_h per
  // model, one map per model and incidence, its colour scale naming the nine levels (smooth, k =
  // 1, 4, 9, 16 with the rational and the exact erf); the first map's bottom row is the first 7
  // cells of its CSV, which names the family.
  const io::CsvTable kt = io::read_csv(d / "adequacy-maps-kemppinen.csv");
  ASSERT_EQ(kt.num_rows(), 168u);
  const std::vector<std::string> kemppinen_names = {
      "smooth",   "k1_rational", "k1_exact",     "k4_rational", "k4_exact",
      "k9_rational", "k9_exact", "k16_rational", "k16_exact"};
  for (const char* model : {"kemppinen_ggx", "kemppinen_beckmann"})
    for (const char* theta : {"0", "60"}) {
      const std::string stem = fmt::format("adequacy_{}_theta{}", model, theta);
      expect_labelled_chart(d / (stem + ".png"), 1);
      const io::ExrFile exr = io::read_exr(d / (stem + ".exr"));
      EXPECT_EQ(exr.image.width, 7);
      EXPECT_EQ(exr.image.height, 6);
      EXPECT_EQ(exr.attributes.at("glintlab_family"), "kemppinen");
      const nlohmann::json spec = nlohmann::json::parse(read_text(d / (stem + ".chart.json")));
      std::vector<std::string> legend;
      for (const nlohmann::json& c : spec["panels"][0]["categories"])
        legend.push_back(c["label"].get<std::string>());
      EXPECT_EQ(legend, kemppinen_names) << stem;
      EXPECT_NE(spec["panels"][0]["x"]["label"].get<std::string>().find("[expected points]"),
                std::string::npos);
    }
  const Image kfirst = io::read_exr(d / "adequacy_kemppinen_ggx_theta0.exr").image;
  for (int k = 0; k < 7; ++k) {
    EXPECT_EQ(kt.text(std::size_t(k), kt.column("family")), "kemppinen");
    EXPECT_EQ(kt.text(std::size_t(k), kt.column("model")), "kemppinen_ggx");
    EXPECT_EQ(kemppinen_names[std::size_t(kfirst.at(k, 0, kfirst.channel("chosen")))],
              std::string(kt.text(std::size_t(k), kt.column("chosen"))))
        << k;
    EXPECT_EQ(std::string(kt.text(std::size_t(k), kt.column("chooser_refuted"))), "0");
  }
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
  // The index names every map's family, in the sheet's order: binomial, Kemppinen, area, Chermain.
  const io::CsvTable index = io::read_csv(d / "adequacy-maps-index.csv");
  ASSERT_EQ(index.num_rows(), 26u);
  const std::pair<std::size_t, const char*> families[] = {
      {0, "binomial"}, {11, "binomial"}, {12, "kemppinen"}, {15, "kemppinen"},
      {16, "area"},    {21, "area"},     {22, "chermain"},  {25, "chermain"}};
  for (const auto& [row, family] : families)
    EXPECT_EQ(index.text(row, index.column("family")), family) << row;
  EXPECT_EQ(index.text(12, index.column("map")), "adequacy_kemppinen_ggx_theta0");
  const std::string md = read_text(d / "summary.md");
  EXPECT_NE(md.find("The Chermain family"), std::string::npos);
  EXPECT_NE(md.find("The Kemppinen family"), std::string::npos);
  EXPECT_NE(md.find("| adequacy_kemppinen_beckmann_theta60 | kemppinen | kemppinen_beckmann |"),
            std::string::npos);
  EXPECT_NE(md.find("| adequacy_chermain_dh0_theta0 | chermain | chermain |"), std::string::npos);
  EXPECT_NE(md.find("| kemppinen_ggx | 84 |"), std::string::npos);
  EXPECT_NE(md.find("refuted in 0"), std::string::npos);
  EXPECT_NE(md.find("| kneiphof_klein | 324 |"), std::string::npos);
  EXPECT_NE(md.find("| kneiphof_klein_area | 324 |"), std::string::npos);
}

}  // namespace
}  // namespace glintlab::cli_test
