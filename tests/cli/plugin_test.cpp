// Model plug-ins (glintlab/plugin.h, core/plugin_loader.h) through the CLI: the example model
// built as a plug-in (tests/plugin/example_plugin.cpp) is listed, evaluates and samples with the
// same numbers as the same model registered in this process, and reaches the sweeps, the generic
// claims, the registry-driven figure and a report; each kind of bad plug-in is refused with one line.
#include <gtest/gtest.h>
#include <stdlib.h>

#include <cmath>
#include <map>
#include <nlohmann/json.hpp>
#include <string>

#include "cli/cli_test_util.h"
#include "core/model_registry.h"
#include "experiments/example_glint_model.h"

namespace glintlab::cli_test {
namespace {

using PluginTest = CliTest;

// The same model, registered in this process as a built-in model would be: the reference the
// plug-in's numbers must equal.
const ModelEntry& in_process_example() {
  static const ModelEntry entry = make_model_entry<example::ExampleGlints>();
  return entry;
}

// Sets an environment variable for the runs of one test (the children inherit it).
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const std::string& value) : name_(name) {
    setenv(name, value.c_str(), 1);
  }
  ~ScopedEnv() { unsetenv(name_); }
  ScopedEnv(const ScopedEnv&) = delete;
  ScopedEnv& operator=(const ScopedEnv&) = delete;

 private:
  const char* name_;
};

ModelQuery<double> query_of(const io::CsvTable& t, std::size_t row) {
  const auto c = [&](const char* name) { return cell_value(t, row, t.column(name)); };
  ModelQuery<double> q{};
  q.footprint.uv = {c("u"), c("v")};
  q.footprint.duv_dx = {c("dudx"), c("dvdx")};
  q.footprint.duv_dy = {c("dudy"), c("dvdy")};
  q.wi = {c("wi_x"), c("wi_y"), c("wi_z")};
  q.wo = {c("wo_x"), c("wo_y"), c("wo_z")};
  q.light = {c("light_cos_half_angle"), c("light_intensity")};
  return q;
}

const char* const kQueries =
    "wi_x,wi_y,wi_z,wo_x,wo_y,wo_z,u,v,dudx,dvdx,dudy,dvdy\n"
    "0.6,0,0.8,-0.36,0.48,0.8,0.1,0.2,0.001,0,0,0.002\n"
    "0,0,1,0.6,0,0.8,0.5,0.5,0.01,0.002,0,0.01\n"
    "0.8,0,0.6,0,0.6,0.8,0.3,0.7,0.0001,0.00002,0.00001,0.0003\n";

