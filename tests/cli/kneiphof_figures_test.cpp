// `glintlab figure kneiphof2024-*` --quick: each writes its EXR, PNG, CSV and summary.md; the
// numbers in them are the ones the paper's statements imply (p > 1 only at √α = 0.1, γ = 5° of
// Fig. 6; the shared-lobe subdivision is invariant; convergence as N_P grows); Table 1 reads its
// times only from --bench-from and says so in one sentence without them.
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
  // The p map is a heat map drawn by matplotlib from p_map.csv: one labelled panel, its colour bar
  // the value with its unit, the p > 1 cells named; the same bytes with one thread.
  expect_labelled_chart(d / "p_map.png", 1);
  const nlohmann::json m = chart_manifest(d / "p_map.png");
  EXPECT_NE(m.value("title", std::string()).find("p of Eq. 20"), std::string::npos);
  const nlohmann::json& a = m["axes"][0];
  EXPECT_EQ(a.value("xlabel", ""), "cap half-angle gamma [deg] (log spacing)");
  EXPECT_EQ(a.value("ylabel", ""), "sqrt(alpha) [1]");
  EXPECT_EQ(a.value("colorbar_label", ""), "cap probability p (Eq. 20) [1] (log scale)");
  EXPECT_TRUE(a.value("map", false) && a.value("legend", false));
  EXPECT_EQ(io::read_csv(d / "p_map.csv").num_rows(), 13u * 17u);
  ASSERT_EQ(
      run({"figure", "kneiphof2024-fig6", "--budget", "quick", "--out", "one", "--threads", "1"})
          .exit_code,
      0);
  EXPECT_EQ(read_text(path("one/kneiphof2024-fig6/p_map.png")), read_text(d / "p_map.png"));
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

// Without benchmark data the table says so in one sentence and shows only the paper's row: no
// column of nan, no CSV of ours, and no fixed path read behind the user's back (a glints.json in
// out/bench is ignored unless --bench-from names the folder).
TEST_F(KneiphofFigureTest, Table1WithoutBenchmarkDataSaysSo) {
  std::filesystem::create_directories(path("out/bench"));
  write_text(path("out/bench/glints.json"), "{\"benchmarks\": []}");
  const RunResult r = run({"figure", "kneiphof2024-table1", "--budget", "quick", "--out", "figs"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const fs::path d = path("figs/kneiphof2024-table1");
  EXPECT_FALSE(fs::exists(d / "table1.csv"));
  const std::string md = read_text(d / "summary.md");
  EXPECT_NE(md.find("No benchmark data: no benchmark folder was given"), std::string::npos) << md;
  EXPECT_NE(md.find("| area | 1.7 / 2.7 / 2.8 / 2.9 |"), std::string::npos) << md;
  for (const char* bad : {"nan", "NaN", "NOT FOUND"}) EXPECT_EQ(md.find(bad), std::string::npos);

  // A folder without the file: the same, naming the file it lacked.
  fs::create_directories(path("empty"));
  ASSERT_EQ(run({"figure", "kneiphof2024-table1", "--budget", "quick", "--out", "figs",
                 "--bench-from", "empty"})
                .exit_code,
            0);
  EXPECT_NE(read_text(d / "summary.md").find("`empty/glints.json` does not exist"),
            std::string::npos);
}

// The table reads its times from --bench-from DIR/glints.json; a row the JSON lacks shows —.
TEST_F(KneiphofFigureTest, Table1ReadsTheBenchFolder) {
  std::string rows;
  for (int light = 0; light < 3; ++light)
    for (int method = 0; method < 4; ++method) {
      if (light == 2 && method == 3) continue;  // one row missing
      rows += fmt::format(
          "{}{{\n      \"name\": \"table1/method:{}/light:{}\",\n      \"real_time\": {},\n"
          "      \"time_unit\": \"ns\"\n    }}",
          rows.empty() ? "" : ",\n    ", method, light, 10 * light + method + 0.5);
    }
  fs::create_directories(path("b"));
  write_text(path("b/glints.json"), "{\n  \"benchmarks\": [\n    " + rows + "\n  ]\n}\n");
  const RunResult r = run(
      {"figure", "kneiphof2024-table1", "--budget", "quick", "--out", "out", "--bench-from", "b"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const io::CsvTable t = io::read_csv(path("out/kneiphof2024-table1/table1.csv"));
  ASSERT_EQ(t.num_rows(), 3u);
  EXPECT_EQ(t.number(1, t.column("deliot_belcour_ns")), 11.5);
  EXPECT_EQ(t.number(2, t.column("kneiphof_klein_ns")), 22.5);
  const std::string md = read_text(path("out/kneiphof2024-table1/summary.md"));
  EXPECT_NE(md.find("read from `b/glints.json`"), std::string::npos) << md;
  EXPECT_NE(md.find("| area | 20.5 | 21.5 | 22.5 | — |"), std::string::npos) << md;
  for (const char* bad : {"nan", "NaN", "NOT FOUND", "No benchmark data"})
    EXPECT_EQ(md.find(bad), std::string::npos) << bad;
}

// --bench-from names a folder that is not there: one line naming the option, no output.
TEST_F(KneiphofFigureTest, BenchFromMissingFolderIsOneLine) {
  expect_input_error(run({"figure", "kneiphof2024-table1", "--budget", "quick", "--out", "out",
                          "--bench-from", "nowhere"}),
                     {"--bench-from", "'nowhere'", "glints.json", "kemppinen.json"}, {});
}

}  // namespace
}  // namespace glintlab::cli_test
