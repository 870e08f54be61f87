// `glintlab figure`: --list, each experiment's --quick run (EXR read back through OpenEXR with its
// attributes, PNG signature, CSV parsed), and the bad-input errors.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "cli/chart_png.h"
#include "cli/cli_test_util.h"
#include "core/io/csv.h"
#include "core/io/exr.h"

namespace glintlab::cli_test {
namespace {

namespace fs = std::filesystem;
using FigureTest = CliTest;

TEST_F(FigureTest, ListShowsBothExperiments) {
  const RunResult r = run({"figure", "--list"});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("eto2023-fig4 "), std::string::npos);
  EXPECT_NE(r.out.find("eto2023-fig4-rmse-spp"), std::string::npos);
  EXPECT_NE(r.out.find("Fig. 4"), std::string::npos);
}

void expect_exr(const fs::path& p, const std::string& spp) {
  const io::ExrFile f = io::read_exr(p);
  EXPECT_EQ(f.image.width, 128);
  for (const char* key : {"glintlab_model", "glintlab_parameters", "glintlab_seed", "glintlab_spp",
                          "glintlab_version", "glintlab_reference_spp"}) {
    EXPECT_TRUE(f.attributes.count(key)) << p << " lacks " << key;
  }
  EXPECT_EQ(f.attributes.at("glintlab_spp"), spp);
  EXPECT_EQ(f.attributes.at("glintlab_model"), "smooth_ggx");
  f.image.channel("R");
  f.image.channel("coverage");
}

void expect_png(const fs::path& p) {
  const std::string bytes = read_text(p);
  ASSERT_GT(bytes.size(), 8u);
  EXPECT_EQ(bytes.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
}

TEST_F(FigureTest, Fig4QuickWritesExrPngAndCsv) {
  const RunResult r =
      run({"figure", "eto2023-fig4", "--budget", "quick", "--out", "out", "--threads", "2"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const fs::path d = path("out/eto2023-fig4");
  for (const char* a : {"a0.2", "a0.8"}) {
    expect_exr(d / (std::string(a) + "_reference.exr"), "256");
    expect_exr(d / (std::string(a) + "_spherical_caps.exr"), "16");
    expect_exr(d / (std::string(a) + "_bounded_caps.exr"), "16");
  }
  expect_png(d / "fig4.png");
  const io::CsvTable t = io::read_csv(d / "fig4.csv");
  ASSERT_EQ(t.num_rows(), 4u);
  const std::size_t method = t.column("method"), rmse = t.column("rmse"), alpha = t.column("alpha");
  std::set<std::string> seen;
  for (std::size_t i = 0; i < 4; ++i) {
    seen.insert(std::string(t.text(i, method)) + "@" + std::string(t.text(i, alpha)));
    EXPECT_GT(t.number(i, rmse), 0.0);
    EXPECT_GT(t.number(i, t.column("rejected_fraction")), 0.0);
  }
  EXPECT_EQ(seen.size(), 4u);
  EXPECT_EQ(
      unexpected_files(
          work(),
          {"out", "out/eto2023-fig4", "out/eto2023-fig4/fig4.csv", "out/eto2023-fig4/fig4.png",
           "out/eto2023-fig4/fig4.panels.json", "out/eto2023-fig4/a0.2_reference.exr",
           "out/eto2023-fig4/a0.2_spherical_caps.exr", "out/eto2023-fig4/a0.2_bounded_caps.exr",
           "out/eto2023-fig4/a0.8_reference.exr", "out/eto2023-fig4/a0.8_spherical_caps.exr",
           "out/eto2023-fig4/a0.8_bounded_caps.exr"}),
      std::vector<std::string>{});
}

TEST_F(FigureTest, RmseSppQuickWritesExrPngAndCsv) {
  const RunResult r = run(
      {"figure", "eto2023-fig4-rmse-spp", "--budget", "quick", "--out", "out", "--threads", "2"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const fs::path d = path("out/eto2023-fig4-rmse-spp");
  expect_exr(d / "a0.2_reference.exr", "256");
  expect_exr(d / "a0.8_reference.exr", "256");
  expect_png(d / "references.png");
  const io::CsvTable t = io::read_csv(d / "rmse_spp.csv");
  EXPECT_EQ(t.num_rows(), 2u * 2u * 6u);  // alphas × methods × spp 1..32
  const io::CsvTable s = io::read_csv(d / "loglog_slopes.csv");
  ASSERT_EQ(s.num_rows(), 4u);
  // A smoke test of the series, not a claim: the expected slope is −½, but a quick image's
  // RMSE at 1–4 spp is dominated by a few sun hits (heavy-tailed; measured slopes −0.32 to −0.53
  // at 48², −0.46 to −0.51 at 128²), so only "falls, at a rate between spp^-0.2 and spp^-1" is
  // checked here, and that 32 spp beats 1 spp by more than 2× for every (alpha, method).
  for (std::size_t i = 0; i < 4; ++i) {
    const double slope = s.number(i, s.column("slope"));
    EXPECT_LT(slope, -0.2);
    EXPECT_GT(slope, -1.0);
  }
  const std::size_t spp = t.column("spp"), rmse = t.column("rmse");
  for (std::size_t i = 0; i + 5 < t.num_rows(); i += 6) {
    ASSERT_EQ(t.number(i, spp), 1.0);
    ASSERT_EQ(t.number(i + 5, spp), 32.0);
    EXPECT_LT(2 * t.number(i + 5, rmse), t.number(i, rmse)) << "row " << i;
  }
}

TEST_F(FigureTest, BadInputGetsOneLineAndNoOutput) {
  expect_input_error(run({"figure", "fig99", "--out", "out"}),
                     {"unknown figure id 'fig99'", "eto2023-fig4"}, {});
  expect_input_error(run({"figure"}), {"figure id is required"}, {});
  write_text(path("blocker"), "x");
  expect_input_error(run({"figure", "eto2023-fig4", "--budget", "quick", "--out", "blocker/sub"}),
                     {"--out", "blocker/sub"}, {"blocker"});
  expect_input_error(run({"figure", "eto2023-fig4", "--threads", "-1"}), {"--threads", "valid"},
                     {"blocker"});
}

// reports/figure_charts.py run on a folder of CSVs and chart specs, as glintlab figure runs it.
class FigureChartsTest : public CliTest {
 protected:
  RunResult draw(const fs::path& dir) const { return draw_all({dir}, {}); }
  // Several folders in one run (as glintlab sweep runs it), a failing spec named below `root`.
  RunResult draw_all(const std::vector<fs::path>& dirs, const fs::path& root) const {
    const fs::path script = fs::path(kReportFixtures).parent_path().parent_path().parent_path() /
                            "reports" / "figure_charts.py";
    std::string cmd = "/usr/bin/python3 '" + script.string() + "'";
    for (const fs::path& d : dirs) cmd += " --dir '" + d.string() + "'";
    if (!root.empty()) cmd += " --root '" + root.string() + "'";
    cmd += " >'" + path("stdout").string() + "' 2>'" + path("stderr").string() + "'";
    const int status = std::system(cmd.c_str());
    return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, read_text(path("stdout")),
            read_text(path("stderr"))};
  }
  // A failed run: exit 2, one stderr line containing `needle`, and no PNG in `dir`.
  void expect_one_line(const fs::path& dir, const std::string& needle) const {
    const RunResult r = draw(dir);
    EXPECT_EQ(r.exit_code, 2);
    ASSERT_EQ(lines_of(r.err).size(), 1u) << r.err;
    EXPECT_EQ(r.err.rfind("glintlab: error: charts: ", 0), 0u) << r.err;
    EXPECT_NE(r.err.find(needle), std::string::npos) << r.err;
    for (const auto& e : fs::directory_iterator(dir))
      EXPECT_NE(e.path().extension(), ".png") << e.path();
  }
};

// Every NAME.chart.json of a folder drawn into NAME.png: a labelled chart (title, axis labels
// with units, legend, read back from the PNG), the same bytes when drawn again; a spec naming a
// column the CSV lacks, or an axis label without its unit, is one line on stderr, exit 2, and no
// PNG.
TEST_F(FigureChartsTest, LineChartsAreLabelledAndTheSameBytesOrFailInOneLine) {
  auto chart_folder = [&](const std::string& name, const std::string& y,
                          const std::string& x_label) {
    const fs::path d = path(name);
    fs::create_directories(d);
    write_text(d / "data.csv", "series,x,y\na,1,2\na,2,3\nb,1,1\nb,2,4\n");
    write_text(d / "data.chart.json",
               R"({"title": "test chart", "csv": "data.csv", "panels": [{"title": "a and b",
 "where": {}, "x": {"column": "x", "label": ")" +
                   x_label + R"(", "log": false}, "y": {"label": "y [1]", "log": false},
 "series": [{"label": "a", "where": {"series": "a"}, "y": ")" +
                   y + R"("}, {"label": "b", "where": {"series": "b"}, "y": "y"}],
 "hlines": []}]})");
    return d;
  };
  const fs::path good = chart_folder("good", "y", "x [m]");
  const RunResult r = draw(good);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  expect_labelled_chart(good / "data.png", 1);
  const std::string first = read_text(good / "data.png");
  ASSERT_EQ(draw(good).exit_code, 0);
  EXPECT_EQ(read_text(good / "data.png"), first);  // no date, no version: the same bytes

  expect_one_line(chart_folder("missing", "no_such_column", "x [m]"),
                  "data.chart.json: data.csv has no column 'no_such_column'");
  expect_one_line(chart_folder("unitless", "y", "x"), "x label 'x' has no unit");
}

// A map of categories (the adequacy maps' kind): one cell per (x value, y row) in its category's
// colour, the categories as its colour scale, a marker per row; a cell whose value is none of the
// categories is one line and no PNG.
TEST_F(FigureChartsTest, CategoryMapsHaveTheirColourScaleOrFailInOneLine) {
  auto map_folder = [&](const std::string& name, const std::string& third_value) {
    const fs::path d = path(name);
    fs::create_directories(d);
    write_text(d / "cells.csv",
               "n,alpha,level,boundary\n1,0.1,1,30\n10,0.1,0,30\n100,0.1,0,30\n1,0.3,1,3\n10,0.3," +
                   third_value + ",3\n100,0.3,0,3\n");
    write_text(d / "cells.chart.json", R"({"kind": "categories", "title": "levels",
 "csv": "cells.csv", "panels": [{"title": "cheapest level", "where": {},
 "x": {"column": "n", "label": "footprint [cells]", "log": true},
 "y": {"columns": ["alpha"], "format": "alpha {alpha}", "label": "alpha [1]"},
 "value": {"column": "level", "label": "level"},
 "categories": [{"value": 0, "label": "smooth", "color": [0.3, 0.7, 0.3]},
                {"value": 1, "label": "exact", "color": [0.8, 0.2, 0.2]}],
 "marker": {"column": "boundary", "label": "predicted boundary"}}]})");
    return d;
  };
  const fs::path good = map_folder("good", "1");
  const RunResult r = draw(good);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  expect_labelled_chart(good / "cells.png", 1);
  const nlohmann::json m = chart_manifest(good / "cells.png");
  EXPECT_TRUE(m["axes"][0].value("map", false));
  EXPECT_TRUE(m["axes"][0].value("colorbar", false));
  expect_one_line(map_folder("unknown", "7"), "level = 7, which is none of the panel's categories");
}

// A heat map (a number over a grid, e.g. p over (gamma, sqrt(alpha)) or a difference over an
// image's pixels): its colour scale and its label, the flagged cells named in the legend with
// their count; a flag naming a column the CSV lacks, or a y format that fits no cell, is one line
// and no PNG.
TEST_F(FigureChartsTest, HeatMapsHaveTheirColourScaleAndFlagsOrFailInOneLine) {
  auto map_folder = [&](const std::string& name, const std::string& flag_column,
                        const std::string& y_format = "{sa:.2f}") {
    const fs::path d = path(name);
    fs::create_directories(d);
    write_text(
        d / "p.csv",
        "gamma,sa,p,over\n0.1,0.1,0.5,0\n1,0.1,2,1\n10,0.1,8,1\n0.1,0.5,0.01,0\n1,0.5,0.1,0\n"
        "10,0.5,nan,0\n");
    write_text(
        d / "p.chart.json", R"({"kind": "heatmap", "title": "p map", "csv": "p.csv",
 "panels": [{"title": "p over the grid", "where": {},
 "x": {"column": "gamma", "label": "gamma [deg]"},
 "y": {"columns": ["sa"], "format": ")" +
                                y_format + R"(", "label": "sqrt(alpha) [1]"},
 "value": {"column": "p", "label": "p [1]", "log": true},
 "flags": [{"column": ")" + flag_column +
                                R"(", "value": 1, "label": "p > 1", "color": [1, 0, 0]}]}]})");
    return d;
  };
  const fs::path good = map_folder("good", "over");
  const RunResult r = draw(good);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  expect_labelled_chart(good / "p.png", 1);
  const nlohmann::json m = chart_manifest(good / "p.png");
  EXPECT_TRUE(m["axes"][0].value("map", false));
  EXPECT_TRUE(m["axes"][0].value("legend", false));  // the flags and the cell without a value
  EXPECT_EQ(m["axes"][0].value("colorbar_label", ""), "p [1]");
  expect_one_line(map_folder("missing", "p_gt_1"), "p.csv has no column 'p_gt_1'");
  // A y format's number spec formats the cell as a number; one that fits no number is one line.
  expect_one_line(map_folder("bad_format", "over", "{sa:.2q}"), "y format '{sa:.2q}' does not fit");
}