TEST_F(PluginTest, ListedByModelsWithItsParameters) {
  const RunResult r = run({"--plugin", kTestPlugin, "models"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* s : {"example_glints:", "needs: footprint", "--param density=10000",
                        "intermediates: expected_facets, p_hit", "smooth_ggx:"}) {
    EXPECT_NE(r.out.find(s), std::string::npos) << s;
  }
  // Without the plug-in the model is not there: the listing above came from loading it.
  EXPECT_EQ(run({"models"}).out.find("example_glints"), std::string::npos);
}

TEST_F(PluginTest, EnvironmentVariableLoadsColonSeparatedPaths) {
  const ScopedEnv env("GLINTLAB_PLUGINS", std::string("::") + kTestPlugin + ":");
  const RunResult r = run({"models"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("example_glints:"), std::string::npos);
}

TEST_F(PluginTest, EvalGivesTheNumbersOfTheInProcessModel) {
  write_text(path("q.csv"), kQueries);
  // --isa scalar: the plug-in's scalar batches are the thunks' code, bit for bit; the other ISAs
  // agree within the budgets of tests/simd (tests/simd/plugin_batch_test.cpp).
  const RunResult r = run({"--plugin", kTestPlugin, "eval", "--model", "example_glints", "--param",
                           "density=1e6", "--isa", "scalar", "--in", "q.csv", "--out", "r.csv"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const io::CsvTable t = io::read_csv(path("r.csv"));
  ASSERT_EQ(t.num_rows(), 3u);
  const ModelEntry& m = in_process_example();
  const std::vector<double> values = resolve_params(m, {{"density", "1e6"}});
  for (std::size_t i = 0; i < t.num_rows(); ++i) {
    const ErasedEval e = m.eval(values, query_of(t, i));
    // Bit for bit: the same kernels, compiled in the plug-in, reached through its thunks.
    EXPECT_EQ(cell_value(t, i, t.column("value")), e.value) << "row " << i;
    EXPECT_EQ(cell_value(t, i, t.column("pdf")), e.pdf) << "row " << i;
    EXPECT_EQ(cell_value(t, i, t.column("expected_facets")), e.intermediates[0]) << "row " << i;
    EXPECT_EQ(cell_value(t, i, t.column("p_hit")), e.intermediates[1]) << "row " << i;
  }
  EXPECT_GT(cell_value(t, 0, t.column("value")), 0.0);
}

TEST_F(PluginTest, SampleWeightsAndPdfsMatchTheInProcessModel) {
  const RunResult r = run({"--plugin", kTestPlugin, "sample", "--model", "example_glints", "--wi",
                           "0.6,0,0.8", "--n", "200", "--query",
                           "u=0.1,v=0.2,dudx=0.001,dvdx=0,dudy=0,dvdy=0.002", "--out", "s.csv"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const io::CsvTable t = io::read_csv(path("s.csv"));
  ASSERT_EQ(t.num_rows(), 200u);
  const ModelEntry& m = in_process_example();
  const std::vector<double> values = resolve_params(m, {});
  ModelQuery<double> q{};
  q.footprint.uv = {0.1, 0.2};
  q.footprint.duv_dx = {0.001, 0.0};
  q.footprint.duv_dy = {0.0, 0.002};
  q.wi = {0.6, 0.0, 0.8};
  q.light = {1.0, 1.0};
  std::size_t accepted = 0;
  for (std::size_t i = 0; i < t.num_rows(); ++i) {
    if (cell_value(t, i, t.column("rejected")) != 0.0) continue;
    ++accepted;
    q.wo = {cell_value(t, i, t.column("wo_x")), cell_value(t, i, t.column("wo_y")),
            cell_value(t, i, t.column("wo_z"))};
    const ErasedEval e = m.eval(values, q);
    const double pdf = cell_value(t, i, t.column("pdf"));
    const double weight = cell_value(t, i, t.column("weight"));
    // The sampler computes its pdf and weight from its own ωo before it is printed and re-read:
    // equal to rounding.
    EXPECT_NEAR(pdf, e.pdf, 1e-9 * e.pdf) << "row " << i;
    EXPECT_NEAR(weight, e.value / e.pdf, 1e-9 * weight) << "row " << i;
  }
  EXPECT_GT(accepted, 150u);
}

TEST_F(PluginTest, SweepFigureAndGenericClaimCoverThePluginModel) {
  // The sweep's maps and the figure's charts are drawn by the stand-in: this test reads what the
  // runs compute for the plug-in model; matplotlib draws the same maps and charts of the built-in
  // models in SweepTest.QuickSweepWritesMapsAndIndex and
  // FigureTest.ModelsHemisphereMapsAreChartsOfTheirCsv.
  stand_in_charts();
  const RunResult sweep = run({"--plugin", kTestPlugin, "sweep", "--models", "example_glints",
                               "--budget", "quick", "--out", "sweeps"});
  ASSERT_EQ(sweep.exit_code, 0) << sweep.err;
  const auto stability = nlohmann::json::parse(read_text(path("sweeps/stability.json")));
  ASSERT_EQ(stability["models"].size(), 1u);
  EXPECT_EQ(stability["models"][0]["model"], "example_glints");

  const RunResult figure = run({"--plugin", kTestPlugin, "figure", "models-hemisphere", "--budget",
                                "quick", "--out", "figures"});
  ASSERT_EQ(figure.exit_code, 0) << figure.err;
  EXPECT_TRUE(std::filesystem::exists(path("figures/models-hemisphere/example_glints.exr")));
  EXPECT_NE(
      read_text(path("figures/models-hemisphere/models_hemisphere.csv")).find("example_glints"),
      std::string::npos);

  // all.stability at the quick budget, the one run of it in the suite (it sweeps every model, the
  // plug-in's too): exit 0 is its recorded verdict; its negative control, the NaN model of
  // verify/stability/nan_control.h, is rejected by the same decision.
  const RunResult verify = run({"--plugin", kTestPlugin, "verify", "--claims", "all.stability",
                                "--budget", "quick", "--out", "verify"});
  ASSERT_EQ(verify.exit_code, 0) << verify.err;
  const auto claims = nlohmann::json::parse(read_text(path("verify/claims.json")));
  ASSERT_EQ(claims.size(), 1u);
  const auto& row = claims[0];
  const std::string detail = row["detail"].get<std::string>();
  EXPECT_NE(detail.find("example_glints/default"), std::string::npos) << detail;
  EXPECT_NE(detail.find("smooth_ggx/vndf"), std::string::npos) << detail;
  const std::string verdict = row["verdict"].get<std::string>();
  EXPECT_EQ(verdict, row["expected_verdict"].get<std::string>());
  EXPECT_TRUE(row["control_rejected"].get<bool>()) << row["control"];
  // The control's verdict opposes the genuine one (verify/check.h control_opposes).
  ASSERT_TRUE(row["control_verdict"].is_string()) << row.dump();
  const std::string control = row["control_verdict"].get<std::string>();
  const auto holding = [](const std::string& v) {
    return v == "holds" || v == "holds-within" || v == "holds-in-regime";
  };
  if (holding(verdict)) {
    EXPECT_EQ(control, "fails") << verdict;
  } else if (verdict == "fails") {
    EXPECT_TRUE(holding(control)) << control;
  } else {
    EXPECT_NE(control, "inconclusive") << verdict;
  }
  EXPECT_EQ(verdict == "holds-in-regime", !row["regime"].is_null()) << row["regime"];
  EXPECT_NE(row["control"].get<std::string>().find("NaN in value"), std::string::npos)
      << row["control"];
  EXPECT_GT(row["configurations"].get<int>(), 0);
}

// `glintlab --plugin X report`: the report's verify, conformance and sweep parts run as child
// processes, which get the same --plugin, so the plug-in model's conformance suite, stability sweep
// and compare row are all in the report, its verdicts shown as measured in this run.
TEST_F(PluginTest, ReportCoversThePluginModelInEveryPart) {
  const RunResult r = run({"--plugin", kTestPlugin, "report", "--out", "r", "--claims",
                           "model.example_glints.energy", "--models", "example_glints", "--skip",
                           "figures,bench", "--threads", "2"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(read_text(path("r/verify/claims.json")).find("\"model.example_glints.energy\""),
            std::string::npos);
  const auto stability = nlohmann::json::parse(read_text(path("r/stability/stability.json")));
  ASSERT_EQ(stability["models"].size(), 1u);
  EXPECT_EQ(stability["models"][0]["model"], "example_glints");
  const auto compare = nlohmann::json::parse(read_text(path("r/compare/compare.json")));
  ASSERT_EQ(compare["models"].size(), 1u);
  EXPECT_EQ(compare["models"][0]["name"], "example_glints");
  const auto conformance = nlohmann::json::parse(read_text(path("r/conformance/claims.json")));
  EXPECT_EQ(conformance.size(), compare["models"][0]["conformance"].size());
  for (const auto& v : compare["models"][0]["conformance"])
    EXPECT_EQ(v["origin"], "read") << v.dump();
  EXPECT_EQ(compare["models"][0]["stability"][0]["origin"].get<std::string>().find("not"),
            std::string::npos)
      << compare["models"][0]["stability"].dump();
}

// A plug-in whose eval throws (throwing_eval) or returns NaN (nan_eval): the checks that need eval
// report verdict error naming the model and the cause (energy too: it integrates eval's value),
// the checks that do not (pdf-normalized reads only pdf()) and the paper's claim run as usual, the stability sweep's NaN is that
// property's fails, the files are written with every row, and the exit status is 3.
TEST_F(PluginTest, FaultyEvalIsReportedAsErrorAndTheRunGoesOn) {
  const RunResult r =
      run({"--plugin", kTestPluginFaultyEval, "verify", "--claims",
           "model.throwing_eval.*,model.nan_eval.*,smooth.projected-area", "--budget", "quick",
           "--out", "verify"});
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_NE(r.err.find("glintlab: error: model throwing_eval: eval-pdf-consistency: exception: "
                       "throwing_eval: eval failed on purpose"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("could not be checked (verdict error)"), std::string::npos) << r.err;
  for (const char* file : {"verify/claims.json", "verify/claims.csv", "verify/claims.md"})
    ASSERT_TRUE(std::filesystem::exists(path(file))) << file;
  std::map<std::string, nlohmann::json> rows;
  for (const auto& row : nlohmann::json::parse(read_text(path("verify/claims.json"))))
    rows[row["id"].get<std::string>()] = row;
  ASSERT_EQ(rows.size(), 17u);
  auto verdict = [&](const std::string& id) { return rows.at(id)["verdict"].get<std::string>(); };
  auto detail = [&](const std::string& id) { return rows.at(id)["detail"].get<std::string>(); };

  EXPECT_EQ(verdict("smooth.projected-area"), "holds");
  EXPECT_TRUE(rows.at("smooth.projected-area")["control_rejected"].get<bool>());
  // An exception from eval, thrown inside the checks' parallel loops.
  for (const char* p : {"eval-pdf-consistency", "sampler-covers-value", "float-vs-double",
                        "stability", "energy"}) {
    const std::string id = std::string("model.throwing_eval.") + p;
    EXPECT_EQ(verdict(id), "error") << id;
    EXPECT_NE(detail(id).find(std::string("model throwing_eval: ") + p + ": exception: "
                              "throwing_eval: eval failed on purpose"),
              std::string::npos)
        << detail(id);
    EXPECT_TRUE(rows.at(id)["control_verdict"].is_null()) << id;
  }
  EXPECT_EQ(verdict("model.throwing_eval.pdf-normalized"), "holds");
  // NaN where a number is required: what was not finite is named.
  EXPECT_EQ(verdict("model.nan_eval.sampler-covers-value"), "error");
  EXPECT_NE(detail("model.nan_eval.sampler-covers-value").find("∫ value dωo at"),
            std::string::npos);
  EXPECT_NE(detail("model.nan_eval.sampler-covers-value").find("is nan"), std::string::npos);
  EXPECT_EQ(verdict("model.nan_eval.float-vs-double"), "error");
  EXPECT_NE(detail("model.nan_eval.float-vs-double").find("not finite on any of the 20000"),
            std::string::npos);
  EXPECT_EQ(verdict("model.nan_eval.sampler-matches-pdf"), "error");
  EXPECT_EQ(verdict("model.nan_eval.energy"), "error");
  EXPECT_EQ(verdict("model.nan_eval.pdf-normalized"), "holds");
  // The NaN a check exists to find is its verdict, not an error.
  EXPECT_EQ(verdict("model.nan_eval.stability"), "fails");
  EXPECT_TRUE(rows.at("model.nan_eval.stability")["control_rejected"].get<bool>());
  EXPECT_NE(read_text(path("verify/claims.csv")).find(",error,"), std::string::npos);
  EXPECT_NE(read_text(path("verify/claims.md")).find("**error**"), std::string::npos);

  // The printed table: a row that measured nothing prints no number, and a plug-in has no recorded
  // verdict to be compared with, only what a conforming model gives.
  auto line = [&](const std::string& id) {
    const std::size_t at = r.out.find("\n" + id + " ");
    if (at == std::string::npos) return std::string();
    return r.out.substr(at + 1, r.out.find('\n', at + 1) - at - 1);
  };
  const std::string error_row = line("model.throwing_eval.eval-pdf-consistency");
  ASSERT_FALSE(error_row.empty()) << r.out;
  EXPECT_EQ(error_row.find(" = "), std::string::npos) << error_row;
  EXPECT_EQ(error_row.find("recorded verdict"), std::string::npos) << error_row;
  EXPECT_NE(error_row.find("[a conforming model: holds; nothing recorded for this model]"),
            std::string::npos)
      << error_row;
  const std::string fails_row = line("model.nan_eval.stability");
  EXPECT_NE(fails_row.find(" = "), std::string::npos) << fails_row;
  EXPECT_NE(fails_row.find("[a conforming model: holds; nothing recorded for this model]"),
            std::string::npos)
      << fails_row;
  const std::string paper_row = line("smooth.projected-area");
  EXPECT_NE(paper_row.find(" = "), std::string::npos) << paper_row;
  EXPECT_EQ(paper_row.find('['), std::string::npos) << paper_row;
  for (const auto& [id, row] : rows)
    if (row["verdict"] == "not claimed") {
      EXPECT_EQ(line(id).find(" = "), std::string::npos) << line(id);
      EXPECT_NE(line(id).find("none (not claimed)"), std::string::npos) << line(id);
    }
}

TEST_F(PluginTest, MissingFileIsRefused) {
  expect_input_error(run({"--plugin", "no_such_plugin.so", "models"}),
                     {"--plugin no_such_plugin.so:", "no such file"}, {});
  const ScopedEnv env("GLINTLAB_PLUGINS", "no_such_plugin.so");
  expect_input_error(run({"models"}), {"GLINTLAB_PLUGINS: no_such_plugin.so:", "no such file"}, {});
}

TEST_F(PluginTest, FileThatIsNotALoadableModuleIsRefused) {
  write_text(path("text.so"), "not an ELF file\n");
  expect_input_error(run({"--plugin", "text.so", "models"}),
                     {"--plugin text.so:", "cannot be loaded"}, {"text.so"});
}

TEST_F(PluginTest, ModuleWithoutTheEntryPointIsRefused) {
  expect_input_error(run({"--plugin", kTestNotAPlugin, "models"}),
                     {"--plugin", "not a glintlab plug-in", "glintlab_plugin_v1"}, {});
}

TEST_F(PluginTest, PluginBuiltAgainstAnotherVersionIsRefused) {
  expect_input_error(
      run({"--plugin", kTestPluginWrongVersion, "models"}),
      {"--plugin", "built against glintlab 0.0.1", std::string("this is glintlab ") + kVersion},
      {});
}

TEST_F(PluginTest, NameClashesAreRefused) {
  expect_input_error(run({"--plugin", kTestPluginBuiltinClash, "models"}),
                     {"--plugin", "model 'smooth_ggx' clashes"}, {});
  expect_input_error(run({"--plugin", kTestPlugin, "--plugin", kTestPlugin, "models"}),
                     {"--plugin", "model 'example_glints' clashes"}, {});
}

TEST_F(PluginTest, MisspelledNotClaimedPropertyIsRefused) {
  expect_input_error(
      run({"--plugin", kTestPluginMisspelledNotClaimed, "models"}),
      {"--plugin", "model 'misspelled_not_claimed'", "'enrgy'", "not a conformance property",
       "valid: eval-pdf-consistency", "energy", "constant-time"},
      {});
}

TEST_F(PluginTest, PluginWithoutAPathIsRefused) {
  expect_input_error(run({"--plugin"}), {"--plugin: needs a value"}, {});
}

}  // namespace
}  // namespace glintlab::cli_test
