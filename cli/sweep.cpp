// `glintlab sweep [--out DIR] [--budget quick|full] [--models GLOBS] [--threads N]`: the stability
// maps of every registered model × sampler (claim all.stability; experiments/sweeps/).
#include <fmt/format.h>
#include <tbb/global_control.h>
#include <tbb/info.h>

#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "cli/input.h"
#include "cli/progress.h"
#include "cli/suite_runs.h"
#include "core/model_registry.h"
#include "experiments/sweeps/stability_run.h"

namespace glintlab::cli {
namespace {

struct SweepOptions {
  std::string out = "out/sweeps";
  BudgetOption budget;
  std::string models = "*";
  std::string threads;
};

void run(const CLI::App* cmd, const SweepOptions& o) {
  SweepRequest r;
  r.out = o.out;
  r.budget = resolve_budget(cmd, o.budget);
  r.models = o.models;
  r.threads = o.threads;
  const auto s = run_sweep_request(r);
  // Each target's verdict and failure region, as stability.json records them.
  const nlohmann::json doc = nlohmann::json::parse(std::ifstream(s.json));
  for (const auto& m : doc.at("models")) {
    fmt::print("{:<32} {:<16} {}\n",
               m.value("model", std::string()) + "/" + m.value("sampler", std::string()),
               m.value("verdict", std::string()), m.value("failure_region", std::string()));
  }
  fmt::print("sweep: {} model×sampler targets; wrote {}\n", s.targets, s.json.string());
}

constexpr const char* kFooter =
    R"(For every registered model and every choice of its `sampler` parameter, eval/pdf/sample
(double, and float where the model has a float instantiation) are swept over planes of a
parameter x the incidence angle theta_i (0 .. 89.999 deg, and back-facing): alpha 1e-4 .. 4,
anisotropy alpha_x/alpha_y 1 .. 1000, `density` and `microroughness` over their ranges,
footprint size (footprint models) and light half-angle (light models). Per cell: fractions of
NaN, Inf and negative values, the white-furnace albedo (energy gain > 1 beyond 4 standard
errors), p > 1 for probability intermediates (named p or p_*), and Var(w)/E(w)^2 of the
sample weight at the worst of 4 fixed surface positions (blow-up above 81.92, a pixel still 10 %
noisy at 8192 samples; docs/stability.md).
Writes DIR/<model>/<sampler>/<plane>.csv (every number per cell), <plane>_<quantity>.exr (one
pixel per cell; row 0 = the smallest row value) and .png, and DIR/stability.json: machine,
budget, and per target its maps and its failure region in words. Files are staged and moved
into DIR only when every target finished. Output is identical for any --threads.)";

}  // namespace

experiments::SweepRunSummary run_sweep_request(const SweepRequest& o) {
  const bool quick = quick_budget(o.budget);
  std::vector<std::string> names;
  for (const ModelEntry& m : registered_models()) names.emplace_back(m.name);
  // Every glob must name a model; the sweep gets the trimmed list.
  (void)select_by_globs(o.models, "--models", names,
                        fmt::format("model names: {}", fmt::join(names, ", ")));
  const std::vector<std::string> globs = split_list(o.models, "--models", "");
  const int threads = resolve_threads(o.threads);
  check_output_dir(o.out, "--out");
  register_staging_parent(o.out);
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, std::size_t(threads));
  experiments::SweepRunOptions r;
  r.budget = quick ? verify::Budget::kQuick : verify::Budget::kFull;
  r.models = fmt::format("{}", fmt::join(globs, ","));
  std::unique_ptr<Progress> bar;
  std::string current;
  r.progress = [&](const std::string& target, long, long total) {
    if (target != current) {
      bar = std::make_unique<Progress>("sweep " + target, total);
      current = target;
    }
    bar->step("planes");
  };
  try {
    return experiments::run_sweeps(o.out, r);
  } catch (const experiments::SweepError& e) {
    throw InputError(e.what());
  }
}

void add_sweep_command(CLI::App& app) {
  auto o = std::make_shared<SweepOptions>();
  CLI::App* cmd =
      add_command(app, "sweep", "Stability maps of every registered model (all.stability)");
  o->budget.budget = "full";
  add_text_option(cmd, "--out", o->out, "output folder", "DIR");
  add_budget_option(cmd, o->budget,
                    "quick = coarser grids and 64 + 64 calls per cell (seconds), full = finer");
  add_text_option(cmd, "--models", o->models,
                  "comma-separated globs over model names (see glintlab models)", "LIST");
  add_threads_option(cmd, o->threads);
  set_footer(cmd, kFooter);
  set_callback(cmd, [cmd, o] { run(cmd, *o); });
}

}  // namespace glintlab::cli
