// `glintlab figure ID [--out DIR] [--quick] [--threads N]` and `glintlab figure --list`: runs a
// registered figure experiment (experiments/figures/).
#include <fmt/format.h>

#include <memory>
#include <string>

#include "cli/commands.h"
#include "cli/progress.h"
#include "core/io/environment_exr.h"
#include "experiments/figures/figure_registry.h"

namespace glintlab::cli {
namespace {

struct FigureOptions {
  std::string id;
  std::string out = "out/figures";
  bool quick = false;
  bool list = false;
  int threads = 0;
  std::string env;  // lat-long EXR environment map; empty = the experiment's procedural sky
};

void list_figures() {
  for (const experiments::FigureEntry& e : experiments::registered_figures()) {
    fmt::print("{:<24} {}, {}: {}\n", e.id, e.paper, e.target, e.description);
  }
}

void run(const FigureOptions& o) {
  if (o.list) {
    if (!o.id.empty()) throw InputError("figure: give either --list or a figure id, not both");
    list_figures();
    return;
  }
  if (o.id.empty()) {
    throw InputError("figure: a figure id is required (see glintlab figure --list)");
  }
  if (o.threads < 0 || o.threads > 1024) {
    throw InputError(
        fmt::format("--threads: {} is out of range (valid: an integer in [0, 1024], "
                    "0 = all cores)",
                    o.threads));
  }
  try {
    const experiments::FigureEntry& entry = experiments::find_figure(o.id);
    experiments::FigureContext ctx;
    ctx.quick = o.quick;
    ctx.threads = o.threads;
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
    const auto dir = experiments::run_figure(entry, o.out, ctx);
    bar.reset();
    fmt::print("{}: wrote {}\n", entry.id, dir.string());
  } catch (const experiments::FigureError& e) {
    throw InputError(e.what());
  }
}

constexpr const char* kFooter =
    R"(Each experiment writes into DIR/<id>/ (default DIR: out/figures): EXR images (32-bit float
R, G, B plus extra channels; header attributes glintlab_model, glintlab_parameters, glintlab_seed,
glintlab_spp, glintlab_reference_spp, glintlab_version), a tonemapped PNG preview and a CSV of
every number the figure plots. Files are written into a staging folder that replaces DIR/<id>
only when the whole experiment succeeded. Output is identical for any --threads.)";

}  // namespace

void add_figure_command(CLI::App& app) {
  auto o = std::make_shared<FigureOptions>();
  CLI::App* cmd = app.add_subcommand("figure", "Run a registered paper-figure experiment");
  cmd->add_option("id", o->id, "Figure id (see --list)");
  cmd->add_flag("--list", o->list,
                "List the registered experiments and the figure each reproduces");
  cmd->add_option("--out", o->out, "Output folder (default out/figures)");
  cmd->add_flag("--quick", o->quick, "Smaller images and sample budgets (seconds)");
  cmd->add_option("--threads", o->threads,
                  "Worker threads (0 = all cores; the output is the same)");
  cmd->add_option("--env", o->env,
                  "Lat-long EXR environment map (R, G, B radiance; width = 2 x height; row 0 at "
                  "the zenith, z up) lighting the experiments that use one, instead of their "
                  "procedural sky");
  cmd->footer(kFooter);
  cmd->callback([o] { run(*o); });
}

}  // namespace glintlab::cli
