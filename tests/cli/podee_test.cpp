// Podee et al. through the executable: `glintlab eval --model podee` exposes the selected
// reflection vector and the weight, with one-line errors for a zero-radius disk, a light below the
// surface and missing corner columns; each podee figure's --quick run writes EXR, PNG and CSV.
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
using PodeeCliTest = CliTest;

const char* kHeader =
    "wi_x,wi_y,wi_z,wo_x,wo_y,wo_z,u,v,dudx,dvdx,dudy,dvdy,light_cos_half_angle,light_intensity,"
    "r0_x,r0_y,r0_z,r1_x,r1_y,r1_z,r2_x,r2_y,r2_z,r3_x,r3_y,r3_z\n";

// Corner vectors normalize((cx ± 0.02, ±0.02, 1)) around the light direction (0, 0, 1).
std::string row(double cx, double cos_half, double wo_z = 1) {
  std::string s = "0,0,1,0," + std::to_string(std::sqrt(1 - wo_z * wo_z)) + "," +
                  std::to_string(wo_z) + ",0,0,0,0,0,0," + std::to_string(cos_half) + ",1";
  const double ox[4] = {-0.02, 0.02, -0.02, 0.02}, oy[4] = {-0.02, -0.02, 0.02, 0.02};
  for (int k = 0; k < 4; ++k) {
    const double x = cx + ox[k], y = oy[k], n = std::sqrt(x * x + y * y + 1);
    s += "," + std::to_string(x / n) + "," + std::to_string(y / n) + "," + std::to_string(1 / n);
  }
  return s + "\n";
}

