// `glintlab models` and `glintlab eval --model`: the listing, values that match the kernels, and
// one-line errors for bad models, parameters and columns.
#include <gtest/gtest.h>

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

}  // namespace
}  // namespace glintlab::cli_test
