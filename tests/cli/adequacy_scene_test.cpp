// `glintlab figure adequacy-scene --budget quick`: the labelled sheet (matplotlib) and its pixels'
// CSV, the montage and its panel labels, one EXR per validation scene with every per-pixel
// quantity (the binomial scenes at 128 pixels, the Kemppinen scenes at 32, the area scenes at 64,
// the Chermain scenes at 32; the area and Chermain families each a plane and a sphere at two
// densities), each family's per-scene CSV whose counts are the EXRs' pixels, and
// summary.md with the claim's decision per family at the claim's Šidák share over its four
// families.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

#include "cli/chart_png.h"
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

// Each row of a family's CSV against its scene's EXR: the size, and the lit, exceeding and cheaper
// (level below `complete`) pixels counted from the EXR's channels; returns the levels of the lit
// pixels over all scenes.
std::set<int> expect_counts_match_exrs(const fs::path& d, const io::CsvTable& t, int size,
                                       int complete, double min_lit) {
  std::set<int> levels;
  for (std::size_t i = 0; i < t.num_rows(); ++i) {
    const std::string name(t.text(i, t.column("scene")));
    const Image im = io::read_exr(d / (name + ".exr")).image;
    EXPECT_EQ(im.width, size) << name;
    EXPECT_EQ(im.height, size) << name;
    EXPECT_EQ(t.number(i, t.column("width")), size) << name;
    const std::size_t level = im.channel("level"), lit = im.channel("lit"),
                      exceeds = im.channel("exceeds");
    double n_lit = 0, n_exceeds = 0, n_cheaper = 0;
    for (int y = 0; y < im.height; ++y)
      for (int x = 0; x < im.width; ++x) {
        if (im.at(x, y, lit) == 0) continue;
        ++n_lit;
        n_exceeds += im.at(x, y, exceeds);
        n_cheaper += im.at(x, y, level) < complete ? 1 : 0;
        levels.insert(int(im.at(x, y, level)));
      }
    EXPECT_EQ(n_lit, t.number(i, t.column("lit"))) << name;
    EXPECT_EQ(n_exceeds, t.number(i, t.column("exceeds"))) << name;
    EXPECT_EQ(n_cheaper, t.number(i, t.column("cheaper"))) << name;
    EXPECT_GT(n_lit, min_lit) << name;
  }
  return levels;
}

// Rows adequacy/<model>/level=<level>/<isa> of a nine-level family appended to a benchmark file.
void add_level_costs(nlohmann::json& bench, const std::string& model,
                     const std::vector<std::string>& levels, const std::vector<double>& ns) {
  for (const char* isa : {"scalar", "sse4.2", "avx2", "avx512"})
    for (std::size_t l = 0; l < levels.size(); ++l) {
      const std::string name = "adequacy/" + model + "/level=" + levels[l] + "/" + isa;
      bench["benchmarks"].push_back({{"name", name}, {"run_name", name}, {"run_type", "iteration"},
                                     {"real_time", 1e6}, {"time_unit", "ns"},
                                     {"items_per_second", 1e9 / ns[l]}});
    }
}

