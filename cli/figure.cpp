// `glintlab figure IDS [--out DIR] [--budget quick|full] [--threads N] [--env FILE]
// [--bench-from DIR] [--shard K/N]` and `glintlab figure --list`: runs registered figure
// experiments (experiments/figures/), a selection of ids and globs, or shard K of N of it.
#include <fmt/format.h>
#include <fnmatch.h>

#include <algorithm>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "cli/child_process.h"
#include "cli/commands.h"
#include "cli/figure_costs.h"
#include "cli/input.h"
#include "cli/progress.h"
#include "cli/shard.h"
#include "cli/shard_plan.h"
#include "cli/suite_runs.h"
#include "core/io/atomic_file.h"
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
  std::string shard;       // K/N: run the K-th of N cost-balanced shards of the selection
};

constexpr const char* kBenchFiles =
    "a folder of Google Benchmark JSON: glints.json of glintlab_bench_glints, kemppinen.json of "
    "glintlab_bench_kemppinen";

// One line per figure: id, paper, target, description and its measured cost, the weight of
// --shard's balance (cli/figure_costs.cpp).
void list_figures() {
  for (const experiments::FigureEntry& e : experiments::registered_figures()) {
    const auto& costs = figure_costs();
    const auto c =
        std::find_if(costs.begin(), costs.end(), [&](const FigureCost& f) { return f.id == e.id; });
    const auto seconds = [](double s) {
      return s >= 10 ? fmt::format("{:.0f} s", s) : fmt::format("{:.2g} s", s);
    };
    const std::string cost = c == costs.end()
                                 ? std::string("CPU not measured")
                                 : fmt::format("CPU quick {}, full {}", seconds(c->quick_seconds),
                                               seconds(c->full_seconds));
    fmt::print("{:<24} {}, {}: {} ({})\n", e.id, e.paper, e.target, e.description, cost);
  }
}

// The figures a selection names, in registry order: comma-separated items, each a figure id (an
// unknown one is find_figure's error, which lists the valid ids) or a glob over the ids that must
// match at least one.
std::vector<const experiments::FigureEntry*> figure_selection(const std::string& text) {
  const std::vector<std::string> items = split_list(
      text, "figure", "comma-separated figure ids or globs (see glintlab figure --list)");
  std::vector<bool> chosen(experiments::registered_figures().size(), false);
  for (const std::string& item : items) {
    if (item.find_first_of("*?[") == std::string::npos) {
      const experiments::FigureEntry& e = experiments::find_figure(item);
      chosen[std::size_t(&e - experiments::registered_figures().data())] = true;
      continue;
    }
    bool matched = false;
    for (std::size_t i = 0; i < chosen.size(); ++i)
      if (fnmatch(item.c_str(), std::string(experiments::registered_figures()[i].id).c_str(), 0) ==
          0)
        chosen[i] = matched = true;
    if (!matched)
      throw InputError(fmt::format(
          "figure: '{}' matches no figure id (valid: comma-separated figure ids or globs, see "
          "glintlab figure --list)",
          item));
  }
  std::vector<const experiments::FigureEntry*> out;
  for (std::size_t i = 0; i < chosen.size(); ++i)
    if (chosen[i]) out.push_back(&experiments::registered_figures()[i]);
  return out;
}

// The checks a figure run makes before it writes anything, in this order: --threads,
// --bench-from, the figures (`select`), --out, --env; fills `ctx` (without its progress).
std::vector<const experiments::FigureEntry*> prepare_figures(
    const FigureRequest& o,
    const std::function<std::vector<const experiments::FigureEntry*>()>& select,
    experiments::FigureContext& ctx) {
  const bool quick = quick_budget(o.budget);
  // 0 = all cores is passed on as 0: the experiments size their own pools.
  const int threads = int(integer_option(o.threads, "--threads", 0, 1024));
  std::error_code ec;
  if (o.bench_from && !std::filesystem::is_directory(*o.bench_from, ec))
    throw InputError(
        fmt::format("--bench-from: '{}' is not a folder (valid: {})", *o.bench_from, kBenchFiles));
  try {
    std::vector<const experiments::FigureEntry*> entries = select();
    check_output_dir(o.out, "--out");
    register_staging_parent(o.out);
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
    return entries;
  } catch (const experiments::FigureError& e) {
    throw InputError(e.what());
  }
}

