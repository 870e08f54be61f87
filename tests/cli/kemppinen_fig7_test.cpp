// `glintlab figure kemppinen2025-fig7 --quick`: the environment-light convergence figure's EXR
// (with attributes), PNGs, CSVs and summary, and the convergence property it shows.
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
class KemppinenFig7Test : public CliTest {};

TEST_F(KemppinenFig7Test, ConvergenceUnderEnvironmentLight) {
  const std::string id = "kemppinen2025-fig7";
  const RunResult r = run({"figure", id, "--budget", "quick", "--out", "out", "--threads", "2"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const fs::path d = path("out/" + id);
  for (const char* ndf : {"ggx", "beckmann"}) {
    for (const std::string f :
         {"reference", "glinty_is_4spp", "glinty_is_printed_pdf_4spp", "smooth_ndf_is_4spp"}) {
      const io::ExrFile e = io::read_exr(d / (std::string(ndf) + "_" + f + ".exr"));
      EXPECT_EQ(e.attributes.at("glintlab_model"), std::string("kemppinen_") + ndf);
      EXPECT_TRUE(e.attributes.count("glintlab_seed"));
      EXPECT_GE(e.image.width, 128);  // a render panel a person can see
      EXPECT_GE(e.image.height, 128);
      for (double v : e.image.data) ASSERT_TRUE(std::isfinite(v) && v >= 0) << ndf << " " << f;
    }
  }
  EXPECT_EQ(read_text(d / "fig7_images.png").substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  expect_labelled_chart(d / "fig7_rmse_spp.png", 2);  // matplotlib, one panel per NDF
  EXPECT_NE(read_text(d / "summary.md").find("128 spp"), std::string::npos);
  const io::CsvTable t = io::read_csv(d / "rmse_spp.csv");
  ASSERT_EQ(t.num_rows(), 2u * 3u * 5u);  // NDFs × strategies × spp 1..16
  for (std::size_t i = 0; i < t.num_rows(); ++i) {
    EXPECT_GT(t.number(i, t.column("rmse")), 0.0) << "row " << i;
    EXPECT_EQ(t.number(i, t.column("reference_spp")), 128.0);
  }
  // Unbiased strategies converge as spp^−½ (a loose band on the raw slope, which the 128-spp
  // reference's noise flattens; a tight one once that noise is subtracted: 128² pixels, 5 points);
  // glinty IS has the lower error at 1 spp in this glinty setting (the figure's point).
  const io::CsvTable s = io::read_csv(d / "loglog_slopes.csv");
  ASSERT_EQ(s.num_rows(), 6u);
  double rmse1[2][3] = {};
  for (std::size_t i = 0; i < s.num_rows(); ++i) {
    const std::string strategy(s.text(i, s.column("strategy")));
    const int n = s.text(i, s.column("ndf")) == "ggx" ? 1 : 0;
    const int k = strategy == "glinty_is" ? 0 : strategy == "smooth_ndf_is" ? 2 : 1;
    rmse1[n][k] = s.number(i, s.column("rmse_at_1spp"));
    if (k != 1) {
      EXPECT_GT(s.number(i, s.column("slope")), -0.7) << strategy;
      EXPECT_LT(s.number(i, s.column("slope")), -0.3) << strategy;
      EXPECT_NEAR(s.number(i, s.column("slope_minus_reference_noise")), -0.5, 0.05) << strategy;
    }
  }
  for (int n = 0; n < 2; ++n) EXPECT_LT(rmse1[n][0], rmse1[n][2]) << "ndf " << n;
}

}  // namespace
}  // namespace glintlab::cli_test
