// `glintlab sweep [--out DIR] [--budget quick|full] [--models GLOBS] [--threads N] [--shard K/N]`:
// the stability maps of every registered model × sampler (claim all.stability;
// experiments/sweeps/); with --shard, every N-th model from the K-th, joined by `glintlab merge`
// (merge_sweep_shards).
#include <fmt/format.h>
#include <tbb/global_control.h>
#include <tbb/info.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "cli/child_process.h"
#include "cli/commands.h"
#include "cli/input.h"
#include "cli/progress.h"
#include "cli/shard.h"
#include "cli/shard_merge.h"
#include "cli/shard_plan.h"
#include "cli/suite_runs.h"
#include "cli/sweep_costs.h"
#include "core/io/atomic_file.h"
#include "core/model_registry.h"
#include "experiments/sweeps/stability_run.h"

namespace glintlab::cli {
namespace {

struct SweepOptions {
  std::string out = "out/sweeps";
  BudgetOption budget;
  std::string models = "*";
  std::string threads;
  std::string shard;  // K/N: run the K-th of N shards of the selected models
  bool list = false;  // print the models (of the shard) and their costs; run nothing
};

namespace fs = std::filesystem;

experiments::SweepRunSummary run_sweep(const SweepRequest& o, const Shard* shard);

std::vector<std::string> selected_models(const std::string& globs) {
  std::vector<std::string> names;
  for (const ModelEntry& m : registered_models()) names.emplace_back(m.name);
  return select_by_globs(globs, "--models", names,
                         fmt::format("model names: {}", fmt::join(names, ", ")));
}

std::vector<double> sweep_model_costs(const std::vector<std::string>& models, bool quick) {
  std::vector<double> costs;
  for (const std::string& m : models) costs.push_back(sweep_cost_seconds(m, quick));
  return costs;
}

// `sweep --list [--shard K/N]`: the models the run (or its shard) would sweep, each with its
// measured cost, and their share of the selection's. Runs nothing.
void print_sweep_plan(const SweepRequest& o, const Shard* shard) {
  const bool quick = quick_budget(o.budget);
  const std::vector<std::string> models = selected_models(o.models);
  const std::vector<double> costs = sweep_model_costs(models, quick);
  double total = 0, mine = 0;
  for (double c : costs) total += c;
  const std::vector<std::size_t> positions = cost_balanced_positions(costs, shard ? *shard : Shard{});
  for (std::size_t i : positions) {
    fmt::print("{:<24} {:g} s\n", models[i], costs[i]);
    mine += costs[i];
  }
  fmt::print("{}{} of {} models, {:g} s of {:g} s measured at --budget {} (cli/sweep_costs.cpp)\n",
             shard ? fmt::format("shard {}/{}: ", shard->k, shard->n) : std::string(),
             positions.size(), models.size(), mine, total, quick ? "quick" : "full");
}

void run(const CLI::App* cmd, const SweepOptions& o) {
  const bool sharded = option_count(cmd, "--shard") > 0;
  const Shard shard = sharded ? parse_shard(o.shard, "--shard") : Shard{};
  SweepRequest r;
  r.out = o.out;
  r.budget = resolve_budget(cmd, o.budget);
  r.models = o.models;
  r.threads = o.threads;
  if (o.list) {
    print_sweep_plan(r, sharded ? &shard : nullptr);
    return;
  }
  const auto s = run_sweep(r, sharded ? &shard : nullptr);
  if (s.targets == 0) {
    fmt::print("sweep: shard {}/{} holds no model; wrote {}\n", shard.k, shard.n,
               (fs::path(r.out) / "shard.json").string());
    return;
  }
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
pixel per cell; row 0 = the smallest row value) and .png (a heat map drawn by matplotlib from
<plane>_maps.csv and <plane>_<quantity>.chart.json; every target's maps in one run of
reports/figure_charts.py, about 0.1 s a map), and DIR/stability.json: machine, budget, and per
target its maps and its failure region in words. Files are staged and moved into DIR only when
every target finished and its maps are drawn. Output is identical for any --threads.)";

}  // namespace

