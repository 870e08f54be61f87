// `glintlab adequacy`: the quick table, maps and index for one model, identical output (timing
// columns aside) for any --threads, and the bad-input errors (one line, exit 2, nothing written).
#include <gtest/gtest.h>

#include <array>
#include <cstdlib>
#include <filesystem>
#include <set>
#include <nlohmann/json.hpp>

#include "cli/chart_png.h"
#include "cli/cli_test_util.h"
#include "core/io/csv.h"

namespace glintlab::cli_test {
namespace {

namespace fs = std::filesystem;
using AdequacyTest = CliTest;

// The table priced by benchmark costs (--bench-from): with the exact count cheaper than the two
// approximations (as measured on CPUs), the cheapest adequate level by the benchmark is smooth
// where smooth is adequate and exact everywhere else, and the totals are the costs summed.
TEST_F(AdequacyTest, QuickRunWritesTableAndMaps) {
  fs::create_directories(path("bench"));
  write_text(path("bench/glints.json"), level_costs_json({"kneiphof_klein"}, {10, 200, 300, 100}));
  const RunResult r = run({"adequacy", "--budget", "quick", "--models", "kneiphof_klein",
                           "--out", "a", "--threads", "2", "--bench-from", "bench"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("cheapest adequate level by the benchmark"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("324 cells"), std::string::npos) << r.out;  // 9 × 2 × 3 × 3 × 2
  const auto doc = nlohmann::json::parse(read_text(path("a/adequacy.json")));
  EXPECT_EQ(doc["threshold"], 0.02);
  EXPECT_EQ(doc["cells"].size(), 324u);
  EXPECT_EQ(doc["maps"].size(), 6u);
  for (const auto& m : doc["maps"]) {
    // Drawn by matplotlib: a title, labelled axes with units, the levels as its colour scale.
    const fs::path png = path("a") / m["png"].get<std::string>();
    expect_labelled_chart(png, 1);
    const nlohmann::json chart = chart_manifest(png);
    EXPECT_NE(chart["axes"][0].value("title", "").find("kneiphof_klein"), std::string::npos);
    EXPECT_EQ(chart["axes"][0].value("xlabel", ""), "footprint size N_P [expected facets]");
    EXPECT_TRUE(fs::exists(path("a") / m["exr"].get<std::string>()));
  }
  // The maps' cells as drawn: 324 cells, each with its level and its row's predicted boundary.
  EXPECT_EQ(io::read_csv(path("a/adequacy-levels.csv")).num_rows(), 324u);
  EXPECT_EQ(io::read_csv(path("a/adequacy.csv")).num_rows(), 324u);
  // Every level appears somewhere in 1 .. 1e8 facets except possibly small_count.
  std::size_t smooth = doc["summary"]["chosen"]["smooth"], exact = doc["summary"]["chosen"]["exact"];
  EXPECT_GT(smooth, 0u);
  EXPECT_GT(exact, 0u);
  EXPECT_EQ(doc["summary"]["chooser_refuted"], 0);
  // adequacy.csv, .json, adequacy-levels.csv and per map its EXR, PNG and chart spec.
  EXPECT_EQ(unexpected_files(path("a"), {}).size(), 3u + 18u);
  const auto& costs = doc["benchmark_costs"];
  ASSERT_TRUE(costs.is_object());
  EXPECT_EQ(costs["exact_ns_total"], 100.0 * 324);
  EXPECT_EQ(costs["ns_per_eval"]["kneiphof_klein"]["realtime"], 200.0);
  std::size_t by_bench_smooth = 0;
  double cheapest_total = 0;
  for (const auto& c : doc["cells"]) {
    const bool smooth_ok = c["levels"]["smooth"]["adequate"];
    EXPECT_EQ(c["cheapest_by_benchmark"], smooth_ok ? "smooth" : "exact") << c.dump();
    by_bench_smooth += smooth_ok ? 1 : 0;
    cheapest_total += smooth_ok ? 10 : 100;
  }
  EXPECT_EQ(costs["cheapest_by_benchmark"]["smooth"], by_bench_smooth);
  EXPECT_DOUBLE_EQ(costs["cheapest_ns_total"].get<double>(), cheapest_total);
  const auto header = io::read_csv(path("a/adequacy.csv")).header();
  ASSERT_GE(header.size(), 4u);
  EXPECT_EQ(header[header.size() - 4], "cheapest_by_benchmark");
  EXPECT_EQ(header.back(), "bench_cheapest_ns");
}

// The run on two threads draws its maps with matplotlib, the run on one thread with the stand-in
// (CliTest::stand_in_charts): its PNG is then its chart spec's and data's bytes, compared with the
// two-thread run's spec and data (the same spec and data are the same PNG in any run:
// FigureChartsTest.SeveralFoldersInOneRunAreTheBytesOfSeparateRunsOrNone). At 1000 positions per
// cell (--positions), which the table records.
TEST_F(AdequacyTest, OutputDoesNotDependOnThreads) {
  for (const char* t : {"2", "1"}) {
    if (t[0] == '1') stand_in_charts();
    ASSERT_EQ(run({"adequacy", "--models", "deliot_belcour", "--positions", "1000", "--out",
                   std::string("t") + t, "--threads", t})
                  .exit_code,
              0);
  }
  EXPECT_EQ(nlohmann::json::parse(read_text(path("t2/adequacy.json")))["samples_per_cell"], 1000);
  // Every line up to the four *_ns columns, cheapest_measured and time_saved_ns (timing, last) is identical.
  const auto without_timing = [](const std::string& line) {
    std::size_t cut = line.size();
    for (int k = 0; k < 6; ++k) cut = line.rfind(',', cut - 1);
    return line.substr(0, cut);
  };
  // Without --bench-from the table has no benchmark columns and says how to get them.
  EXPECT_EQ(nlohmann::json::parse(read_text(path("t1/adequacy.json")))["benchmark_costs"],
            nullptr);
  const auto a = lines_of(read_text(path("t1/adequacy.csv")));
  const auto b = lines_of(read_text(path("t2/adequacy.csv")));
  ASSERT_EQ(a.size(), b.size());
  ASSERT_GT(a.size(), 100u);
  for (std::size_t i = 0; i < a.size(); ++i) EXPECT_EQ(without_timing(a[i]), without_timing(b[i])) << i;
  // The maps: the same cells, the same chart specs and data (every map).
  EXPECT_EQ(read_text(path("t1/adequacy-levels.csv")), read_text(path("t2/adequacy-levels.csv")));
  std::size_t maps = 0;
  for (const auto& e : fs::directory_iterator(path("t2"))) {
    if (e.path().extension() != ".png") continue;
    const std::string stem = e.path().stem().string();
    const std::string spec = read_text(path("t2") / (stem + ".chart.json"));
    const std::string csv = nlohmann::json::parse(spec).at("csv").get<std::string>();
    EXPECT_EQ(read_text(path("t1") / (stem + ".png")), spec + read_text(path("t2") / csv)) << stem;
    EXPECT_TRUE(chart_manifest(e.path()).is_object()) << stem;  // matplotlib's
    ++maps;
  }
  EXPECT_EQ(maps, 6u);
}

// The maps' chart script failing is the run's one-line error, exit 2, and no map PNG (the script
// here is a stand-in that fails as figure_charts.py does on a bad spec; the table is written).
TEST_F(AdequacyTest, AFailedMapChartIsOneLineAndNoMap) {
  const fs::path reports = work().parent_path() / "failing_reports";
  fs::create_directories(reports);
  write_text(reports / "figure_charts.py",
             "import sys\nprint('glintlab: error: charts: adequacy_x.chart.json: "
             "adequacy-levels.csv has no column \\'boundary\\'', file=sys.stderr)\nsys.exit(2)\n");
  ::setenv("GLINTLAB_REPORTS_DIR", reports.c_str(), 1);
  const RunResult r =
      run({"adequacy", "--models", "deliot_belcour", "--positions", "500", "--out", "a"});
  ::unsetenv("GLINTLAB_REPORTS_DIR");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  const auto err = lines_of(r.err);
  ASSERT_FALSE(err.empty());
  EXPECT_EQ(err.back(),
            "glintlab: error: charts: adequacy_x.chart.json: adequacy-levels.csv has no column "
            "'boundary'")
      << r.err;
  for (const auto& e : fs::directory_iterator(path("a")))
    EXPECT_NE(e.path().extension(), ".png") << e.path();
}

TEST_F(AdequacyTest, BadInputIsOneLineAndWritesNothing) {
  expect_input_error(run({"adequacy", "--threshold", "0", "--out", "o"}),
                     {"--threshold", "(0, 1]"}, {});
  expect_input_error(run({"adequacy", "--threshold", "1.5", "--out", "o"}),
                     {"--threshold", "(0, 1]"}, {});
  expect_input_error(run({"adequacy", "--threshold", "abc", "--out", "o"}), {"--threshold"}, {});
  expect_input_error(run({"adequacy", "--models", "smooth_ggx", "--out", "o"}),
                     {"--models", "deliot_belcour, kneiphof_klein", "chermain"}, {});
  expect_input_error(run({"adequacy", "--budget", "huge", "--out", "o"}), {"--budget"}, {});
  expect_input_error(run({"adequacy", "--threads", "-1", "--out", "o"}), {"--threads"}, {});
  for (const char* bad : {"99", "1000001", "2.5", "many"})
    expect_input_error(run({"adequacy", "--positions", bad, "--out", "o"}),
                       {"--positions", "[100, 1000000]"}, {});
  expect_input_error(run({"adequacy", "--calibrate", "--runs", "0", "--out", "o"}),
                     {"--runs", "[1, 1000000]"}, {});
  expect_input_error(run({"adequacy", "--runs", "10", "--out", "o"}), {"--runs", "--calibrate"},
                     {});
  expect_input_error(run({"adequacy", "--calibrate", "--tables", "-1", "--out", "o"}),
                     {"--tables", "[0, 100000]"}, {});
  expect_input_error(run({"adequacy", "--tables", "2", "--out", "o"}), {"--tables", "--calibrate"},
                     {});
  expect_input_error(run({"adequacy", "--bench-from", "nowhere", "--out", "o"}),
                     {"--bench-from", "nowhere", "not a folder"}, {});
  // The folders given to --bench-from are the only files there.
  fs::create_directories(path("empty"));
  expect_input_error(run({"adequacy", "--bench-from", "empty", "--out", "o"}),
                     {"--bench-from", "glints.json", "glintlab_bench_glints"}, {"empty"});
  fs::create_directories(path("partial"));
  write_text(path("partial/glints.json"),
             level_costs_json({"deliot_belcour"}, {1, 2, 3, 4}, "level=exact/"));
  const std::set<std::string> given = {"empty", "partial", "partial/glints.json"};
  expect_input_error(run({"adequacy", "--models", "deliot_belcour", "--bench-from", "partial",
                          "--out", "o"}),
                     {"--bench-from", "adequacy/deliot_belcour/level=exact/"}, given);
  // The area family is priced by its own rows: a file of the binomial rows alone does not price it.
  write_text(path("partial/glints.json"), level_costs_json({"deliot_belcour"}, {1, 2, 3, 4}));
  expect_input_error(run({"adequacy", "--models", "deliot_belcour,kneiphof_klein_area",
                          "--bench-from", "partial", "--out", "o"}),
                     {"--bench-from", "adequacy/kneiphof_klein_area/level=smooth/"}, given);
  // So is every family: a file without the Kemppinen or Chermain rows is refused, naming the first
  // row it lacks, rather than leaving the family unpriced.
  expect_input_error(run({"adequacy", "--models", "deliot_belcour,kemppinen_ggx", "--bench-from",
                          "partial", "--out", "o"}),
                     {"--bench-from", "adequacy/kemppinen_ggx/level=smooth/"}, given);
  expect_input_error(
      run({"adequacy", "--models", "chermain", "--bench-from", "partial", "--out", "o"}),
      {"--bench-from", "adequacy/chermain/level=smooth/"}, given);
  write_text(path("partial/glints.json"), "{\"benchmarks\": 3}");
  expect_input_error(run({"adequacy", "--bench-from", "partial", "--out", "o"}),
                     {"--bench-from", "benchmarks"}, given);
  expect_input_error(run({"adequacy", "--calibrate", "--bench-from", "partial", "--out", "o"}),
                     {"--bench-from", "--calibrate"}, given);
}

TEST_F(AdequacyTest, CalibrateWritesRatesForEveryCaseDeltaAndLevel) {
  const RunResult r = run({"adequacy", "--calibrate", "--runs", "3", "--tables", "1", "--models",
                           "deliot_belcour", "--out", "c", "--threads", "2"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("972 decisions"), std::string::npos) << r.out;  // 324 cells × 3 levels
  const auto doc = nlohmann::json::parse(read_text(path("c/adequacy-calibration.json")));
  EXPECT_EQ(doc["table_decisions"], 972);
  EXPECT_EQ(doc["positions_per_cell"], 8000);
  // 7 cases × 7 δ × (4 nominal levels + the table's share).
  EXPECT_EQ(doc["rows"].size(), 7u * 7u * 5u);
  EXPECT_EQ(io::read_csv(path("c/adequacy-calibration.csv")).num_rows(), 7u * 7u * 5u);
  EXPECT_EQ(doc["pooled"].size(), 7u * 5u);  // the five pooled cases summed per δ and level
  EXPECT_EQ(doc["pooled"][0]["decisions"], 5 * 3);
  EXPECT_EQ(doc["pooled"][0]["verdict"], "power");  // δ = −0.5: truly adequate
  ASSERT_EQ(doc["family_wise"].size(), 4u);  // δ = 0, 0.05, 0.1, 0.25
  EXPECT_EQ(doc["family_wise"][0]["tables"], 1);
  EXPECT_EQ(doc["family_wise"][0]["table_decisions"], 972);
  EXPECT_EQ(unexpected_files(path("c"), {}).size(), 2u);
  // --positions: the synthetic cells drawn at that many positions.
  ASSERT_EQ(run({"adequacy", "--calibrate", "--runs", "2", "--tables", "0", "--models",
                 "deliot_belcour", "--positions", "300", "--out", "c300"})
                .exit_code,
            0);
  EXPECT_EQ(nlohmann::json::parse(read_text(path("c300/adequacy-calibration.json")))
                ["positions_per_cell"],
            300);
}

}  // namespace
}  // namespace glintlab::cli_test
