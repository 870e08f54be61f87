// `glintlab figure kemppinen2025-table3 / kemppinen2025-speed-accuracy --quick` without and with a
// benchmark JSON (rows read from it, the others measured in process and marked so), and the
// triplanar mode of the Kemppinen models through `glintlab eval` (equal to uv on the plane ⊥ z,
// one-line errors for bad values).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "cli/chart_png.h"
#include "cli/cli_test_util.h"

namespace glintlab::cli_test {
namespace {

namespace fs = std::filesystem;
using KemppinenTimingTest = CliTest;

TEST_F(KemppinenTimingTest, Table3WithoutJsonMeasuresInProcess) {
  const RunResult r = run({"figure", "kemppinen2025-table3", "--budget", "quick", "--out", "out"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const io::CsvTable t = io::read_csv(path("out/kemppinen2025-table3/table3.csv"));
  ASSERT_EQ(t.num_rows(), 8u);  // 2 NDFs × 2 planes × 2 roughnesses
  for (std::size_t i = 0; i < t.num_rows(); ++i) {
    EXPECT_GT(t.number(i, t.column("ns_per_pixel")), 0);
    EXPECT_GT(t.number(i, t.column("paper_rtx3090_ms_per_frame")), 1);
    EXPECT_EQ(t.text(i, t.column("time_source")), "in_process_thread_cputime");
  }
  const std::string md = read_text(path("out/kemppinen2025-table3/summary.md"));
  EXPECT_NE(md.find("No benchmark data: no benchmark folder was given"), std::string::npos);
  EXPECT_NE(md.find("glintlab_bench_kemppinen --benchmark_out=out/bench/kemppinen.json"),
            std::string::npos);
  EXPECT_NE(md.find("--bench-from out/bench"), std::string::npos);
  for (const char* bad : {"nan", "NaN", "NOT FOUND"}) EXPECT_EQ(md.find(bad), std::string::npos);
  EXPECT_NE(md.find("3.26/1.70"), std::string::npos);  // the paper's number beside ours
}

// A --bench-from folder whose JSON has one Table 3 row and one method row: those are read
// (1e9/items_per_second, the counters), every other row is measured.
TEST_F(KemppinenTimingTest, FiguresReadTheBenchmarkJson) {
  fs::create_directories(path("out/bench"));
  write_text(path("out/bench/kemppinen.json"), R"({"context": {}, "benchmarks": [
 {"name": "table3/ndf:ggx/plane:25/roughness:low/model:kemppinen",
  "run_name": "table3/ndf:ggx/plane:25/roughness:low/model:kemppinen", "run_type": "iteration",
  "iterations": 10, "real_time": 1234.5, "cpu_time": 1234.0, "time_unit": "ns",
  "items_per_second": 8.0e5},
 {"name": "method/kemppinen_ggx.dstar_f_vs_smooth/k=4,erf=fast",
  "run_name": "method/kemppinen_ggx.dstar_f_vs_smooth/k=4,erf=fast", "run_type": "iteration",
  "iterations": 10, "real_time": 900, "cpu_time": 900, "time_unit": "ns",
  "items_per_second": 2.0e6, "err_max": 0.5, "err_rms": 0.125, "err_p99": 0.25, "err_n": 1024,
  "label": "x"}]})");
  ASSERT_EQ(run({"figure", "kemppinen2025-table3", "--budget", "quick", "--out", "out",
                 "--bench-from", "out/bench"})
                .exit_code,
            0);
  const io::CsvTable t = io::read_csv(path("out/kemppinen2025-table3/table3.csv"));
  int from_json = 0;
  for (std::size_t i = 0; i < t.num_rows(); ++i) {
    if (t.text(i, t.column("time_source")) != "google_benchmark_json") continue;
    ++from_json;
    EXPECT_EQ(t.text(i, t.column("ndf")), "ggx");
    EXPECT_EQ(t.number(i, t.column("plane_deg")), 25);
    EXPECT_DOUBLE_EQ(t.number(i, t.column("ns_per_pixel")), 1250.0);
  }
  EXPECT_EQ(from_json, 1);

  const RunResult r = run({"figure", "kemppinen2025-speed-accuracy", "--budget", "quick", "--out",
                           "out", "--bench-from", "out/bench"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const fs::path d = path("out/kemppinen2025-speed-accuracy");
  const io::CsvTable s = io::read_csv(d / "speed_accuracy.csv");
  ASSERT_EQ(s.num_rows(), 50u);  // 2 NDFs × (16 vs Eq. 5 + the reference + 8 vs D)
  int read = 0;
  for (std::size_t i = 0; i < s.num_rows(); ++i) {
    const bool json = s.text(i, s.column("time_source")) == "google_benchmark_json";
    if (json) {
      ++read;
      EXPECT_EQ(s.text(i, s.column("setting")), "k=4;erf=fast");
      EXPECT_DOUBLE_EQ(s.number(i, s.column("ns_per_eval")), 500.0);
      EXPECT_EQ(s.number(i, s.column("err_rms")), 0.125);
      EXPECT_EQ(s.number(i, s.column("err_n")), 1024);
    } else {
      EXPECT_GT(s.number(i, s.column("ns_per_eval")), 0);
      EXPECT_GT(s.number(i, s.column("err_n")), 0);
      EXPECT_GE(s.number(i, s.column("err_rms")), 0);
    }
  }
  EXPECT_EQ(read, 1);
  // Drawn by matplotlib from their chart specs: one labelled panel per NDF, and time and points
  // visited against the footprint.
  expect_labelled_chart(d / "speed_accuracy.png", 2);
  expect_labelled_chart(d / "cost_vs_footprint.png", 2);
  const std::string md = read_text(d / "summary.md");
  EXPECT_NE(md.find("in_process_thread_cputime"), std::string::npos);
  EXPECT_NE(md.find("are from `out/bench/kemppinen.json`"), std::string::npos);
  EXPECT_EQ(md.find("No benchmark data"), std::string::npos);
}

// The constant-time claim's picture: Algorithm 1 visits 2k² cell pairs at every footprint, the
// brute force more as the footprint grows; far-field error of k = 16 no worse than k = 1.
TEST_F(KemppinenTimingTest, SpeedAccuracyWithoutJson) {
  ASSERT_EQ(run({"figure", "kemppinen2025-speed-accuracy", "--budget", "quick", "--out", "out"})
                .exit_code,
            0);
  const fs::path d = path("out/kemppinen2025-speed-accuracy");
  const io::CsvTable c = io::read_csv(d / "cost_vs_footprint.csv");
  double bf_first = NAN, bf_last = NAN;
  for (std::size_t i = 0; i < c.num_rows(); ++i) {
    const std::string m(c.text(i, c.column("method")));
    if (c.text(i, c.column("time_source")) == "not_measured") continue;
    const double pts = c.number(i, c.column("points_visited"));
    if (m == "constant_time") {
      const double k = c.number(i, c.column("k"));
      EXPECT_EQ(pts, 2 * k * k);
    } else {
      if (std::isnan(bf_first)) bf_first = pts;
      bf_last = pts;
    }
  }
  EXPECT_GT(bf_last, 10 * bf_first);
  const std::string md = read_text(d / "summary.md");
  EXPECT_NE(md.find("No benchmark data"), std::string::npos);
  for (const char* bad : {"nan", "NaN", "NOT FOUND"}) EXPECT_EQ(md.find(bad), std::string::npos);
}

TEST_F(KemppinenTimingTest, EvalTriplanarOnTheZPlaneEqualsUv) {
  write_text(path("q.csv"),
             "wi_x,wi_y,wi_z,wo_x,wo_y,wo_z,u,v,dudx,dvdx,dudy,dvdy\n"
             "0.6,0,0.8,-0.36,0.48,0.8,0.31,0.72,0.004,0,0,0.004\n"
             "0,0,1,0.1,0,0.994987437106620,1.7,-2.2,0.02,0.001,0,0.02\n");
  const RunResult a = run({"eval", "--model", "kemppinen_ggx", "--param", "mapping=uv", "--in",
                           "q.csv", "--out", "a.csv"});
  ASSERT_EQ(a.exit_code, 0) << a.err;
  const RunResult b = run({"eval", "--model", "kemppinen_ggx", "--param", "mapping=triplanar",
                           "--in", "q.csv", "--out", "b.csv"});
  ASSERT_EQ(b.exit_code, 0) << b.err;
  const RunResult c =
      run({"eval", "--model", "kemppinen_ggx", "--param", "mapping=triplanar", "--param",
           "normal_theta=60", "--param", "normal_phi=30", "--in", "q.csv", "--out", "c.csv"});
  ASSERT_EQ(c.exit_code, 0) << c.err;
  const io::CsvTable ta = io::read_csv(path("a.csv")), tb = io::read_csv(path("b.csv")),
                     tc = io::read_csv(path("c.csv"));
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(ta.text(i, ta.column("D_star_f")), tb.text(i, tb.column("D_star_f")));
    EXPECT_EQ(ta.text(i, ta.column("pdf")), tb.text(i, tb.column("pdf")));
    EXPECT_EQ(3 * ta.number(i, ta.column("points_visited")),
              tc.number(i, tc.column("points_visited")));
  }
  EXPECT_NE(ta.text(0, ta.column("D_star_f")), tc.text(0, tc.column("D_star_f")));
}

TEST_F(KemppinenTimingTest, BadTriplanarParametersAreOneLine) {
  write_text(path("q.csv"),
             "wi_x,wi_y,wi_z,wo_x,wo_y,wo_z,u,v,dudx,dvdx,dudy,dvdy\n"
             "0,0,1,0,0,1,0.3,0.7,0.004,0,0,0.004\n");
  expect_input_error(run({"eval", "--model", "kemppinen_ggx", "--param", "mapping=cubic", "--in",
                          "q.csv", "--out", "r.csv"}),
                     {"mapping", "uv", "triplanar"}, {"q.csv"});
  expect_input_error(run({"eval", "--model", "kemppinen_beckmann", "--param", "normal_theta=200",
                          "--in", "q.csv", "--out", "r.csv"}),
                     {"normal_theta", "180"}, {"q.csv"});
  expect_input_error(run({"eval", "--model", "kemppinen_ggx", "--param", "normal_phi=nan", "--in",
                          "q.csv", "--out", "r.csv"}),
                     {"normal_phi"}, {"q.csv"});
}

}  // namespace
}  // namespace glintlab::cli_test