// Runs one figure into out/<id>/ with a progress bar per stage; returns that folder.
std::filesystem::path run_prepared(const experiments::FigureEntry& entry,
                                   const std::filesystem::path& out,
                                   experiments::FigureContext ctx) {
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
  // The figure's charts, drawn by matplotlib from its chart specs before its folder is swapped in.
  ctx.finish = [&entry](const std::filesystem::path& dir) {
    try {
      draw_figure_charts(dir);
    } catch (const InputError& e) {
      throw InputError(fmt::format("figure {}: {}", entry.id, e.what()));
    }
  };
  try {
    return experiments::run_figure(entry, out, ctx);
  } catch (const experiments::FigureError& e) {
    throw InputError(e.what());
  }
}

// The figures of `selection` that shard s of a run at the budget runs, and the costs they are
// balanced by: `figure IDS --list --shard K/N`, a plan that runs nothing.
std::vector<std::size_t> shard_plan(const std::vector<const experiments::FigureEntry*>& selection,
                                    Shard s, bool quick, std::vector<double>& costs) {
  costs.clear();
  for (const auto* e : selection) costs.push_back(figure_cost_seconds(e->id, quick));
  return cost_balanced_positions(costs, s);
}

void list_shard(const std::string& ids, Shard s, bool quick) {
  std::vector<const experiments::FigureEntry*> selected;
  try {
    selected = figure_selection(ids);
  } catch (const experiments::FigureError& e) {
    throw InputError(e.what());
  }
  std::vector<double> costs;
  const std::vector<std::size_t> mine = shard_plan(selected, s, quick, costs);
  double total = 0, shard_total = 0;
  for (double c : costs) total += c;
  for (std::size_t i : mine) {
    fmt::print("{:<28} {:g} s\n", selected[i]->id, costs[i]);
    shard_total += costs[i];
  }
  fmt::print(
      "shard {}/{}: {} of {} figures, {:g} s of {:g} s of CPU at --budget {} "
      "(cli/figure_costs.cpp)\n",
      s.k, s.n, mine.size(), selected.size(), shard_total, total, quick ? "quick" : "full");
}

// What a shard's manifest records besides the budget: the options that change the figures'
// files, so that shards run with another --env or --bench-from are another run to merge.
std::string figure_run_key(const FigureRequest& r) {
  return fmt::format("{}\n--env {}\n--bench-from {}", r.budget, r.env,
                     r.bench_from ? *r.bench_from : std::string("(none)"));
}

void run(const CLI::App* cmd, const FigureOptions& o) {
  const bool sharded = option_count(cmd, "--shard") > 0;
  if (o.list && sharded) {
    list_shard(o.id.empty() ? "*" : o.id, parse_shard(o.shard, "--shard"),
               quick_budget(resolve_budget(cmd, o.budget)));
    return;
  }
  if (o.list) {
    if (!o.id.empty())
      throw InputError(fmt::format(
          "figure: '{}' given with --list (valid: either --list or a figure id; ids with --list "
          "only with --shard)",
          o.id));
    list_figures();
    return;
  }
  const Shard shard = sharded ? parse_shard(o.shard, "--shard") : Shard{};
  check_figure_id(o.id);
  FigureRequest r;
  r.id = o.id;
  r.out = o.out;
  r.budget = resolve_budget(cmd, o.budget);
  r.threads = o.threads;
  r.env = o.env;
  if (option_count(cmd, "--bench-from") > 0) r.bench_from = o.bench_from;
  experiments::FigureContext ctx;
  const std::vector<const experiments::FigureEntry*> selected = prepare_figures(
      r, [&] { return figure_selection(o.id); }, ctx);
  std::vector<const experiments::FigureEntry*> part = selected;
  ShardManifest manifest;
  if (sharded) {
    // Balanced by each figure's measured cost at this budget (cli/figure_costs.h).
    for (const auto* e : selected) manifest.selection.emplace_back(e->id);
    std::vector<double> costs;
    part.clear();
    for (std::size_t i : shard_plan(selected, shard, ctx.quick, costs)) {
      part.push_back(selected[i]);
      manifest.covered.emplace_back(selected[i]->id);
    }
    manifest.command = "figure";
    manifest.version = glintlab_version_text();
    manifest.budget = r.budget;
    manifest.selection_digest = selection_digest(figure_run_key(r), manifest.selection);
    manifest.shard = shard;
    manifest.threads = ctx.threads;
    manifest.machine = fmt::format("{} hardware thread(s), --threads {}",
                                   std::thread::hardware_concurrency(), ctx.threads);
  }
  for (const auto* e : part)
    fmt::print("{}: wrote {}\n", e->id, run_prepared(*e, r.out, ctx).string());
  if (sharded) {
    std::error_code ec;
    std::filesystem::create_directories(r.out, ec);  // an empty shard ran no figure
    if (ec)
      throw InputError(fmt::format("--out: cannot create directory '{}': {}", r.out, ec.message()));
    io::write_file_atomic(std::filesystem::path(r.out) / "shard.json", to_json(manifest));
  }
}