TEST_F(AdequacySceneFigureTest, QuickWritesSheetExrCsvAndSummary) {
  // Benchmark costs with the exact count cheaper than both approximations (as on CPUs), for the
  // binomial and the area family's models; for kemppinen_ggx k16_exact below k16_rational, for
  // chermain dict16 below dict8_ggaa (orders of CPU rows), the most complete level 100 ns.
  std::filesystem::create_directories(path("bench"));
  nlohmann::json bench = nlohmann::json::parse(level_costs_json(
      {"deliot_belcour", "kneiphof_klein", "kneiphof_klein_area"}, {10, 200, 300, 100}));
  add_level_costs(bench, "kemppinen_ggx",
                  {"smooth", "k1_rational", "k1_exact", "k4_rational", "k4_exact", "k9_rational",
                   "k9_exact", "k16_rational", "k16_exact"},
                  {1, 10, 11, 20, 21, 30, 31, 101, 100});
  add_level_costs(bench, "chermain",
                  {"smooth", "dict4", "dict4_ggaa", "dict8", "dict8_ggaa", "dict12", "dict12_ggaa",
                   "dict16", "dict16_ggaa"},
                  {1, 20, 30, 40, 50, 60, 70, 35, 100});
  write_text(path("bench/glints.json"), bench.dump(1));
  const RunResult r = run(
      {"figure", "adequacy-scene", "--budget", "quick", "--out", "out", "--bench-from", "bench"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const fs::path d = path("out/adequacy-scene");
  expect_png(d / "adequacy-scene.png");
  // The sheet, drawn by matplotlib: per scene its difference map and its chosen-level map, each
  // titled, with pixel axes and a colour scale; the scenes named in the panels' titles.
  expect_labelled_chart(d / "adequacy-scene.png", 36);
  const nlohmann::json sheet = chart_manifest(d / "adequacy-scene.png");
  EXPECT_NE(sheet["axes"][0].value("title", "").find("plane-point-low"), std::string::npos);
  EXPECT_NE(sheet["axes"][19].value("title", "").find("kemppinen-sphere-high"), std::string::npos);
  EXPECT_NE(sheet["axes"][23].value("title", "").find("area-plane-rect-high"), std::string::npos);
  EXPECT_NE(sheet["axes"][27].value("title", "").find("area-sphere-rect-high"), std::string::npos);
  EXPECT_NE(sheet["axes"][31].value("title", "").find("chermain-plane-high"), std::string::npos);
  EXPECT_NE(sheet["axes"][35].value("title", "").find("chermain-sphere-high"), std::string::npos);
  // Its data: every pixel of every scene, image order, the level as in the scene's EXR.
  const io::CsvTable px = io::read_csv(d / "adequacy-scene-pixels.csv");
  ASSERT_EQ(px.num_rows(), 6u * 128 * 128 + 4u * 32 * 32 + 4u * 64 * 64 + 4u * 32 * 32);
  const Image first = io::read_exr(d / "plane-point-low.exr").image;
  for (std::size_t i = 0; i < 128u * 128; ++i) {
    ASSERT_EQ(px.text(i, px.column("scene")), "plane-point-low");
    const int x = int(i % 128), y = int(i / 128);
    EXPECT_EQ(px.number(i, px.column("level")), first.at(x, y, first.channel("level"))) << i;
  }
  // The montage holds the renders only (the difference and level maps are the sheet's): per
  // scene the chosen level's and the most complete level's, the Kemppinen scenes after the
  // binomial ones.
  expect_png(d / "panels.png");
  const std::string layout = read_text(d / "panels.panels.json");
  EXPECT_EQ(layout.find("difference / TAU"), std::string::npos);
  EXPECT_EQ(layout.find("chosen level map"), std::string::npos);
  for (const char* name : {"plane-point-low", "kemppinen-plane-low", "kemppinen-plane-high",
                           "kemppinen-sphere-low", "kemppinen-sphere-high", "area-plane-rect-low",
                           "area-plane-rect-high", "area-sphere-rect-low", "area-sphere-rect-high",
                           "chermain-sphere-low", "chermain-sphere-high"})
    for (const char* column : {"chosen level", "most complete level"})
      EXPECT_NE(layout.find(fmt::format("\"{}: {}\"", name, column)), std::string::npos)
          << name << ": " << column;
  const nlohmann::json panels = nlohmann::json::parse(layout);
  EXPECT_EQ(panels["labels"].size(), 2u * 18u);
  const io::CsvTable t = io::read_csv(d / "adequacy-scene.csv");
  ASSERT_EQ(t.num_rows(), 6u);
  // The binomial scenes reach every level of the family.
  EXPECT_EQ(expect_counts_match_exrs(d, t, 128, 3, 500), (std::set<int>{0, 1, 2, 3}));
  // The Kemppinen scenes: 32 pixels, cheaper meaning below k16_exact (8); the chooser takes the
  // smooth level where the footprint holds enough points and k16_rational where it holds few.
  const io::CsvTable k = io::read_csv(d / "adequacy-scene-kemppinen.csv");
  ASSERT_EQ(k.num_rows(), 4u);
  const std::set<int> k_levels = expect_counts_match_exrs(d, k, 32, 8, 400);
  EXPECT_TRUE(k_levels.count(0)) << "no Kemppinen pixel at the smooth level";
  EXPECT_TRUE(k_levels.count(7)) << "no Kemppinen pixel at k16_rational";
  for (std::size_t i = 0; i < k.num_rows(); ++i)
    EXPECT_EQ(k.text(i, k.column("model")), "kemppinen_ggx");
  // The area scenes (kneiphof_klein_area, the plane and the sphere under the square light): 64
  // pixels, the binomial levels (cheaper meaning below exact, 3), both sides of the smooth
  // boundary reached.
  const io::CsvTable a = io::read_csv(d / "adequacy-scene-area.csv");
  ASSERT_EQ(a.num_rows(), 4u);  // the planes, then the spheres
  EXPECT_EQ(a.text(3, a.column("shape")), "sphere");
  const std::set<int> a_levels = expect_counts_match_exrs(d, a, 64, 3, 1000);
  EXPECT_TRUE(a_levels.count(0)) << "no area pixel at the smooth level";
  EXPECT_TRUE(a_levels.count(3)) << "no area pixel at exact counting";
  for (std::size_t i = 0; i < a.num_rows(); ++i) {
    EXPECT_EQ(a.text(i, a.column("model")), "kneiphof_klein_area");
    EXPECT_EQ(a.text(i, a.column("light")), "square");
    // The same count read as the wrong family (the Kemppinen levels, k16_exact = 8, most
    // complete) differs: every lit pixel would be "cheaper".
    const Image im = io::read_exr(d / (std::string(a.text(i, a.column("scene"))) + ".exr")).image;
    double as_kemppinen = 0;
    for (int y = 0; y < im.height; ++y)
      for (int x = 0; x < im.width; ++x)
        as_kemppinen +=
            im.at(x, y, im.channel("lit")) != 0 && im.at(x, y, im.channel("level")) < 8 ? 1 : 0;
    EXPECT_NE(as_kemppinen, a.number(i, a.column("cheaper")));
  }
  // The Chermain scenes (the plane and the sphere at two microfacet densities): 32 pixels, cheaper
  // meaning below dict16_ggaa (8); the chooser takes shorter dictionaries (GGAA twins) where they
  // are identical.
  const io::CsvTable ch = io::read_csv(d / "adequacy-scene-chermain.csv");
  ASSERT_EQ(ch.num_rows(), 4u);  // the planes, then the spheres (fewer lit pixels at 32²)
  EXPECT_EQ(ch.text(3, ch.column("shape")), "sphere");
  const std::set<int> c_levels = expect_counts_match_exrs(d, ch, 32, 8, 60);
  EXPECT_TRUE(c_levels.count(8)) << "no Chermain pixel at dict16_ggaa";
  EXPECT_TRUE(c_levels.count(4) || c_levels.count(6))
      << "no Chermain pixel at a shorter dictionary";
  for (std::size_t i = 0; i < ch.num_rows(); ++i)
    EXPECT_EQ(ch.text(i, ch.column("model")), "chermain");
  const std::string md = read_text(d / "summary.md");
  EXPECT_NE(md.find("lit pixels exceed TAU"), std::string::npos);
  EXPECT_NE(md.find("Binomial family"), std::string::npos);
  EXPECT_NE(md.find("Kemppinen family"), std::string::npos);
  EXPECT_NE(md.find("most complete: k16_exact"), std::string::npos);
  EXPECT_NE(md.find("Area family"), std::string::npos);
  EXPECT_NE(md.find("Chermain family"), std::string::npos);
  // Each family at the claim's Šidák share: over its four families, as the claim decides.
  EXPECT_NE(md.find("over the 4 families"), std::string::npos);
  EXPECT_EQ(md.find("over the 3 families"), std::string::npos);
  EXPECT_EQ(md.find("over the 2 families"), std::string::npos);
  EXPECT_EQ(md.find("over the two families"), std::string::npos);
  EXPECT_EQ(md.find("are not priced"), std::string::npos);
  // Each scene's time: the most complete level everywhere = 100 ns per surface pixel; the chooser
  // for these costs never costs more than the most complete level nor than the GPU-order choice,
  // and less than it where the costs order levels otherwise (k16_exact for k16_rational; dict16
  // where GGAA off is predicted adequate).
  EXPECT_NE(md.find("## Time per evaluation"), std::string::npos);
  const io::CsvTable c = io::read_csv(d / "adequacy-scene-cost.csv");
  ASSERT_EQ(c.num_rows(), 18u);  // binomial, Kemppinen, area, Chermain scenes
  EXPECT_EQ(c.text(13, c.column("scene")), "area-sphere-rect-high");
  EXPECT_EQ(c.text(17, c.column("scene")), "chermain-sphere-high");
  std::set<std::string> cheaper_by_cost;
  for (std::size_t i = 0; i < c.num_rows(); ++i) {
    EXPECT_LE(c.number(i, c.column("by_cost_ns")), c.number(i, c.column("chosen_ns")));
    if (c.number(i, c.column("by_cost_ns")) < c.number(i, c.column("chosen_ns")))
      cheaper_by_cost.insert(std::string(c.text(i, c.column("model"))));
  }
  EXPECT_TRUE(cheaper_by_cost.count("kemppinen_ggx"));
  EXPECT_TRUE(cheaper_by_cost.count("chermain"));
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
