// `glintlab sweep`: the quick sweep's files and stability.json, its maps drawn by matplotlib
// (labels read back from the PNGs), identical output for any --threads, and the bad-input errors
// (one line, exit 2, no output left behind).
#include <gtest/gtest.h>
#include <stdlib.h>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "cli/chart_png.h"
#include "cli/cli_test_util.h"

namespace glintlab::cli_test {
namespace {

namespace fs = std::filesystem;
using SweepTest = CliTest;

TEST_F(SweepTest, QuickSweepWritesMapsAndIndex) {
  const RunResult r = run({"sweep", "--budget", "quick", "--models", "smooth_beckmann", "--out",
                           "s", "--threads", "2"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("2 model×sampler targets"), std::string::npos) << r.out;
  // One line per target with its verdict (as stability.json records it).
  EXPECT_NE(r.out.find("smooth_beckmann/ndf"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("smooth_beckmann/vndf"), std::string::npos) << r.out;
  EXPECT_TRUE(r.err.empty()) << r.err;  // progress only on a terminal
  const auto doc = nlohmann::json::parse(read_text(path("s/stability.json")));
  EXPECT_EQ(doc["budget"], "quick");
  EXPECT_TRUE(doc["machine"].is_string());
  ASSERT_EQ(doc["models"].size(), 2u);
  for (const auto& m : doc["models"]) {
    EXPECT_EQ(m["model"], "smooth_beckmann");
    EXPECT_TRUE(m["failure_region"].is_string());
    EXPECT_NE(r.out.find(m["verdict"].get<std::string>()), std::string::npos) << r.out;
    EXPECT_EQ(m["maps"].size(), 2u * 5u);  // alpha, anisotropy × nan, inf, negative, gain, var
    for (const auto& map : m["maps"]) {
      for (const char* k : {"quantity", "png", "exr", "csv"}) EXPECT_TRUE(map.contains(k));
      // A heat map drawn by matplotlib: labelled axes, its colour bar, the failing cells named.
      const fs::path png = path("s") / map["png"].get<std::string>();
      expect_labelled_chart(png, 1);
      const nlohmann::json chart = chart_manifest(png);
      const nlohmann::json& a = chart["axes"][0];
      EXPECT_EQ(a.value("xlabel", ""), "incidence angle theta_i [deg]") << png;
      EXPECT_NE(a.value("colorbar_label", "").find("[1]"), std::string::npos) << png;
      EXPECT_TRUE(a.value("legend", false)) << png;
      const std::string q = map["quantity"].get<std::string>();
      EXPECT_NE(chart.value("title", "").find(q), std::string::npos) << png;
    }
  }
  EXPECT_EQ(doc["models"][1]["sampler"], "vndf");
  // Nothing but the model folder and the index (no staging folder left).
  EXPECT_EQ(std::distance(fs::directory_iterator(path("s")), fs::directory_iterator()), 2);
}

// The maps drawn by the stand-in (CliTest::stand_in_charts): a map's PNG is then its spec's and
// CSV's bytes, the same for any thread count exactly when the data are; matplotlib's drawing of
// them is the same bytes in any run, also of a sweep shard on one thread against one on two
// (SweepShardTest.MergedShardsAreTheFilesOfOneRun, its first pass).
TEST_F(SweepTest, OutputDoesNotDependOnThreads) {
  stand_in_charts();
  ASSERT_EQ(
      run({"sweep", "--budget", "quick", "--models", "smooth_ggx", "--out", "a", "--threads", "1"})
          .exit_code,
      0);
  ASSERT_EQ(
      run({"sweep", "--budget", "quick", "--models", "smooth_ggx", "--out", "b", "--threads", "2"})
          .exit_code,
      0);
  EXPECT_EQ(read_text(path("a/stability.json")), read_text(path("b/stability.json")));
  for (const char* f : {"smooth_ggx/ndf/alpha.csv", "smooth_ggx/bounded_caps/anisotropy.csv",
                        "smooth_ggx/ndf/alpha_maps.csv", "smooth_ggx/ndf/alpha_variance.png",
                        "smooth_ggx/bounded_caps/anisotropy_energy_gain.png"})
    EXPECT_EQ(read_text(path("a") / f), read_text(path("b") / f)) << f;
}

// The maps' chart script failing is the sweep's one-line error naming the target's spec, exit 2,
// and nothing in the output folder (the maps are drawn in the staging folder, before the move).
// The script here is a stand-in that fails as figure_charts.py does on a bad spec: it names the
// first spec of its first --dir by its path below --root (one run for every target).
TEST_F(SweepTest, AFailedMapChartIsOneLineAndLeavesNothing) {
  const fs::path reports = work().parent_path() / "failing_sweep_reports";
  fs::create_directories(reports);
  write_text(reports / "figure_charts.py",
             "import glob, os, sys\na = sys.argv\nd = a[a.index('--dir') + 1]\n"
             "spec = sorted(glob.glob(os.path.join(d, '*.chart.json')))[0]\n"
             "name = os.path.relpath(spec, a[a.index('--root') + 1])\n"
             "print(f'glintlab: error: charts: {name}: alpha_maps.csv has no column \\'x\\'', "
             "file=sys.stderr)\nsys.exit(2)\n");
  ::setenv("GLINTLAB_REPORTS_DIR", reports.c_str(), 1);
  const RunResult r = run({"sweep", "--budget", "quick", "--models", "smooth_beckmann", "--out",
                           "s", "--threads", "2"});
  ::unsetenv("GLINTLAB_REPORTS_DIR");
  // The output folder itself stays, empty.
  expect_input_error(r, {"sweep: charts: smooth_beckmann/ndf/", "alpha_maps.csv has no column 'x'"},
                     {"s"});
}

TEST_F(SweepTest, HelpDocumentsTheOutputs) {
  const RunResult r = run({"sweep", "--help"});
  EXPECT_EQ(r.exit_code, 0);
  for (const char* n : {"--out", "--budget", "quick", "--models", "--threads", "stability.json",
                        "89.999", "p_*", "Var(w)/E(w)^2", "float"})
    EXPECT_NE(r.out.find(n), std::string::npos) << "help lacks " << n;
}

TEST_F(SweepTest, BadInputIsOneLine) {
  expect_input_error(run({"sweep", "--budget", "quick", "--models", "nope*", "--out", "s"}),
                     {"--models", "nope*", "smooth_ggx"}, {});
  expect_input_error(run({"sweep", "--budget", "quick", "--threads", "-1", "--out", "s"}),
                     {"--threads", "[0, 1024]"}, {});
  write_text(path("file"), "x");
  expect_input_error(run({"sweep", "--budget", "quick", "--models", "smooth_ggx", "--out", "file"}),
                     {"--out", "file"}, {"file"});
}

}  // namespace
}  // namespace glintlab::cli_test