constexpr const char* kFooter =
    R"(Each experiment writes into DIR/<id>/ (default DIR: out/figures): EXR images (32-bit float
R, G, B plus extra channels; header attributes glintlab_model, glintlab_parameters, glintlab_seed,
glintlab_spp, glintlab_reference_spp, glintlab_version), a tonemapped PNG preview and a CSV of
every number the figure plots; its line charts are drawn from the CSV with matplotlib
(/usr/bin/python3 reports/figure_charts.py, from each NAME.chart.json into NAME.png). Files are written into a staging folder that replaces DIR/<id>
only when the whole experiment succeeded. Output is identical for any --threads. The timing figures
(kneiphof2024-table1, kemppinen2025-table3, kemppinen2025-speed-accuracy) read benchmark JSON only
from --bench-from DIR (DIR/glints.json, DIR/kemppinen.json); without it they say so, and the
Kemppinen ones time their rows in process. Several figures (a list or globs) run one after another,
each into its own folder.)";

}  // namespace

void check_figure_id(const std::string& id) {
  if (id.empty())
    throw InputError("figure: a figure id is required (valid: an id of glintlab figure --list)");
}

std::filesystem::path run_figure_request(const FigureRequest& o) {
  check_figure_id(o.id);
  experiments::FigureContext ctx;
  // One id, as given (no list or glob): the Python module's figure() runs one figure.
  const auto entries = prepare_figures(
      o,
      [&] { return std::vector<const experiments::FigureEntry*>{&experiments::find_figure(o.id)}; },
      ctx);
  return run_prepared(*entries.front(), o.out, ctx);
}

void add_figure_command(CLI::App& app) {
  auto o = std::make_shared<FigureOptions>();
  CLI::App* cmd = add_command(app, "figure", "Run registered paper-figure experiments");
  o->budget.budget = "full";
  add_text_option(cmd, "id", o->id,
                  "figure ids or globs, comma-separated (ids: glintlab figure --list), e.g. "
                  "eto2023-fig4 or 'kemppinen2025-*,podee-*'; run in --list order",
                  "IDS");
  add_bool_flag(cmd, "--list", o->list,
                "list the registered experiments and the figure each reproduces; with --shard "
                "K/N (and ids; none: every figure): the figures that shard would run at "
                "--budget and the cost each is balanced by, running nothing");
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
  add_text_option(cmd, "--shard", o->shard,
                  "K/N: run only the K-th of N shards of the selected figures, balanced by each "
                  "figure's measured cost at the budget (cli/figure_costs.cpp), and write "
                  "shard.json beside the figures' folders; glintlab merge joins the N folders "
                  "into the folders of one run. 1 <= K <= N <= 10000",
                  "K/N");
  set_footer(cmd, kFooter);
  set_callback(cmd, [cmd, o] { run(cmd, *o); });
}

}  // namespace glintlab::cli
