// `glintlab figure ID [--out DIR] [--budget quick|full] [--threads N] [--env FILE]
// [--bench-from DIR]` and `glintlab figure --list`: runs a registered figure experiment
// (experiments/figures/).
#include <fmt/format.h>

#include <filesystem>
#include <memory>
#include <string>

#include "cli/commands.h"
#include "cli/input.h"
#include "cli/progress.h"
#include "cli/suite_runs.h"
#include "core/io/environment_exr.h"
#include "experiments/figures/figure_registry.h"

namespace glintlab::cli {
namespace {

struct FigureOptions {
  std::string id;
  std::string out = "out/figures";
  BudgetOption budget;
  bool list = false;
  std::string threads;
  std::string env;         // lat-long EXR environment map; empty = the experiment's procedural sky
  std::string bench_from;  // folder of Google Benchmark JSON for the timing figures
};

constexpr const char* kBenchFiles =
    "a folder of Google Benchmark JSON: glints.json of glintlab_bench_glints, kemppinen.json of "
    "glintlab_bench_kemppinen";

void list_figures() {
  for (const experiments::FigureEntry& e : experiments::registered_figures()) {
    fmt::print("{:<24} {}, {}: {}\n", e.id, e.paper, e.target, e.description);
  }
}

void run(const CLI::App* cmd, const FigureOptions& o) {
  if (o.list) {
    if (!o.id.empty())
      throw InputError(fmt::format(
          "figure: '{}' given with --list (valid: either --list or a figure id)", o.id));
    list_figures();
    return;
  }
  check_figure_id(o.id);
  FigureRequest r;
  r.id = o.id;
  r.out = o.out;
  r.budget = resolve_budget(cmd, o.budget);
  r.threads = o.threads;
  r.env = o.env;
  if (option_count(cmd, "--bench-from") > 0) r.bench_from = o.bench_from;
  const auto dir = run_figure_request(r);
  fmt::print("{}: wrote {}\n", r.id, dir.string());
}

constexpr const char* kFooter =
    R"(Each experiment writes into DIR/<id>/ (default DIR: out/figures): EXR images (32-bit float
R, G, B plus extra channels; header attributes glintlab_model, glintlab_parameters, glintlab_seed,
glintlab_spp, glintlab_reference_spp, glintlab_version), a tonemapped PNG preview and a CSV of
every number the figure plots. Files are written into a staging folder that replaces DIR/<id>
only when the whole experiment succeeded. Output is identical for any --threads. The timing figures
(kneiphof2024-table1, kemppinen2025-table3, kemppinen2025-speed-accuracy) read benchmark JSON only
from --bench-from DIR (DIR/glints.json, DIR/kemppinen.json); without it they say so, and the
Kemppinen ones time their rows in process.)";

}  // namespace

void check_figure_id(const std::string& id) {
  if (id.empty())
    throw InputError("figure: a figure id is required (valid: an id of glintlab figure --list)");
}

std::filesystem::path run_figure_request(const FigureRequest& o) {
  check_figure_id(o.id);
  const bool quick = quick_budget(o.budget);
  // 0 = all cores is passed on as 0: the experiments size their own pools.
  const int threads = int(integer_option(o.threads, "--threads", 0, 1024));
  std::error_code ec;
  if (o.bench_from && !std::filesystem::is_directory(*o.bench_from, ec))
    throw InputError(
        fmt::format("--bench-from: '{}' is not a folder (valid: {})", *o.bench_from, kBenchFiles));
  try {
    const experiments::FigureEntry& entry = experiments::find_figure(o.id);
    check_output_dir(o.out, "--out");
    register_staging_parent(o.out);
    experiments::FigureContext ctx;
    ctx.quick = quick;
    ctx.threads = threads;
    ctx.bench_dir = o.bench_from.value_or(std::string());
    if (!o.env.empty()) {
      // Loaded before anything is written, so a missing or malformed map leaves no output.
      try {
        ctx.environment = std::make_shared<const EnvironmentMap>(io::load_environment_map(o.env));
      } catch (const io::ExrError& e) {
        throw InputError(fmt::format("--env: {}", e.what()));
      }
      ctx.environment_name = fmt::format("lat-long EXR {} ({}x{})", o.env, ctx.environment->width(),
                                         ctx.environment->height());
    }
    std::unique_ptr<Progress> bar;
    std::string current;
    ctx.progress = [&](const std::string& stage, long done, long total) {
      if (stage != current) {
        bar = std::make_unique<Progress>(stage, total);
        current = stage;
      }
      bar->step("rows");
      (void)done;
    };
    return experiments::run_figure(entry, o.out, ctx);
  } catch (const experiments::FigureError& e) {
    throw InputError(e.what());
  }
}

void add_figure_command(CLI::App& app) {
  auto o = std::make_shared<FigureOptions>();
  CLI::App* cmd = add_command(app, "figure", "Run a registered paper-figure experiment");
  o->budget.budget = "full";
  add_text_option(cmd, "id", o->id, "figure id: one of glintlab figure --list", "ID");
  add_bool_flag(cmd, "--list", o->list,
                "list the registered experiments and the figure each reproduces");
  add_text_option(cmd, "--out", o->out, "output folder", "DIR");
  add_budget_option(cmd, o->budget,
                    "quick = smaller images and sample budgets (seconds), full = the paper's");
  add_threads_option(cmd, o->threads);
  add_text_option(cmd, "--env", o->env,
                  "lat-long EXR environment map (R, G, B radiance; width = 2 x height; row 0 at "
                  "the zenith, z up) lighting the experiments that use one, instead of their "
                  "procedural sky",
                  "FILE");
  add_text_option(cmd, "--bench-from", o->bench_from,
                  std::string(kBenchFiles) +
                      ", read by the timing figures (e.g. out/bench); none = no benchmark data",
                  "DIR");
  set_footer(cmd, kFooter);
  set_callback(cmd, [cmd, o] { run(cmd, *o); });
}

}  // namespace glintlab::cli