namespace {

// run_sweep_request, or with `shard` its K-th of N parts: the selected models (each with all its
// samplers) balanced by their measured costs (cli/sweep_costs.h), and the shard's manifest beside
// the maps. An empty shard writes its manifest alone.
experiments::SweepRunSummary run_sweep(const SweepRequest& o, const Shard* shard) {
  const bool quick = quick_budget(o.budget);
  // Every glob must name a model; the sweep gets the trimmed list.
  const std::vector<std::string> selected = selected_models(o.models);
  const std::vector<std::string> globs = split_list(o.models, "--models", "");
  const int threads = resolve_threads(o.threads);
  check_output_dir(o.out, "--out");
  register_staging_parent(o.out);
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, std::size_t(threads));
  experiments::SweepRunOptions r;
  r.budget = quick ? verify::Budget::kQuick : verify::Budget::kFull;
  r.models = fmt::format("{}", fmt::join(globs, ","));
  ShardManifest manifest;
  if (shard) {
    manifest.command = "sweep";
    manifest.version = glintlab_version_text();
    manifest.budget = quick ? "quick" : "full";
    manifest.selection = selected;
    manifest.selection_digest = selection_digest(manifest.budget, selected);
    manifest.shard = *shard;
    manifest.threads = threads;
    manifest.machine =
        fmt::format("{} hardware thread(s), {} used", std::thread::hardware_concurrency(), threads);
    for (std::size_t i : cost_balanced_positions(sweep_model_costs(selected, quick), *shard))
      manifest.covered.push_back(selected[i]);
    if (manifest.covered.empty()) {
      fs::create_directories(o.out);
      io::write_file_atomic(fs::path(o.out) / "shard.json", to_json(manifest));
      return {0, fs::path(o.out) / "stability.json"};
    }
    // Model names hold no glob characters: each selects itself.
    r.models = fmt::format("{}", fmt::join(manifest.covered, ","));
  }
  std::unique_ptr<Progress> bar;
  std::string current;
  r.progress = [&](const std::string& target, long, long total) {
    if (target != current) {
      bar = std::make_unique<Progress>("sweep " + target, total);
      current = target;
    }
    bar->step("planes");
  };
  // Every target's maps, drawn by matplotlib from their chart specs in one run of the script,
  // before the files are moved in; a failing spec is named by its <model>/<sampler>/ path.
  r.finish = [](const fs::path& staging, const std::vector<fs::path>& dirs) {
    try {
      draw_folders_charts(dirs, staging);
    } catch (const InputError& e) {
      throw InputError(fmt::format("sweep: {}", e.what()));
    }
  };
  try {
    experiments::SweepRunSummary summary = experiments::run_sweeps(o.out, r);
    if (shard) io::write_file_atomic(fs::path(o.out) / "shard.json", to_json(manifest));
    return summary;
  } catch (const experiments::SweepError& e) {
    throw InputError(e.what());
  }
}

