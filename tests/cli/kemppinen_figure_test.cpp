// `glintlab figure kemppinen2025-*` --quick: each Kemppinen et al. 2025 figure's EXR (read back
// with its attributes), PNG and CSV, and the property the figure shows checked on its numbers.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "cli/chart_png.h"
#include "cli/cli_test_util.h"
#include "core/io/exr.h"

namespace glintlab::cli_test {
namespace {

namespace fs = std::filesystem;
class KemppinenFigureTest : public CliTest {
 protected:
  fs::path run_quick(const std::string& id) const {
    const RunResult r = run({"figure", id, "--budget", "quick", "--out", "out", "--threads", "2"});
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return path("out/" + id);
  }
};

void expect_png(const fs::path& p) {
  const std::string bytes = read_text(p);
  ASSERT_GT(bytes.size(), 8u) << p;
  EXPECT_EQ(bytes.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
}

// A heat map drawn by matplotlib from its chart spec and NAME_map.csv: `panels` labelled panels,
// each a map with its colour bar, whose label holds `bar`; no panels.json (no C++ raster).
void expect_heat_map(const fs::path& png, std::size_t panels, const std::string& bar) {
  expect_labelled_chart(png, panels);
  const nlohmann::json m = chart_manifest(png);
  for (const nlohmann::json& a : m["axes"]) {
    EXPECT_TRUE(a.value("map", false)) << png;
    EXPECT_TRUE(a.value("colorbar", false)) << png;
    EXPECT_NE(a.value("colorbar_label", "").find(bar), std::string::npos) << png;
  }
  fs::path layout = png;
  EXPECT_FALSE(fs::exists(layout.replace_extension(".panels.json"))) << png;
}

io::ExrFile expect_exr(const fs::path& p, const std::string& model) {
  io::ExrFile f = io::read_exr(p);
  for (const char* key : {"glintlab_figure", "glintlab_model", "glintlab_parameters",
                          "glintlab_seed", "glintlab_version"}) {
    EXPECT_TRUE(f.attributes.count(key)) << p << " lacks " << key;
  }
  EXPECT_EQ(f.attributes.at("glintlab_model"), model);
  return f;
}

TEST_F(KemppinenFigureTest, ListShowsTheFigures) {
  const RunResult r = run({"figure", "--list"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* id : {"kemppinen2025-fig2-3 ", "kemppinen2025-fig6 ", "kemppinen2025-fig10 ",
                         "kemppinen2025-fig14 ", "kemppinen2025-fig15 "}) {
    EXPECT_NE(r.out.find(id), std::string::npos) << id;
  }
}

// Fig. 2–3: the smooth integral is 1 on both domains; for Beckmann the glinty integral is the same
// number by the disk and by the hemisphere quadrature; glints concentrate energy (peaks above D).
TEST_F(KemppinenFigureTest, Fig2_3DiskAndHemisphere) {
  const fs::path d = run_quick("kemppinen2025-fig2-3");
  for (const char* ndf : {"ggx", "beckmann"}) {
    for (const char* dom : {"disk", "hemisphere"}) {
      const io::ExrFile f =
          expect_exr(d / (std::string(ndf) + "_" + dom + ".exr"), std::string("kemppinen_") + ndf);
      EXPECT_EQ(f.image.width, 128);
      f.image.channel("D_star_f");
      f.image.channel("D_smooth");
      for (double v : f.image.data) ASSERT_TRUE(std::isfinite(v)) << ndf << " " << dom;
    }
  }
  // Per NDF: disk smooth and glinty (D*f / D), hemisphere smooth and glinty (D [1/sr]).
  expect_heat_map(d / "fig2_3.png", 8, "[1");
  // The map's cells are the pixels inside the disk (128 x 128: one pixel a cell).
  const io::CsvTable cells = io::read_csv(d / "fig2_3_map.csv");
  EXPECT_GT(cells.num_rows(), 8u * 12000u);
  EXPECT_LT(cells.num_rows(), 8u * 128u * 128u);
  const io::CsvTable t = io::read_csv(d / "integrals.csv");
  ASSERT_EQ(t.num_rows(), 4u);
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_NEAR(t.number(i, t.column("smooth_integral")), 1.0, 0.01) << "row " << i;
    EXPECT_GT(t.number(i, t.column("glinty_max")), 1.5);
    EXPECT_GT(t.number(i, t.column("area_mean_se")), 0.0);
  }
  // Beckmann's map pushes D cosθ to the uniform density on U_Ω, so the disk mean of D★^f/D is
  // the hemisphere integral; the printed GGX map does not (kemppinen.jacobian), so no such check.
  EXPECT_EQ(t.text(2, t.column("ndf")), "beckmann");
  EXPECT_EQ(t.text(2, t.column("domain")), "disk");
  EXPECT_NEAR(t.number(2, t.column("glinty_integral")), t.number(3, t.column("glinty_integral")),
              0.005);
}

// Fig. 15: the smooth furnace never exceeds 1; the glinty furnace stays below 1 (the paper: "at
// least be less than 1") and below the smooth one on average over θo.
TEST_F(KemppinenFigureTest, Fig15Furnace) {
  const fs::path d = run_quick("kemppinen2025-fig15");
  // Drawn by matplotlib from furnace.chart.json: one labelled panel per NDF.
  expect_labelled_chart(d / "furnace.png", 2);
  const io::CsvTable t = io::read_csv(d / "furnace.csv");
  ASSERT_EQ(t.num_rows(), 2u * 2u * 9u);  // NDFs × alphas × θo 0..80 step 10
  double gap = 0;
  for (std::size_t i = 0; i < t.num_rows(); ++i) {
    const double g = t.number(i, t.column("energy_glinty"));
    const double gs = t.number(i, t.column("energy_glinty_se"));
    const double s = t.number(i, t.column("energy_smooth"));
    const double ss = t.number(i, t.column("energy_smooth_se"));
    EXPECT_LE(s, 1 + 4 * ss + 1e-12) << "row " << i;
    EXPECT_LE(g, 1 + 4 * gs) << "row " << i;
    gap += s - g;
  }
  EXPECT_GT(gap / double(t.num_rows()), 0.0);
}

// Fig. 14: k = 16 reaches the far-field level at a smaller footprint than k = 4; α★ = 0.5 on an
// α = 0.05 surface loses the highlight's peak, α★ = 0.02 keeps it.
TEST_F(KemppinenFigureTest, Fig14Limitations) {
  const fs::path d = run_quick("kemppinen2025-fig14");
  for (const char* k : {"4", "16"}) {
    const io::ExrFile f =
        expect_exr(d / (std::string("background_k") + k + ".exr"), "kemppinen_ggx");
    f.image.channel("error_vs_D");
  }
  expect_heat_map(d / "background.png", 2, "D*f / D [1]");
  EXPECT_EQ(io::read_csv(d / "background_map.csv").num_rows(), 2u * 48u * 32u);
  const io::CsvTable t = io::read_csv(d / "background.csv");
  ASSERT_EQ(t.num_rows(), 64u);
  const std::size_t m = t.column("mean_ratio_to_D");
  const double far4 = t.number(31, m), far16 = t.number(63, m);
  EXPECT_NEAR(far4, far16, 0.02);
  EXPECT_LT(std::abs(t.number(32, m) - far16), std::abs(t.number(0, m) - far4));
  const io::CsvTable h = io::read_csv(d / "highlight_shape.csv");
  ASSERT_GT(h.num_rows(), 2u);
  const double peak = h.number(0, h.column("D_smooth"));
  EXPECT_GT(h.number(0, h.column("mean_D_star_f_microroughness_0.02")), 0.7 * peak);
  EXPECT_LT(h.number(0, h.column("mean_D_star_f_microroughness_0.5")), 0.05 * peak);
}

// Fig. 6: at whole levels both blendings are the same image; between levels linear blending
// lowers the variation (twice the glints at half the intensity), the roulette does not.
TEST_F(KemppinenFigureTest, Fig6Blending) {
  const fs::path d = run_quick("kemppinen2025-fig6");
  expect_exr(d / "strip_roulette.exr", "kemppinen_ggx");
  expect_exr(d / "strip_linear.exr", "kemppinen_ggx");
  expect_heat_map(d / "strip.png", 2, "D*f / D(h) [1]");
  // Its cells are the EXR's D*f over D(h): the roulette's first pixel.
  const io::CsvTable cells = io::read_csv(d / "strip_map.csv");
  ASSERT_EQ(cells.num_rows(), 2u * 17u * 64u);
  EXPECT_EQ(cells.text(0, cells.column("panel")), "roulette");
  const io::ExrFile roulette = io::read_exr(d / "strip_roulette.exr");
  const double d_h = io::read_csv(d / "blending.csv").number(0, 11);  // D_smooth
  EXPECT_NEAR(cells.number(0, cells.column("D_star_f_over_D")),
              roulette.image.at(0, 0, roulette.image.channel("D_star_f")) / d_h, 1e-9);
  const io::CsvTable t = io::read_csv(d / "blending.csv");
  ASSERT_EQ(t.num_rows(), 34u);
  const std::size_t mean = t.column("mean_D_star_f"), cv = t.column("cv_D_star_f");
  for (std::size_t c : {0u, 8u, 16u}) {
    EXPECT_NEAR(t.number(c, mean), t.number(17 + c, mean), 1e-5 * t.number(c, mean));
  }
  EXPECT_EQ(t.text(4, t.column("blending")), "roulette");
  EXPECT_NEAR(t.number(4, t.column("lambda")), 3.5, 1e-12);
  EXPECT_LT(t.number(17 + 4, cv), 0.9 * t.number(4, cv));
}

// Fig. 10: one sweep per parameter; sparser glints (lower density, lower microroughness) raise the
// pixel variation, and the densest setting converges to the smooth image.
TEST_F(KemppinenFigureTest, Fig10Sweeps) {
  const fs::path d = run_quick("kemppinen2025-fig10");
  for (const char* s : {"alpha", "microroughness", "density", "anisotropy"}) {
    const io::ExrFile f = expect_exr(d / (std::string("sweep_") + s + ".exr"), "kemppinen_ggx");
    EXPECT_EQ(f.image.width, 5 * f.image.height);
  }
  expect_png(d / "sweeps.png");
  const io::CsvTable t = io::read_csv(d / "sweeps.csv");
  ASSERT_EQ(t.num_rows(), 20u);
  const std::size_t cv = t.column("cv_radiance"), ratio = t.column("glinty_over_smooth");
  EXPECT_EQ(t.text(10, t.column("parameter")), "density");
  EXPECT_GT(t.number(10, cv), 2 * t.number(14, cv));  // density 1e2 vs 1e6
  EXPECT_GT(t.number(5, cv), t.number(9, cv));        // microroughness 0.005 vs 0.1
  EXPECT_NEAR(t.number(14, ratio), 1.0, 0.05);
}

}  // namespace
}  // namespace glintlab::cli_test
