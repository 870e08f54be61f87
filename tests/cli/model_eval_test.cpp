// `glintlab models` and `glintlab eval --model`: the listing, values that match the kernels, and
// one-line errors for bad models, parameters and columns.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "cli/cli_test_util.h"
#include "core/ndf/microfacet.h"
#include "core/samplers/bounded_vndf.h"

namespace glintlab::cli_test {
namespace {

using ModelEvalTest = CliTest;

TEST_F(ModelEvalTest, ModelsListsParametersDefaultsAndRanges) {
  const RunResult r = run({"models"});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  for (const char* s : {"smooth_ggx", "smooth_beckmann", "alpha_x=0.5", "[0.0001, 100]",
                        "one of: ndf, vndf, spherical_caps, bounded_caps", "intermediates: h_x",
                        "needs: directions only"}) {
    EXPECT_NE(r.out.find(s), std::string::npos) << s;
  }
}

TEST_F(ModelEvalTest, EvaluatesTheKernel) {
  write_text(path("q.csv"),
             "wi_x,wi_y,wi_z,wo_x,wo_y,wo_z\n0.6,0,0.8,-0.36,0.48,0.8\n0,0,1,0.6,0,0.8\n");
  const RunResult r =
      run({"eval", "--model", "smooth_ggx", "--param", "alpha_x=0.3", "--param", "alpha_y=0.6",
           "--param", "sampler=bounded_caps", "--in", "q.csv", "--out", "r.csv"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const io::CsvTable t = io::read_csv(path("r.csv"));
  ASSERT_EQ(t.num_rows(), 2u);
  const GGX<double> ggx{0.3, 0.6};
  const Vec3<double> wi{0.6, 0, 0.8}, wo{-0.36, 0.48, 0.8};
  EXPECT_EQ(cell_value(t, 0, t.column("value")), microfacet_brdf(ggx, wi, wo, 1.0) * wo.z);
  EXPECT_EQ(cell_value(t, 0, t.column("pdf")), pdf_bounded_vndf(ggx, wi, wo));
  EXPECT_EQ(cell_value(t, 0, t.column("D")), ggx.D(half_vector(wi, wo)));
  EXPECT_EQ(cell_value(t, 1, t.column("light_cos_half_angle")), 1.0);  // default filled in
  EXPECT_EQ(cell_value(t, 1, t.column("u")), 0.0);
}

TEST_F(ModelEvalTest, BadModelParameterOrColumnIsOneLine) {
  write_text(path("q.csv"), "wi_x,wi_y,wi_z,wo_x,wo_y,wo_z\n0,0,1,0,0,1\n");
  expect_input_error(run({"eval", "--model", "phong", "--in", "q.csv", "--out", "r.csv"}),
                     {"--model", "'phong'", "smooth_ggx"}, {"q.csv"});
  expect_input_error(run({"eval", "--model", "smooth_ggx", "--param", "alpha_x=-1", "--in", "q.csv",
                          "--out", "r.csv"}),
                     {"--param alpha_x", "[0.0001, 100]"}, {"q.csv"});
  expect_input_error(
      run({"eval", "--model", "smooth_ggx", "--param", "alpha", "--in", "q.csv", "--out", "r.csv"}),
      {"--param", "name=value"}, {"q.csv"});
  expect_input_error(run({"eval", "--param", "alpha_x=1", "--in", "q.csv", "--out", "r.csv"}),
                     {"--param", "needs --model"}, {"q.csv"});
  write_text(path("bad.csv"), "wi_x,wi_y,wi_z,wo_x,wo_y\n0,0,1,0,0\n");
  expect_input_error(run({"eval", "--model", "smooth_ggx", "--in", "bad.csv", "--out", "r.csv"}),
                     {"missing column(s) wo_z"}, {"q.csv", "bad.csv"});
  write_text(path("nonunit.csv"), "wi_x,wi_y,wi_z,wo_x,wo_y,wo_z\n0,0,1,0,0,1\n0,0,2,0,0,1\n");
  expect_input_error(
      run({"eval", "--model", "smooth_ggx", "--in", "nonunit.csv", "--out", "r.csv"}),
      {"data row 2", "wi", "not unit"}, {"q.csv", "bad.csv", "nonunit.csv"});
}

// --grid fills only the directions: a model that needs a footprint or a light takes those columns
// from --query, as sample --model does; without them it is an error naming them (it used to
// evaluate a zero footprint, value 0 everywhere, without a word), as a file without them is.
TEST_F(ModelEvalTest, GridNeedsTheModelsQueryColumns) {
  const std::vector<std::string> grid = {"eval",
                                         "--model",
                                         "deliot_belcour",
                                         "--grid",
                                         "theta_i=30:30:1,theta_o=0:60:3,phi_o=180:180:1",
                                         "--out",
                                         "r.csv"};
  expect_input_error(run(grid),
                     {"--query", "deliot_belcour", "u, v, dudx, dvdx, dudy, dvdy",
                      "light_cos_half_angle, light_intensity"},
                     {});
  std::vector<std::string> partial = grid;
  partial.insert(partial.end(), {"--query", "u=0.5,v=0.5"});
  expect_input_error(run(partial), {"--query", "dudx, dvdx, dudy, dvdy"}, {});
  std::vector<std::string> bad_light = grid;
  bad_light.insert(bad_light.end(), {"--query",
                                     "u=0.5,v=0.5,dudx=1e-3,dvdx=0,dudy=0,dvdy=1e-3,"
                                     "light_cos_half_angle=2,light_intensity=1"});
  expect_input_error(run(bad_light), {"--query light_cos_half_angle"}, {});
  expect_input_error(run({"eval", "--model", "smooth_ggx", "--grid", "theta_i=0:60:3", "--query",
                          "u=0.5", "--out", "r.csv"}),
                     {"--query", "only the directions"}, {});
  write_text(path("q.csv"), "wi_x,wi_y,wi_z,wo_x,wo_y,wo_z\n0,0,1,0,0,1\n");
  expect_input_error(
      run({"eval", "--model", "smooth_ggx", "--in", "q.csv", "--query", "u=0.5", "--out", "r.csv"}),
      {"--query", "only with --grid"}, {"q.csv"});
  expect_input_error(run({"eval", "--in", "q.csv", "--query", "u=0.5", "--out", "r.csv"}),
                     {"--query", "needs --model"}, {"q.csv"});
  // From a file, the same columns are required in its header.
  expect_input_error(run({"eval", "--model", "deliot_belcour", "--in", "q.csv", "--out", "r.csv"}),
                     {"missing column(s) u, v, dudx, dvdx, dudy, dvdy, light_cos_half_angle, "
                      "light_intensity",
                      "deliot_belcour"},
                     {"q.csv"});
}

// The grid's rows with --query are the rows --in would give: the same query columns, the same
// value, pdf and intermediates.
TEST_F(ModelEvalTest, GridWithQueryEqualsTheSameRowsFromAFile) {
  const RunResult g = run({"eval", "--model", "deliot_belcour", "--grid",
                           "theta_i=0:60:3,phi_i=0:0:1,theta_o=0:60:4,phi_o=180:180:1", "--query",
                           "u=0.25,v=0.5,dudx=0.004,dvdx=-0.001,dudy=0.001,dvdy=0.003,"
                           "light_cos_half_angle=0.999,light_intensity=2",
                           "--out", "grid.csv"});
  ASSERT_EQ(g.exit_code, 0) << g.err;
  const io::CsvTable t = io::read_csv(path("grid.csv"));
  ASSERT_EQ(t.num_rows(), 12u);
  const std::vector<std::string> columns = {"wi_x",
                                            "wi_y",
                                            "wi_z",
                                            "wo_x",
                                            "wo_y",
                                            "wo_z",
                                            "u",
                                            "v",
                                            "dudx",
                                            "dvdx",
                                            "dudy",
                                            "dvdy",
                                            "light_cos_half_angle",
                                            "light_intensity"};
  std::string csv;
  for (std::size_t c = 0; c < columns.size(); ++c) csv += (c ? "," : "") + columns[c];
  csv += "\n";
  for (std::size_t r = 0; r < t.num_rows(); ++r) {
    EXPECT_EQ(cell_value(t, r, t.column("u")), 0.25);
    EXPECT_EQ(cell_value(t, r, t.column("light_intensity")), 2.0);
    for (std::size_t c = 0; c < columns.size(); ++c)
      csv += (c ? "," : "") + std::string(t.text(r, t.column(columns[c])));
    csv += "\n";
  }
  write_text(path("rows.csv"), csv);
  const RunResult f =
      run({"eval", "--model", "deliot_belcour", "--in", "rows.csv", "--out", "file.csv"});
  ASSERT_EQ(f.exit_code, 0) << f.err;
  const io::CsvTable u = io::read_csv(path("file.csv"));
  ASSERT_EQ(u.num_rows(), t.num_rows());
  for (std::size_t r = 0; r < t.num_rows(); ++r)
    for (const char* c : {"value", "pdf", "N_P", "p", "count", "D"})
      EXPECT_EQ(t.text(r, t.column(c)), u.text(r, u.column(c))) << c << " row " << r;
}

}  // namespace
}  // namespace glintlab::cli_test
