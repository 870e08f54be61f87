// `glintlab sweep [--out DIR] [--quick] [--models GLOB] [--threads N]`: the stability maps of every
// registered model × sampler (claim all.stability; experiments/sweeps/).
#include <fmt/format.h>
#include <tbb/global_control.h>
#include <tbb/info.h>

#include <memory>
#include <string>

#include "cli/commands.h"
#include "cli/progress.h"
#include "experiments/sweeps/stability_run.h"

namespace glintlab::cli {
namespace {

struct SweepOptions {
  std::string out = "out/sweeps";
  bool quick = false;
  std::string models;
  int threads = 0;
};

void run(const SweepOptions& o) {
  if (o.threads < 0 || o.threads > 1024) {
    throw InputError(
        fmt::format("--threads: {} is out of range (valid: an integer in [0, 1024], 0 = all cores)",
                    o.threads));
  }
  const int threads = o.threads > 0 ? o.threads : tbb::info::default_concurrency();
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, std::size_t(threads));
  experiments::SweepRunOptions r;
  r.budget = o.quick ? verify::Budget::kQuick : verify::Budget::kFull;
  r.models = o.models;
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
    const auto s = experiments::run_sweeps(o.out, r);
    bar.reset();
    fmt::print("sweep: {} model×sampler targets; wrote {}\n", s.targets, s.json.string());
  } catch (const experiments::SweepError& e) {
    throw InputError(e.what());
  }
}

constexpr const char* kFooter =
    R"(For every registered model and every choice of its `sampler` parameter, eval/pdf/sample
(double, and float where the model has a float instantiation) are swept over planes of a
parameter x the incidence angle theta_i (0 .. 89.999 deg, and back-facing): alpha 1e-4 .. 4,
anisotropy alpha_x/alpha_y 1 .. 1000, `density` and `microroughness` over their ranges,
footprint size (footprint models) and light half-angle (light models). Per cell: fractions of
NaN, Inf and negative values, the white-furnace albedo (energy gain > 1 beyond 4 standard
errors), p > 1 for probability intermediates (named p or p_*), and Var(w)/E(w)^2 of the
sample weight (blow-up above 100).
Writes DIR/<model>/<sampler>/<plane>.csv (every number per cell), <plane>_<quantity>.exr (one
pixel per cell; row 0 = the smallest row value) and .png, and DIR/stability.json: machine,
budget, and per target its maps and its failure region in words. Files are staged and moved
into DIR only when every target finished. Output is identical for any --threads.)";

}  // namespace

void add_sweep_command(CLI::App& app) {
  auto o = std::make_shared<SweepOptions>();
  CLI::App* cmd =
      app.add_subcommand("sweep", "Stability maps of every registered model (all.stability)");
  cmd->add_option("--out", o->out, "Output folder (default out/sweeps)");
  cmd->add_flag("--quick", o->quick, "Coarser grids and 64 + 64 calls per cell (seconds)");
  cmd->add_option("--models", o->models,
                  "Comma-separated globs over model names (default: every registered model)");
  cmd->add_option("--threads", o->threads,
                  "Worker threads (0 = all cores; the output is the same)");
  cmd->footer(kFooter);
  cmd->callback([o] { run(*o); });
}

}  // namespace glintlab::cli