TEST_F(PodeeCliTest, EvalExposesTheSelectedVectorAndWeight) {
  write_text(path("q.csv"),
             std::string(kHeader) + row(0, std::cos(0.05)) + row(0.2, std::cos(0.05)));
  const RunResult r = run({"eval", "--model", "podee", "--in", "q.csv", "--out", "r.csv"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const io::CsvTable t = io::read_csv(path("r.csv"));
  ASSERT_EQ(t.num_rows(), 2u);
  // Light circle (radius tan 0.05) covers the 0.04-wide reflection space: weight 1, lit.
  EXPECT_NEAR(cell_value(t, 0, t.column("weight")), 1.0, 1e-9);
  EXPECT_EQ(cell_value(t, 0, t.column("inside")), 1.0);
  EXPECT_NEAR(cell_value(t, 0, t.column("value")), 1.0, 1e-9);
  EXPECT_NEAR(cell_value(t, 0, t.column("r_z")), 1.0, 1e-12);
  // Reflection space 0.18..0.22 to the side: the nearest edge point is at 0.18, not lit.
  EXPECT_EQ(cell_value(t, 1, t.column("inside")), 0.0);
  EXPECT_NEAR(cell_value(t, 1, t.column("distance")), 0.18, 1e-5);
  EXPECT_EQ(cell_value(t, 1, t.column("value")), 0.0);
  EXPECT_GT(cell_value(t, 1, t.column("r_x")), 0.17);
  EXPECT_NO_THROW(t.column("r3_z"));  // the corner columns are echoed
}

TEST_F(PodeeCliTest, BadLightsGetOneLineErrors) {
  write_text(path("zero.csv"), std::string(kHeader) + row(0, 1.0));
  expect_input_error(run({"eval", "--model", "podee", "--in", "zero.csv", "--out", "r.csv"}),
                     {"light_cos_half_angle", "radius > 0"}, {"zero.csv"});
  write_text(path("below.csv"), std::string(kHeader) + row(0, std::cos(0.05), -0.6));
  expect_input_error(run({"eval", "--model", "podee", "--in", "below.csv", "--out", "r.csv"}),
                     {"wo_z", "above the surface"}, {"zero.csv", "below.csv"});
  write_text(path("nocorners.csv"),
             "wi_x,wi_y,wi_z,wo_x,wo_y,wo_z,u,v,dudx,dvdx,dudy,dvdy,"
             "light_cos_half_angle,light_intensity\n0,0,1,0,0,1,0,0,0,0,0,"
             "0,0.99,1\n");
  expect_input_error(run({"eval", "--model", "podee", "--in", "nocorners.csv", "--out", "r.csv"}),
                     {"missing column", "r0_x"}, {"zero.csv", "below.csv", "nocorners.csv"});
}

void expect_exr(const fs::path& p, int size) {
  const io::ExrFile f = io::read_exr(p);
  EXPECT_EQ(f.image.width, size) << p;
  for (const char* key : {"glintlab_figure", "glintlab_method", "glintlab_distance", "glintlab_spp",
                          "glintlab_version"})
    EXPECT_TRUE(f.attributes.count(key)) << p << " lacks " << key;
  f.image.channel("Y");
}

void expect_png(const fs::path& p) {
  const std::string bytes = read_text(p);
  ASSERT_GT(bytes.size(), 8u);
  EXPECT_EQ(bytes.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
}

TEST_F(PodeeCliTest, Table1Quick) {
  const RunResult r =
      run({"figure", "podee-table1", "--budget", "quick", "--out", "out", "--threads", "2"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const fs::path d = path("out/podee-table1");
  for (const char* m : {"reference64", "converged", "centre", "lean", "podee"})
    expect_exr(d / (std::string("d4_") + m + ".exr"), 128);
  expect_png(d / "table1.png");
  const io::CsvTable t = io::read_csv(d / "table1.csv");
  ASSERT_EQ(t.num_rows(), 15u);  // 3 distances × (4 methods + the 64-spp reference)
  EXPECT_EQ(cell_value(t, 2, t.column("paper_rmse")), 0.0826);
  for (std::size_t i = 0; i < 4; ++i) EXPECT_GT(t.number(i, t.column("rmse_vs_64spp")), 0.0);
  EXPECT_NE(read_text(d / "summary.md").find("0.0977"), std::string::npos);
}

TEST_F(PodeeCliTest, DistanceAndFlickerQuick) {
  RunResult r =
      run({"figure", "podee-fig4-distance", "--budget", "quick", "--out", "out", "--threads", "2"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const fs::path d = path("out/podee-fig4-distance");
  expect_exr(d / "d10_podee.exr", 128);
  expect_png(d / "error_vs_distance.png");
  EXPECT_EQ(io::read_csv(d / "error_vs_distance.csv").num_rows(), 12u);
  r = run({"figure", "podee-fig4-flicker", "--budget", "quick", "--out", "out", "--threads", "2"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const fs::path f = path("out/podee-fig4-flicker");
  expect_exr(f / "d4_podee_temporal_sd.exr", 128);
  // The temporal standard deviations as heat maps (per distance the three methods), each with
  // its colour bar, drawn from flicker_map.csv whose cells are the EXRs' pixels.
  expect_labelled_chart(f / "flicker.png", 9);
  const nlohmann::json manifest = chart_manifest(f / "flicker.png");  // outlives the loop
  for (const nlohmann::json& a : manifest["axes"]) {
    EXPECT_TRUE(a.value("map", false));
    EXPECT_NE(a.value("colorbar_label", "").find("temporal standard deviation"),
              std::string::npos);
  }
  EXPECT_FALSE(fs::exists(f / "flicker.panels.json"));
  const io::CsvTable cells = io::read_csv(f / "flicker_map.csv");
  ASSERT_EQ(cells.num_rows(), 9u * 128u * 128u);
  const Image sd = io::read_exr(f / "d4_podee_temporal_sd.exr").image;  // panel 1_2
  const std::size_t first = (3 + 2) * 128u * 128u;
  EXPECT_EQ(cells.text(first, cells.column("panel")), "1_2");
  EXPECT_NEAR(cells.number(first + 130, cells.column("temporal_sd")), sd.at(2, 1, 0), 1e-12);
  const io::CsvTable t = io::read_csv(f / "flicker.csv");
  EXPECT_EQ(t.num_rows(), 12u);
  EXPECT_EQ(t.number(0, t.column("ratio_to_centre")), 1.0);
}

}  // namespace
}  // namespace glintlab::cli_test