std::string read_file_text(const fs::path& p) {
  std::ifstream in(p);
  if (!in) throw InputError(fmt::format("merge: cannot read {}", p.string()));
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace

experiments::SweepRunSummary run_sweep_request(const SweepRequest& o) {
  return run_sweep(o, nullptr);
}

void merge_sweep_shards(const std::vector<std::string>& dirs,
                        const std::vector<ShardManifest>& manifests, const std::string& out) {
  using json = nlohmann::ordered_json;
  const ShardManifest& first = manifests.front();
  std::map<std::string, json> entries;      // model -> its targets' entries, in sampler order
  std::map<std::string, std::size_t> from;  // model -> index in dirs
  json machine;
  bool have_machine = false;
  for (std::size_t i = 0; i < manifests.size(); ++i) {
    const std::vector<std::string>& covered = manifests[i].covered;
    if (covered.empty()) continue;  // an empty shard wrote its manifest alone
    const fs::path file = fs::path(dirs[i]) / "stability.json";
    try {
      const json doc = json::parse(read_file_text(file));
      if (!have_machine) {
        machine = doc.at("machine");
        have_machine = true;
      }
      std::vector<std::string> models;
      for (const json& t : doc.at("models")) {
        const std::string m = t.at("model").get<std::string>();
        if (models.empty() || models.back() != m) models.push_back(m);
        entries[m].push_back(t);
      }
      if (models != covered)
        throw InputError(
            fmt::format("merge: {} does not hold the models its shard.json lists", file.string()));
    } catch (const json::exception& e) {
      throw InputError(
          fmt::format("merge: {} is not a sweep's stability.json ({})", file.string(), e.what()));
    }
    for (const std::string& m : covered) {
      std::error_code ec;
      if (!fs::is_directory(fs::path(dirs[i]) / m, ec))
        throw InputError(
            fmt::format("merge: '{}' lacks the folder of '{}', which its shard.json "
                        "lists",
                        dirs[i], m));
      from[m] = i;
    }
  }
  // One run's files: the models' folders and stability.json with their targets in the run's
  // order (every model is covered: cli/merge.cpp).
  json doc;
  doc["machine"] = machine;
  doc["budget"] = first.budget;
  doc["models"] = json::array();
  for (const std::string& m : first.selection) {
    if (!entries.count(m)) throw InputError(fmt::format("merge: no shard holds the model '{}'", m));
    for (const json& t : entries.at(m)) doc["models"].push_back(t);
  }
  std::error_code ec;
  fs::create_directories(out, ec);
  if (ec)
    throw InputError(fmt::format("--out: cannot create directory '{}': {}", out, ec.message()));
  register_staging_parent(out);
  // Staged inside `out` as the sweep stages, then moved into place: the model folders, then the
  // index.
  const fs::path staging = fs::path(out) / fmt::format(".stability.tmp.{}", ::getpid());
  struct Cleanup {
    fs::path dir;
    ~Cleanup() {
      std::error_code e;
      fs::remove_all(dir, e);
    }
  } cleanup{staging};
  fs::remove_all(staging, ec);
  fs::create_directory(staging, ec);
  for (const std::string& m : first.selection)
    if (!ec) fs::copy(fs::path(dirs[from.at(m)]) / m, staging / m, fs::copy_options::recursive, ec);
  if (ec) throw InputError(fmt::format("--out: cannot write into '{}': {}", out, ec.message()));
  io::write_file_atomic(staging / "stability.json", doc.dump(2) + "\n");
  std::vector<std::string> top = first.selection;
  top.push_back("stability.json");
  for (const std::string& name : top) {
    fs::remove_all(fs::path(out) / name, ec);
    fs::rename(staging / name, fs::path(out) / name, ec);
    if (ec)
      throw InputError(fmt::format("--out: cannot move results into '{}' ({})",
                                   (fs::path(out) / name).string(), ec.message()));
  }
  fmt::print("sweep: {} model×sampler targets; wrote {}\n", doc["models"].size(),
             (fs::path(out) / "stability.json").string());
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
  add_bool_flag(cmd, "--list", o->list,
                "print the models the run (with --shard: the shard) would sweep, each with its "
                "measured cost; run nothing, write nothing");
  add_text_option(cmd, "--shard", o->shard,
                  "K/N: run only the K-th of N shards of the selected models (each with all its "
                  "samplers), balanced by each model's measured cost at the budget "
                  "(cli/sweep_costs.cpp; --list prints the split), and write shard.json beside the "
                  "maps; glintlab merge joins the N folders into the files of one run. "
                  "1 <= K <= N <= 10000",
                  "K/N");
  set_footer(cmd, kFooter);
  set_callback(cmd, [cmd, o] { run(cmd, *o); });
}

}  // namespace glintlab::cli
