// `glintlab figure kneiphof2024-*` --quick: each writes its EXR, PNG, CSV and summary.md; the
// numbers in them are the ones the paper's statements imply (p > 1 only at √α = 0.1, γ = 5° of
// Fig. 6; the shared-lobe subdivision is invariant; convergence as N_P grows); and
// `glintlab eval --model kneiphof_klein` exposes the intermediates and rejects γ = 0.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "cli/cli_test_util.h"
#include "core/io/csv.h"
#include "core/io/exr.h"

namespace glintlab::cli_test {
namespace {

namespace fs = std::filesystem;
using KneiphofFigureTest = CliTest;

void expect_png(const fs::path& p) {
  const std::string bytes = read_text(p);
  ASSERT_GT(bytes.size(), 8u);
  EXPECT_EQ(bytes.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
}

TEST_F(KneiphofFigureTest, Fig6) {
  const RunResult r = run({"figure", "kneiphof2024-fig6", "--budget", "quick", "--out", "out"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const fs::path d = path("out/kneiphof2024-fig6");
  expect_png(d / "fig6.png");
  expect_png(d / "p_map.png");
  io::read_exr(d / "sa0.1_gamma5.exr").image.channel("p_clamped");
  const io::CsvTable t = io::read_csv(d / "fig6.csv");
  ASSERT_EQ(t.num_rows(), 6u);
  for (std::size_t i = 0; i < 6; ++i) {
    const bool over = t.number(i, t.column("p_gt_1")) > 0;
    const bool expect_over =
        t.number(i, t.column("sqrt_alpha")) == 0.1 && t.number(i, t.column("gamma_deg")) == 5;
    EXPECT_EQ(over, expect_over) << i;
  }
  EXPECT_TRUE(fs::exists(d / "summary.md"));
}

TEST_F(KneiphofFigureTest, Fig9) {
  const RunResult r = run({"figure", "kneiphof2024-fig9", "--budget", "quick", "--out", "out"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const fs::path d = path("out/kneiphof2024-fig9");
  expect_png(d / "fig9.png");
  io::read_exr(d / "halfwidth0.4.exr").image.channel("subdivided_mc");
  io::read_exr(d / "halfwidth0.4.exr").image.channel("subdivided_ltc");
  const io::CsvTable t = io::read_csv(d / "fig9.csv");
  ASSERT_EQ(t.num_rows(), 2u);
  // The single LTC lobe is invariant under subdivision (App. C) up to rounding; the Monte Carlo
  // terms are not.
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_LT(t.number(i, t.column("max_rel_subdivided_ltc_vs_single_ltc")), 1e-9);
    EXPECT_GT(t.number(i, t.column("rel_rms_subdivided_mc_vs_single_mc")), 1e-6);
  }
}

TEST_F(KneiphofFigureTest, Fig10) {
  const RunResult r = run({"figure", "kneiphof2024-fig10", "--budget", "quick", "--out", "out"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const fs::path d = path("out/kneiphof2024-fig10");
  expect_png(d / "fig10.png");
  io::read_exr(d / "sa0.5_small_area.exr").image.channel("glint");
  const io::CsvTable t = io::read_csv(d / "fig10.csv");
  ASSERT_EQ(t.num_rows(), 72u);  // 3 roughnesses × 3 lights × 8 strips
  // For √α ≥ 0.5 the last strip has N_P p ≫ 1 in the highlight: near the smooth BRDF. (At √α = 0.1
  // the highlight is a few pixels of sparse bright glints at these densities: not asserted.)
  for (std::size_t k = 0; k < 72; k += 8) {
    if (t.number(k, t.column("sqrt_alpha")) < 0.5) continue;
    const double first = t.number(k, t.column("rel_rms_vs_smooth"));
    const double last = t.number(k + 7, t.column("rel_rms_vs_smooth"));
    EXPECT_LT(last, first) << t.text(k, t.column("light"));
    EXPECT_LT(last, 0.2) << t.text(k, t.column("light"));
  }
}

TEST_F(KneiphofFigureTest, Table1WithoutBenchmarkJson) {
  const RunResult r = run({"figure", "kneiphof2024-table1", "--budget", "quick", "--out", "out"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const io::CsvTable t = io::read_csv(path("out/kneiphof2024-table1/table1.csv"));
  ASSERT_EQ(t.num_rows(), 3u);
  EXPECT_NE(read_text(path("out/kneiphof2024-table1/summary.md")).find("NOT FOUND"),
            std::string::npos);
}

}  // namespace
}  // namespace glintlab::cli_test
