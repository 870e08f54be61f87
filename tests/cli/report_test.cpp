// `glintlab report`: bad --out and options (one line, exit 2, nothing written), --reuse of cached
// results from the fixtures and a malformed cached claims.json (the old report stays as it was),
// and one small real run (one claim, one quick figure).
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <set>
#include <string>

#include "cli/cli_test_util.h"

namespace glintlab::cli_test {
namespace {

namespace fs = std::filesystem;
using ReportTest = CliTest;

const std::vector<std::string> kNoParts = {"--skip", "claims,conformance,figures,bench,stability"};

std::vector<std::string> with(std::vector<std::string> a, const std::vector<std::string>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

std::set<std::string> files_under(const fs::path& dir) {
  std::set<std::string> out;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    out.insert(fs::relative(e.path(), dir).generic_string());
  return out;
}

TEST_F(ReportTest, OutThatIsAFileIsAnError) {
  write_text(path("afile"), "x");
  expect_input_error(run(with({"report", "--out", "afile"}, kNoParts)),
                     {"--out", "afile", "not a folder"}, {"afile"});
}

TEST_F(ReportTest, OutBelowAFileIsAnError) {
  write_text(path("afile"), "x");
  expect_input_error(run(with({"report", "--out", "afile/report"}, kNoParts)),
                     {"--out", "afile", "cannot create"}, {"afile"});
}

TEST_F(ReportTest, OutThatIsTheWorkingFolderIsAnError) {
  expect_input_error(run(with({"report", "--out", "."}, kNoParts)), {"--out", "'.'"}, {});
  expect_input_error(run(with({"report", "--out", "/"}, kNoParts)), {"--out", "'/'"}, {});
}

TEST_F(ReportTest, BadOptionsAreErrors) {
  expect_input_error(run({"report", "--out", "r", "--budget", "huge"}),
                     {"--budget", "huge", "valid: quick, full"}, {});
  expect_input_error(run({"report", "--out", "r", "--skip", "claims,pictures"}),
                     {"--skip", "pictures", "claims, conformance, bench, figures, stability"}, {});
  expect_input_error(run({"report", "--out", "r", "--figures", "nope*"}),
                     {"--figures", "nope*", "figure --list"}, {});
  expect_input_error(run({"report", "--out", "r", "--models", "nope*"}),
                     {"--models", "nope*", "smooth_ggx"}, {});
  expect_input_error(run({"report", "--out", "r", "--conformance", "nope*"}),
                     {"--conformance", "nope*", "smooth_ggx"}, {});
  expect_input_error(run({"report", "--out", "r", "--claims-from", "missing"}),
                     {"--claims-from", "missing", "claims.json"}, {});
}

TEST_F(ReportTest, ReuseReadsCachedResultsAndAMalformedOneLeavesTheOldReport) {
  fs::copy(kReportFixtures, path("report"), fs::copy_options::recursive);
  RunResult r = run({"report", "--out", "report", "--reuse", "--skip", "bench,conformance",
                     "--models", "smooth_ggx"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string html = read_text(path("report/index.html"));
  EXPECT_NE(html.find("fixture.fails"), std::string::npos);
  EXPECT_NE(html.find("fixture_model_energy_gain.png"), std::string::npos);
  EXPECT_NE(html.find("NaN for alpha below 1e-3"), std::string::npos);
  EXPECT_TRUE(fs::exists(path("report/report.md")));
  const auto info = nlohmann::json::parse(read_text(path("report/run.json")));
  EXPECT_EQ(info["parts"]["claims"]["status"], "reused");
  EXPECT_EQ(info["parts"]["figures"]["status"], "reused");
  EXPECT_EQ(info["parts"]["bench"]["status"], "skipped");
  // The cached part keeps the machine it was made on, not this one.
  EXPECT_EQ(info["parts"]["claims"]["machine"]["cpu_model"], "Fixture CPU");

  // Corrupt the cached claims: one line, exit 2, and the previous report is untouched.
  write_text(path("report/verify/claims.json"), "[{\"id\": ");
  std::set<std::string> before = files_under(work());
  r = run({"report", "--out", "report", "--reuse", "--skip", "bench,conformance"});
  expect_input_error(r, {"verify/claims.json", "not valid JSON"}, before);
  EXPECT_EQ(read_text(path("report/index.html")), html);

  // A malformed cached run.json is an error too.
  write_text(path("report/run.json"), "{\"parts\": 3}");
  before = files_under(work());
  expect_input_error(run({"report", "--out", "report", "--reuse", "--skip", "bench,conformance"}),
                     {"--reuse", "run.json"}, before);
}

// The report checks claims.json against the schema the program prints, which it writes beside the
// results; a cached claims.json that lacks a field of this program's rows is an error naming it.
TEST_F(ReportTest, ClaimsAreCheckedAgainstTheProgramsSchema) {
  fs::copy(kReportFixtures, path("report"), fs::copy_options::recursive);
  fs::remove_all(path("report/schemas"));
  const std::vector<std::string> reuse = {"report",   "--out",     "report",
                                          "--reuse",  "--skip",    "bench,conformance",
                                          "--models", "smooth_ggx"};
  RunResult r = run(reuse);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  RunResult schema = run({"schema", "claims.json"});
  ASSERT_EQ(schema.exit_code, 0) << schema.err;
  EXPECT_EQ(read_text(path("report/schemas/claims.schema.json")), schema.out);

  auto rows = nlohmann::json::parse(read_text(path("report/verify/claims.json")));
  rows[1].erase("power");
  write_text(path("report/verify/claims.json"), rows.dump(1));
  const std::set<std::string> before = files_under(work());
  expect_input_error(run(reuse), {"verify/claims.json", "(fixture.fails) lacks power"}, before);
}

TEST_F(ReportTest, SchemaNamesTheFilesItDescribes) {
  expect_input_error(run({"schema"}), {"schema", "needs one file name", "claims.json"}, {});
  expect_input_error(run({"schema", "claims.csv"}), {"'claims.csv'", "valid: claims.json"}, {});
  const RunResult r = run({"schema", "claims.json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto schema = nlohmann::json::parse(r.out);
  EXPECT_EQ(schema["items"]["properties"]["verdict"]["enum"].size(), 7u);
}

// The benchmarks run (here: are reused) before the figures, and the timing figures read the
// report's own bench/ folder, named as the report's folder, not the staging one; without that
// part they say in one sentence that they have no benchmark data.
TEST_F(ReportTest, TimingFiguresReadTheReportsOwnBenchmarks) {
  fs::create_directories(path("r"));
  fs::copy(fs::path(kReportFixtures) / "bench", path("r/bench"), fs::copy_options::recursive);
  write_text(path("r/bench/glints.json"),
             "{\n  \"benchmarks\": [\n    {\n      \"name\": \"table1/method:2/light:2\",\n"
             "      \"real_time\": 42.5,\n      \"time_unit\": \"ns\"\n    }\n  ]\n}\n");
  RunResult r = run({"report", "--out", "r", "--reuse", "--figures", "kneiphof2024-table1",
                     "--skip", "claims,conformance,stability,compare", "--threads", "1"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::string md = read_text(path("r/figures/kneiphof2024-table1/summary.md"));
  EXPECT_NE(md.find("read from `r/bench/glints.json`"), std::string::npos) << md;
  EXPECT_NE(md.find("| area | — | — | 42.5 | — |"), std::string::npos) << md;
  std::string html = read_text(path("r/index.html"));
  EXPECT_EQ(html.find(".tmp."), std::string::npos) << "a staging path is shown in the report";

  r = run({"report", "--out", "r2", "--figures", "kneiphof2024-table1", "--skip",
           "claims,conformance,bench,stability,compare", "--threads", "1"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  md = read_text(path("r2/figures/kneiphof2024-table1/summary.md"));
  EXPECT_NE(md.find("No benchmark data: no benchmark folder was given"), std::string::npos) << md;
  html = read_text(path("r2/index.html"));
  for (const char* bad : {">nan<", ">NaN<", "NOT FOUND"})
    EXPECT_EQ(html.find(bad), std::string::npos) << bad;
}

TEST_F(ReportTest, SmallRealRun) {
  // compare covers the --models only: one model with a cubature reference (smooth_ggx), one with
  // Monte Carlo (deliot_belcour); the conformance part measures deliot_belcour's suite (the
  // cheapest with every property), smooth_ggx's verdicts are recorded ones. The figure is
  // kneiphof2024-fig6 (about 0.9 s of CPU at quick, eto2023-fig4 2.8 s): a montage with its
  // panels, EXRs and a chart drawn by matplotlib.
  const RunResult r = run({"report", "--out", "r", "--claims", "kneiphof.total-area", "--figures",
                           "kneiphof2024-fig6", "--models", "smooth_ggx,deliot_belcour",
                           "--conformance", "deliot_belcour", "--skip", "bench,stability",
                           "--threads", "2"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("report: wrote r/index.html and r/report.md"), std::string::npos) << r.out;
  for (const char* f : {"r/index.html", "r/report.md", "r/run.json", "r/verify/claims.json",
                        "r/figures/figures.json", "r/figures/kneiphof2024-fig6/fig6.png",
                        "r/figures/kneiphof2024-fig6/fig6.csv",
                        "r/figures/kneiphof2024-fig6/p_map.png"})
    EXPECT_TRUE(fs::exists(path(f))) << f;
  const std::string html = read_text(path("r/index.html"));
  // The claim's row, anchored so the summary can link to it.
  EXPECT_NE(html.find("id=\"claim-kneiphof.total-area\""), std::string::npos);
  EXPECT_NE(html.find(">kneiphof.total-area</a></td>"), std::string::npos);
  // The montage drawn as labelled panels (its NAME.panels.json), the PNG itself linked.
  EXPECT_NE(html.find("src=\"plots/kneiphof2024-fig6__fig6_panels.png\""), std::string::npos);
  EXPECT_NE(html.find("href=\"figures/kneiphof2024-fig6/fig6.png\""), std::string::npos);
  EXPECT_NE(html.find("href=\"figures/kneiphof2024-fig6/sa0.1_gamma5.exr\""), std::string::npos);
  const std::string md = read_text(path("r/report.md"));
  EXPECT_NE(md.find("| kneiphof.total-area |"), std::string::npos);
  EXPECT_NE(
      md.find("![kneiphof2024-fig6 fig6.png panels](plots/kneiphof2024-fig6__fig6_panels.png)"),
      std::string::npos);
  const auto info = nlohmann::json::parse(read_text(path("r/run.json")));
  EXPECT_EQ(info["parts"]["claims"]["status"], "ran");
  EXPECT_EQ(info["parts"]["stability"]["status"], "skipped");
  EXPECT_EQ(info["budget"], "quick");
  // The compare part names the report's own folders, never the staging folder it was built in.
  const auto cmp = nlohmann::json::parse(read_text(path("r/compare/compare.json")));
  EXPECT_EQ(cmp["settings"]["claims_from"], "r/verify");
  ASSERT_EQ(cmp["models"].size(), 2u);
  EXPECT_EQ(cmp["models"][0]["name"], "smooth_ggx");
  EXPECT_EQ(cmp["models"][1]["name"], "deliot_belcour");
  EXPECT_EQ(cmp["models"][0]["reference"][0]["method"], "cubature");
  EXPECT_EQ(cmp["models"][1]["reference"][0]["method"], "monte-carlo");
  // Measured in this run (read from the conformance part) or recorded, never mixed.
  EXPECT_EQ(cmp["settings"]["conformance_from"], "r/conformance");
  EXPECT_EQ(info["parts"]["conformance"]["status"], "ran");
  EXPECT_EQ(info["parts"]["conformance"]["note"],
            "not measured (left out by --conformance): smooth_ggx");
  for (const auto& v : cmp["models"][1]["conformance"]) EXPECT_EQ(v["origin"], "read") << v.dump();
  for (const auto& v : cmp["models"][0]["conformance"])
    EXPECT_EQ(v["origin"], "recorded") << v.dump();
  EXPECT_NE(md.find("## Models' conformance"), std::string::npos);
  EXPECT_NE(md.find("| deliot_belcour | holds | holds |"), std::string::npos) << md;
  EXPECT_EQ(md.find("| smooth_ggx | holds"), std::string::npos) << md;
  EXPECT_EQ(html.find(".tmp."), std::string::npos) << "a staging path is shown in the report";
  // Nothing but the report itself is left in the working folder (no staging folder).
  for (const auto& e : fs::directory_iterator(work()))
    EXPECT_EQ(e.path().filename(), "r") << "left behind: " << e.path();
}

}  // namespace
}  // namespace glintlab::cli_test
