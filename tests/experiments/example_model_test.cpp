// docs/adding_a_model.md, end to end: the example glint model (example_glint_model.h) registered
// with one register_model line at run time goes through everything a registered model gets — the
// CLI-facing registry, its float instantiation, the stability sweep and its maps, the model-generic
// sampler-vs-pdf chi-square (with its negative control) and the registry-driven figure
// models-hemisphere. The benchmark (experiments/bench/bench_models.cpp) is exercised by the ctest
// example_model.benchmark where that target exists; the claim all.stability by
// PluginTest.SweepFigureAndGenericClaimCoverThePluginModel, with the same model as a plug-in.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "core/io/csv.h"
#include "core/io/exr.h"
#include "core/model_registry.h"
#include "experiments/example_glint_model.h"
#include "experiments/figures/figure_registry.h"
#include "experiments/sweeps/stability_maps.h"
#include "experiments/sweeps/stability_run.h"
#include "verify/check.h"
#include "verify/generic/model_sampler_gof.h"
#include "verify/stability/failure_region.h"
#include "verify/stats/multiple_testing.h"

namespace glintlab {
namespace {

namespace fs = std::filesystem;

// The one line a new model needs (here at run time; a built-in model puts
// m.push_back(make_model_entry<ExampleGlints>()) into core/model_registry.cpp instead).
const ModelEntry& example() {
  static const bool registered = [] {
    register_model(make_model_entry<example::ExampleGlints>());
    return true;
  }();
  (void)registered;
  return find_model("example_glints");
}

fs::path temp_dir(const std::string& tag) {
  const fs::path d = fs::temp_directory_path() / fmt::format("glintlab_{}_{}", tag, ::getpid());
  fs::remove_all(d);
  return d;
}

TEST(ExampleModel, RegistersOnceWithItsParametersAndFloatPath) {
  const ModelEntry& m = example();
  EXPECT_EQ(m.params.size(), 3u);
  EXPECT_TRUE(m.eval_float) << "the template kernels instantiate for float";
  EXPECT_THROW(register_model(make_model_entry<example::ExampleGlints>()), ModelParamError);
  const auto v = resolve_params(m, {{"density", "1e6"}});
  EXPECT_DOUBLE_EQ(v[2], 1e6);
  EXPECT_THROW(resolve_params(m, {{"density", "0.5"}}), ModelParamError);
  ModelQuery<double> q{};
  q.wi = {0, 0, 1};
  q.wo = {0, 0, 1};
  q.footprint = {{0.5, 0.5}, {1e-3, 0}, {0, 1e-3}};
  const ErasedEval e = m.eval(v, q);
  EXPECT_GT(e.value, 0);
  EXPECT_GT(e.intermediates[1], 0);  // p_hit
  EXPECT_LE(e.intermediates[1], 1);
}

TEST(ExampleModel, GetsTheStabilitySweepAndItsMaps) {
  example();
  const auto targets = verify::stability::sweep_targets("example_*");
  ASSERT_EQ(targets.size(), 1u);
  EXPECT_EQ(targets[0].id(), "example_glints/default");
  const auto s = verify::stability::sweep_model(targets[0], verify::Budget::kQuick);
  std::vector<std::string> planes;
  for (const auto& m : s.maps) planes.push_back(m.plane.name);
  EXPECT_EQ(planes, (std::vector<std::string>{"alpha", "anisotropy", "density", "footprint"}));
  EXPECT_TRUE(s.has_probability);
  EXPECT_TRUE(s.has_float);
  EXPECT_EQ(verify::stability::stability_verdict(s), verify::Verdict::kHolds)
      << verify::stability::describe_failure_region(s);

  const fs::path dir = temp_dir("example_sweep");
  experiments::SweepRunOptions o;
  o.models = "example_glints";
  const auto summary = experiments::run_sweeps(dir, o);
  std::ifstream in(summary.json);
  const auto doc = nlohmann::json::parse(in);
  EXPECT_EQ(doc["budget"], "quick");
  ASSERT_EQ(doc["models"].size(), 1u);
  const auto& entry = doc["models"][0];
  EXPECT_EQ(entry["model"], "example_glints");
  EXPECT_EQ(entry["sampler"], "default");
  EXPECT_EQ(entry["maps"].size(), 4u * 6u);  // 4 planes × nan, inf, negative, gain, p, variance
  for (const auto& map : entry["maps"]) {
    for (const char* k : {"exr", "csv"})
      EXPECT_TRUE(fs::exists(dir / map[k].get<std::string>())) << map[k];
    // The PNG's chart spec: `glintlab sweep` draws it (SweepRunOptions::finish), this run does not.
    fs::path spec = dir / map["png"].get<std::string>();
    EXPECT_TRUE(fs::exists(spec.replace_extension(".chart.json"))) << spec;
  }
  const io::ExrFile p = io::read_exr(dir / "example_glints/default/density_p_gt_1.exr");
  EXPECT_EQ(p.image.width, 12);  // θi columns
  EXPECT_EQ(p.attributes.at("glintlab_quantity"), "p_gt_1");
  const io::CsvTable t = io::read_csv(dir / "example_glints/default/footprint.csv");
  EXPECT_EQ(t.num_rows(), 7u * 12u);
  EXPECT_TRUE(t.find_column("footprint"));
  EXPECT_TRUE(t.find_column("nan_value_float_fraction"));
  fs::remove_all(dir);
}

TEST(ExampleModel, GetsTheGenericSamplerCheckAndItsControlIsRejected) {
  const ModelEntry& m = example();
  const auto v = resolve_params(m, {});
  ModelQuery<double> q{};
  q.wi = {0.5, 0.1, std::sqrt(1 - 0.26)};
  q.footprint = {{0.5, 0.5}, {1e-3, 0}, {0, 1e-3}};
  verify::ModelGofOptions o;
  o.samples = 1u << 15;
  const auto id = std::string("example.sampler-matches-pdf");
  const auto good = verify::model_sampler_chi_square(m, v, q, verify::check_seed(id, 0), o);
  EXPECT_FALSE(good.inconclusive) << good.reason;
  EXPECT_GT(good.p_value, verify::kFamilyWiseRate) << good.summary();
  o.pdf_scale = 1.05;  // the negative control: a pdf 5 % too large
  const auto bad = verify::model_sampler_chi_square(m, v, q, verify::check_seed(id, 1), o);
  EXPECT_TRUE(bad.rejects(verify::kFamilyWiseRate)) << bad.summary();
}

TEST(ExampleModel, GetsTheRegistryDrivenFigure) {
  example();
  const fs::path dir = temp_dir("example_fig");
  experiments::FigureContext ctx;
  ctx.quick = true;
  const fs::path out =
      experiments::run_figure(experiments::find_figure("models-hemisphere"), dir, ctx);
  // Its map as data and a chart spec; the PNG is drawn by matplotlib when `glintlab figure` runs
  // it (FigureContext::finish), which this direct run leaves out.
  EXPECT_TRUE(fs::exists(out / "example_glints.chart.json"));
  EXPECT_FALSE(fs::exists(out / "example_glints.png"));
  EXPECT_GT(io::read_csv(out / "example_glints_map.csv").num_rows(), 12000u);  // π/4 of 128²
  const io::ExrFile f = io::read_exr(out / "example_glints.exr");
  EXPECT_EQ(f.image.width, 128);
  f.image.channel("value");
  f.image.channel("pdf");
  const io::CsvTable t = io::read_csv(out / "models_hemisphere.csv");
  bool found = false;
  for (std::size_t r = 0; r < t.num_rows(); ++r) {
    if (t.text(r, t.column("model")) != "example_glints") continue;
    found = true;
    // The smooth GGX mean at α = 0.3: an albedo below 1; the VNDF puts a few % of its mass below
    // the horizon (rejected there), so the upper hemisphere holds a little less than 1.
    EXPECT_GT(t.number(r, t.column("albedo_estimate")), 0.8);
    EXPECT_LT(t.number(r, t.column("albedo_estimate")), 1.0);
    EXPECT_GT(t.number(r, t.column("pdf_mass_upper_hemisphere")), 0.8);
    EXPECT_LT(t.number(r, t.column("pdf_mass_upper_hemisphere")), 1.0);
    EXPECT_EQ(t.number(r, t.column("nonfinite_pixels")), 0);
  }
  EXPECT_TRUE(found);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace glintlab