// Several folders drawn in one run (glintlab sweep's targets): each folder's charts are the bytes
// of a run on that folder alone; a bad spec in a later folder is one line naming it by its path
// below the root, and no PNG is left in any folder.
TEST_F(FigureChartsTest, SeveralFoldersInOneRunAreTheBytesOfSeparateRunsOrNone) {
  auto folder = [&](const std::string& name, const std::string& y) {
    const fs::path d = path(name);
    fs::create_directories(d);
    write_text(d / "data.csv", "x,y\n1,2\n2,3\n");
    write_text(d / "data.chart.json",
               R"({"title": "chart )" + name + R"(", "csv": "data.csv", "panels": [{"title": "y",
 "x": {"column": "x", "label": "x [m]"}, "y": {"label": "y [1]"},
 "series": [{"label": "y", "y": ")" + y + R"("}]}]})");
    return d;
  };
  const fs::path a = folder("root/m/a", "y"), b = folder("root/m/b", "y");
  ASSERT_EQ(draw(a).exit_code, 0);
  ASSERT_EQ(draw(b).exit_code, 0);
  const std::string alone_a = read_text(a / "data.png"), alone_b = read_text(b / "data.png");
  fs::remove(a / "data.png");
  fs::remove(b / "data.png");
  const RunResult r = draw_all({a, b}, path("root"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(read_text(a / "data.png"), alone_a);
  EXPECT_EQ(read_text(b / "data.png"), alone_b);
  EXPECT_NE(alone_a, alone_b);  // their titles differ
  fs::remove(a / "data.png");
  fs::remove(b / "data.png");
  const fs::path bad = folder("root/n/bad", "no_such_column");
  const RunResult f = draw_all({a, b, bad}, path("root"));
  EXPECT_EQ(f.exit_code, 2);
  ASSERT_EQ(lines_of(f.err).size(), 1u) << f.err;
  EXPECT_NE(f.err.find("charts: n/bad/data.chart.json: data.csv has no column 'no_such_column'"),
            std::string::npos)
      << f.err;
  for (const fs::path& d : {a, b, bad}) EXPECT_FALSE(fs::exists(d / "data.png")) << d;
}

// The chart script's failure is the figure's: one line naming the figure and the script's message,
// exit 2, and no figure folder (the charts are drawn in the staging folder, before it is swapped
// in). The script here is a stand-in that fails as figure_charts.py does on a bad spec.
TEST_F(FigureTest, AFailedChartIsTheFiguresOneLineErrorAndLeavesNoFolder) {
  const fs::path reports = work().parent_path() / "failing_reports";
  fs::create_directories(reports);
  write_text(reports / "figure_charts.py",
             "import sys\nprint('glintlab: error: charts: furnace.chart.json: furnace.csv has no "
             "column \\'x\\'', file=sys.stderr)\nsys.exit(2)\n");
  ::setenv("GLINTLAB_REPORTS_DIR", reports.c_str(), 1);
  const RunResult r =
      run({"figure", "kemppinen2025-fig15", "--budget", "quick", "--out", "out", "--threads", "2"});
  ::unsetenv("GLINTLAB_REPORTS_DIR");
  expect_input_error(r, {"figure kemppinen2025-fig15", "furnace.csv has no column 'x'"}, {"out"});
}

// models-hemisphere: per model its value and pdf over the hemisphere as two heat maps drawn by
// matplotlib from STEM_map.csv (at quick the EXR's pixels inside the disk), labelled with their
// units and colour bars; the same chart specs and data with one thread and with two (the run on
// one thread draws with the stand-in, CliTest::stand_in_charts: its PNG is its spec's and CSV's
// bytes, which matplotlib draws as the same PNG in any run).
TEST_F(FigureTest, ModelsHemisphereMapsAreChartsOfTheirCsv) {
  for (const char* threads : {"2", "1"}) {
    if (threads[0] == '1') stand_in_charts();
    const RunResult r = run({"figure", "models-hemisphere", "--budget", "quick", "--out",
                             std::string("out") + threads, "--threads", threads});
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
  const fs::path d = path("out2/models-hemisphere");
  const io::CsvTable models = io::read_csv(d / "models_hemisphere.csv");
  ASSERT_GE(models.num_rows(), 9u);
  for (std::size_t i = 0; i < models.num_rows(); ++i) {
    const std::string stem(models.text(i, models.column("model")));
    const fs::path png = d / (stem + ".png");
    expect_labelled_chart(png, 2);
    const nlohmann::json m = chart_manifest(png);
    EXPECT_NE(m.value("title", std::string()).find(stem), std::string::npos) << stem;
    EXPECT_EQ(m["axes"][0].value("colorbar_label", ""), "f cos(theta_o) [1/sr]") << stem;
    EXPECT_EQ(m["axes"][1].value("colorbar_label", ""), "pdf [1/sr]") << stem;
    const std::string spec = read_text(d / (stem + ".chart.json"));
    const std::string csv = nlohmann::json::parse(spec).at("csv").get<std::string>();
    EXPECT_EQ(spec + read_text(d / csv),
              read_text(path("out1/models-hemisphere/" + stem + ".png")))
        << stem;
  }
  // smooth_ggx's map: every pixel inside the disk, equal to the EXR's (32-bit float) pixels.
  const Image exr = io::read_exr(d / "smooth_ggx.exr").image;
  const io::CsvTable t = io::read_csv(d / "smooth_ggx_map.csv");
  std::size_t inside = 0;
  for (int y = 0; y < 128; ++y)
    for (int x = 0; x < 128; ++x) {
      const double px = (x + 0.5) / 64 - 1, py = 1 - (y + 0.5) / 64;
      if (px * px + py * py >= 1) continue;
      if (x == 40 && y == 90) {
        EXPECT_EQ(t.number(inside, t.column("wo_x")), px);
        EXPECT_EQ(t.number(inside, t.column("wo_y")), py);
        EXPECT_EQ(float(t.number(inside, t.column("value"))),
                  float(exr.at(x, y, exr.channel("value"))));
        EXPECT_EQ(float(t.number(inside, t.column("pdf"))),
                  float(exr.at(x, y, exr.channel("pdf"))));
      }
      ++inside;
    }
  EXPECT_EQ(t.num_rows(), inside);
}

// A lat-long EXR environment: a small uniform map lights the quick Fig. 4 and is named in the EXR
// attributes; a missing file, a non-lat-long size, a missing channel and a negative pixel are each
// one-line errors that leave no output.
TEST_F(FigureTest, EnvironmentMapFromExr) {
  auto env_image = [](int w, int h, std::vector<std::string> channels, double value) {
    Image im(w, h, std::move(channels));
    for (double& v : im.data) v = value;
    return im;
  };
  io::write_exr(path("sky.exr"), env_image(16, 8, {"R", "G", "B"}, 0.5), {});
  const RunResult r =
      run({"figure", "eto2023-fig4", "--budget", "quick", "--env", "sky.exr", "--out", "out"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const io::ExrFile f = io::read_exr(path("out/eto2023-fig4/a0.8_reference.exr"));
  EXPECT_NE(f.attributes.at("glintlab_environment").find("sky.exr (16x8)"), std::string::npos);
  // Uniform radiance 0.5: the background pixels are exactly 0.5.
  EXPECT_EQ(f.image.at(0, 0, f.image.channel("R")), 0.5);
  fs::remove_all(path("out"));

  io::write_exr(path("square.exr"), env_image(8, 8, {"R", "G", "B"}, 1), {});
  io::write_exr(path("gray.exr"), env_image(16, 8, {"Y"}, 1), {});
  io::write_exr(path("negative.exr"), env_image(16, 8, {"R", "G", "B"}, -1), {});
  write_text(path("garbage.exr"), "not an exr file");
  const std::set<std::string> files = {"sky.exr", "square.exr", "gray.exr", "negative.exr",
                                       "garbage.exr"};
  auto bad = [&](const std::string& file, const std::vector<std::string>& needles) {
    expect_input_error(
        run({"figure", "eto2023-fig4", "--budget", "quick", "--env", file, "--out", "out"}),
        needles, files);
  };
  bad("missing.exr", {"--env", "missing.exr"});
  bad("garbage.exr", {"--env", "garbage.exr"});
  bad("square.exr", {"--env", "8x8", "width = 2 x height"});
  bad("gray.exr", {"--env", "no channel R"});
  bad("negative.exr", {"--env", "out of range", "finite, >= 0"});
}

}  // namespace
}  // namespace glintlab::cli_test
