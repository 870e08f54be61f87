// `glintlab eval --model kneiphof_klein_area`: a rectangular light along wo; the output has N_P,
// p before and after the clamp, the count and the radiance factor; a tilt of 90° (the light
// edge-on, its plane through the shading point) and γ = 0 for kneiphof_klein are one-line errors.
#include <gtest/gtest.h>

#include <string>

#include "cli/cli_test_util.h"
#include "core/io/csv.h"

namespace glintlab::cli_test {
namespace {

using KneiphofAreaEvalTest = CliTest;

TEST_F(KneiphofAreaEvalTest, GridShowsTheCountingIntermediates) {
  const RunResult r =
      run({"eval", "--model", "kneiphof_klein_area", "--param", "light_width=0.3", "--param",
           "alpha=0.04", "--grid", "theta_i=30:30:1,phi_i=180:180:1,theta_o=0:60:7", "--query",
           "u=0.5,v=0.5,dudx=0.01,dvdx=0,dudy=0,dvdy=0.01,"
           "light_cos_half_angle=1,light_intensity=1",
           "--out", "r.csv"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const io::CsvTable t = io::read_csv(path("r.csv"));
  ASSERT_EQ(t.num_rows(), 7u);
  for (const char* c : {"N_P", "p_unclamped", "p", "p_clamped", "count", "factor", "D_PR"})
    EXPECT_TRUE(t.find_column(c).has_value()) << c;
  // θo = 30°, the mirror direction of the view: the largest p.
  double best = 0;
  std::size_t at = 0;
  for (std::size_t i = 0; i < 7; ++i)
    if (t.number(i, t.column("p")) > best) best = t.number(i, t.column("p")), at = i;
  EXPECT_EQ(at, 3u);
}

TEST_F(KneiphofAreaEvalTest, BadLightAndCapAreOneLineErrors) {
  expect_input_error(run({"eval", "--model", "kneiphof_klein_area", "--param", "light_tilt_deg=90",
                          "--grid", "theta_i=0:0:1", "--out", "r.csv"}),
                     {"light_tilt_deg", "(-90, 90)"}, {});
  expect_input_error(run({"eval", "--model", "kneiphof_klein", "--param", "gamma_deg=0", "--grid",
                          "theta_i=0:0:1", "--out", "r.csv"}),
                     {"gamma_deg", "(0, 90)"}, {});
}

}  // namespace
}  // namespace glintlab::cli_test
