// `glintlab compare --models A,B[,…] [--budget quick|full] [--out DIR] [--threads N]
// [--claims-from DIR] [--sweeps-from DIR] [--shard K/N]`: the models side by side
// (experiments/compare/), drawn as one page by reports/compare_page.py; with --shard, the models
// of shard K of N balanced by their recorded costs (compare_model_costs), joined by `glintlab
// merge` (merge_compare_shards); with --list, the models a run (or its shard) would compare.
#include "experiments/compare/compare.h"

#include <fmt/format.h>
#include <tbb/global_control.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
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
#include "cli/claim_costs.h"
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
#include "verify/conformance/conformance.h"

namespace glintlab::cli {
namespace {

namespace fs = std::filesystem;

struct CompareCliOptions {
  std::string out = "out/compare";
  BudgetOption budget;
  std::string models = "*";
  std::string threads;
  std::string claims_from, sweeps_from;
  std::string shard;  // K/N: run the K-th of N shards of the selected models
  bool verbose = false;  // print where the time went (print_step_timings)
  bool list = false;     // print the models (of the shard) and their weights; run nothing
};

// The files of the page, in the order they are moved into DIR (index.html last).
constexpr const char* kPageFiles[] = {"compare.json", "compare.csv", "equal_time.csv",
                                      "equal_time.png", "index.html"};

void check_input_folder(const std::string& dir, const char* option, const char* index,
                        const char* made_by) {
  if (!dir.empty() && !fs::is_regular_file(fs::path(dir) / index))
    throw InputError(
        fmt::format("{}: '{}' holds no {} (a {} folder is expected)", option, dir, index, made_by));
}

// Removes the staging folder of a failed run.
struct StagingFolder {
  fs::path dir;
  ~StagingFolder() {
    std::error_code ec;
    fs::remove_all(dir, ec);
  }
};

void draw_page(const fs::path& stage) {
  const fs::path script = reports_dir() / "compare_page.py";
  if (!fs::is_regular_file(script))
    throw std::runtime_error(
        fmt::format("compare: {} not found (set GLINTLAB_REPORTS_DIR to the reports/ folder)",
                    script.string()));
  const fs::path log = stage / "compare_page.log", err = stage / "compare_page.stderr";
  const int rc =
      run_process({"/usr/bin/python3", script.string(), "--dir", stage.string()}, log, err);
  if (rc != 0)
    throw std::runtime_error(
        fmt::format("compare: compare_page.py failed (exit {}): {}", rc, last_error_line(err)));
  fs::remove(log);
  fs::remove(err);
}

// Moves the page's files from the staging folder into `out`.
void move_page(const fs::path& stage, const fs::path& out) {
  fs::create_directories(out);
  for (const char* f : kPageFiles) fs::rename(stage / f, out / f);
}

// The staging folder beside `out` (so a failed run leaves no `out` behind), registered for the
// signal cleanup.
fs::path staging_beside(const fs::path& out) {
  const fs::path absolute = fs::absolute(out).lexically_normal();
  const fs::path parent =
      absolute.has_filename() ? absolute.parent_path() : absolute.parent_path().parent_path();
  fs::create_directories(parent);
  register_staging_parent(parent);
  return parent / fmt::format(".compare.tmp.{}", ::getpid());
}

// What a shard's manifest records besides the budget: the options that change the files, so that
// shards run with other --claims-from or --sweeps-from folders are another run to merge.
std::string compare_run_key(const CompareRequest& r, const std::string& budget) {
  return fmt::format("{}\n--claims-from {}\n--sweeps-from {}", budget, r.claims_from,
                     r.sweeps_from);
}

// Where a run's time went, on stderr: every step (its start, wall seconds, the worker that ran a
// job of the parallel phase, the CPU seconds of a timed step), the parallel phase's wall and CPU
// time and how long it ran on fewer than all workers at its end (the tail: the last long jobs),
// the timed phase per model, the page.
void print_step_timings(const experiments::compare::CompareFiles& f, int threads,
                        double total_seconds, double page_seconds) {
  double jobs = 0, jobs_cpu = 0;
  std::map<int, double> worker_end;  // per worker, when its last job ended
  for (const auto& s : f.steps)
    if (s.phase == "parallel") {
      jobs += s.seconds;
      jobs_cpu += s.cpu_seconds;
      worker_end[s.thread] = std::max(worker_end[s.thread], s.start + s.seconds);
    }
  double all_busy_until = int(worker_end.size()) < threads ? 0 : f.parallel_seconds;
  for (const auto& [w, end] : worker_end) all_busy_until = std::min(all_busy_until, end);
  fmt::print(stderr, "compare: where the time went (wall seconds from the start; --threads {})\n",
             threads);
  fmt::print(stderr, "{:>8} {:>8} {:>8} {:>6}  {:<20} {}\n", "start", "seconds", "cpu", "thread",
             "model", "step");
  std::vector<std::string> timed_models;
  std::map<std::string, std::string> timed_parts;  // model -> "step s (cpu s), ..."
  std::map<std::string, double> timed_wall, timed_cpu;
  for (const auto& s : f.steps) {
    const bool timed = s.phase == "timed";
    fmt::print(stderr, "{:8.1f} {:8.2f} {:>8} {:>6}  {:<20} {}{}\n", s.start, s.seconds,
               fmt::format("{:.2f}", s.cpu_seconds),
               timed ? std::string("-") : std::to_string(s.thread), s.model,
               timed ? "timed: " : "", s.what);
    if (!timed) continue;
    if (!timed_wall.count(s.model)) timed_models.push_back(s.model);
    std::string& parts = timed_parts[s.model];
    parts += fmt::format("{}{} {:.1f} s", parts.empty() ? "" : ", ", s.what, s.seconds);
    timed_wall[s.model] += s.seconds;
    timed_cpu[s.model] += s.cpu_seconds;
  }
  fmt::print(stderr,
             "parallel phase: {:.1f} s wall, {:.1f} s CPU ({:.2f} threads busy on average), "
             "{:.1f} s in its jobs ({:.1f} s CPU on their workers); every worker busy until "
             "{:.1f} s, then {:.1f} s on fewer (the tail)\n",
             f.parallel_seconds, f.parallel_cpu_seconds,
             f.parallel_seconds > 0 ? f.parallel_cpu_seconds / f.parallel_seconds : 0.0, jobs,
             jobs_cpu,
             all_busy_until, f.parallel_seconds - all_busy_until);
  for (const std::string& m : timed_models)
    fmt::print(stderr, "timed phase, {}: {:.1f} s wall, {:.1f} s CPU ({})\n", m, timed_wall[m],
               timed_cpu[m], timed_parts[m]);
  fmt::print(stderr, "timed phase: {:.1f} s wall, {:.1f} s CPU; page: {:.1f} s; total: {:.1f} s\n",
             f.timed_seconds, f.timed_cpu_seconds, page_seconds, total_seconds);
}

// run_compare_request, or with `shard` its K-th of N parts (the selected models balanced by
// compare_model_costs), and the shard's manifest beside the page. An empty shard writes its
// manifest alone.
// The weights `glintlab compare --shard K/N` balances its shards by (cli/shard_plan.h), one per
// model of `models`: 1, plus, where the run measures the models' conformance checks itself (no
// --claims-from), the costs of the model's checks (model.<name>.*) at the budget as recorded
// (cli/claim_costs.h: a check without a row, a plug-in's, costs the mean of the recorded ones),
// whose stability check's sweep the run reuses for the failure regions; else, where it sweeps the
// model itself (no --sweeps-from), half the sweep's measured CPU seconds on one thread
// (cli/sweep_costs.h): about its wall seconds on two, the threads the recorded checks ran on. The
// reference albedos and the timed phase have no recorded time and weigh the same for every model,
// so a run that reads both the verdicts and the sweeps splits every N-th model.
std::vector<double> compare_model_costs(const std::vector<std::string>& models,
                                        bool conformance_measured, bool sweeps_measured,
                                        bool quick) {
  std::vector<double> costs(models.size(), 1.0);
  if (!conformance_measured) {
    if (sweeps_measured)
      for (std::size_t i = 0; i < models.size(); ++i)
        costs[i] += 0.5 * sweep_cost_seconds(models[i], quick);
    return costs;
  }
  for (const ModelEntry& m : registered_models()) {
    const auto it = std::find(models.begin(), models.end(), m.name);
    if (it == models.end()) continue;
    for (const verify::Check& c : verify::conformance_checks(m))
      costs[std::size_t(it - models.begin())] += claim_cost(c.id, quick).seconds;
  }
  return costs;
}

std::vector<std::string> selected_models(const std::string& globs) {
  std::vector<std::string> names;
  for (const ModelEntry& m : registered_models()) names.emplace_back(m.name);
  return select_by_globs(globs, "--models", names,
                         fmt::format("model names: {}", fmt::join(names, ", ")));
}

// `compare --list [--shard K/N]`: the models the run (or its shard) would compare, each with its
// weight in the shard plan, and their share of the selection's weight. Runs nothing.
void print_compare_plan(const CompareRequest& o, const Shard* shard) {
  const bool quick = quick_budget(o.budget);
  const std::vector<std::string> models = selected_models(o.models);
  const std::vector<double> costs =
      compare_model_costs(models, o.claims_from.empty(), o.sweeps_from.empty(), quick);
  const Shard all{1, 1};
  double total = 0, mine = 0;
  for (double c : costs) total += c;
  const std::vector<std::size_t> positions = cost_balanced_positions(costs, shard ? *shard : all);
  for (std::size_t i : positions) {
    fmt::print("{:<24} {:.1f}\n", models[i], costs[i]);
    mine += costs[i];
  }
  const std::string budget = quick ? "quick" : "full";
  fmt::print("{}{} of {} models, weight {:.1f} of {:.1f}: 1 per model{}\n",
             shard ? fmt::format("shard {}/{}: ", shard->k, shard->n) : std::string(),
             positions.size(), models.size(), mine, total,
             o.claims_from.empty()
                 ? fmt::format(" plus the recorded seconds of its conformance checks at --budget {} "
                               "(cli/claim_costs_table.cpp)",
                               budget)
             : o.sweeps_from.empty()
                 ? fmt::format(" plus half its sweep's measured CPU seconds at --budget {} "
                               "(cli/sweep_costs.cpp); the conformance verdicts read from "
                               "--claims-from",
                               budget)
                 : std::string(", the conformance verdicts and sweeps read from --claims-from and "
                               "--sweeps-from"));
}

CompareSummary run_compare(const CompareRequest& o, const Shard* shard, bool verbose = false) {
  const auto run_start = std::chrono::steady_clock::now();
  experiments::compare::CompareOptions c;
  c.budget = quick_budget(o.budget) ? verify::Budget::kQuick : verify::Budget::kFull;
  c.models = selected_models(o.models);
  const int threads = resolve_threads(o.threads);
  check_input_folder(o.claims_from, "--claims-from", "claims.json", "glintlab verify --out");
  check_input_folder(o.sweeps_from, "--sweeps-from", "stability.json", "glintlab sweep --out");
  c.claims_from = o.claims_from;
  c.sweeps_from = o.sweeps_from;
  // The measurements start with the costliest conformance checks, as recorded.
  const bool quick = c.budget == verify::Budget::kQuick;
  c.check_cost = [quick](const std::string& id) { return claim_cost(id, quick).seconds; };
  const fs::path out(o.out);
  check_output_dir(out, "--out");
  ShardManifest manifest;
  if (shard) {
    const std::string budget = c.budget == verify::Budget::kQuick ? "quick" : "full";
    manifest.command = "compare";
    manifest.version = glintlab_version_text();
    manifest.budget = budget;
    manifest.selection = c.models;
    manifest.selection_digest = selection_digest(compare_run_key(o, budget), c.models);
    manifest.shard = *shard;
    manifest.threads = threads;
    manifest.machine =
        fmt::format("{} hardware thread(s), {} used", std::thread::hardware_concurrency(), threads);
    const std::vector<double> costs =
        compare_model_costs(c.models, o.claims_from.empty(), o.sweeps_from.empty(), quick);
    for (std::size_t i : cost_balanced_positions(costs, *shard))
      manifest.covered.push_back(c.models[i]);
    c.models = manifest.covered;
    if (c.models.empty()) {
      fs::create_directories(out);
      io::write_file_atomic(out / "shard.json", to_json(manifest));
      return {0, out};
    }
  }
  const StagingFolder stage{staging_beside(out)};
  fs::remove_all(stage.dir);
  fs::create_directory(stage.dir);

  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, std::size_t(threads));
  Progress bar("compare", long(c.models.size()) * 5);
  c.progress = [&](const std::string& step) { bar.step(step); };
  experiments::compare::CompareFiles files;
  try {
    files = experiments::compare::run_compare(stage.dir, c);
  } catch (const nlohmann::json::exception& e) {
    throw InputError(
        fmt::format("--claims-from/--sweeps-from: a file there is malformed ({})", e.what()));
  }
  const auto page_start = std::chrono::steady_clock::now();
  draw_page(stage.dir);
  if (verbose) {
    const auto end = std::chrono::steady_clock::now();
    print_step_timings(files, threads,
                       std::chrono::duration<double>(end - run_start).count(),
                       std::chrono::duration<double>(end - page_start).count());
  }
  move_page(stage.dir, out);
  if (shard) io::write_file_atomic(out / "shard.json", to_json(manifest));
  return {c.models.size(), out};
}

void run(const CLI::App* cmd, const CompareCliOptions& o) {
  const bool sharded = option_count(cmd, "--shard") > 0;
  const Shard shard = sharded ? parse_shard(o.shard, "--shard") : Shard{};
  CompareRequest r;
  r.out = o.out;
  r.budget = resolve_budget(cmd, o.budget);
  r.models = o.models;
  r.threads = o.threads;
  r.claims_from = o.claims_from;
  r.sweeps_from = o.sweeps_from;
  if (o.list) {
    check_input_folder(o.claims_from, "--claims-from", "claims.json", "glintlab verify --out");
    print_compare_plan(r, sharded ? &shard : nullptr);
    return;
  }
  const CompareSummary s = run_compare(r, sharded ? &shard : nullptr, o.verbose);
  if (s.models == 0)
    fmt::print("compare: shard {}/{} holds no model; wrote {}\n", shard.k, shard.n,
               (s.dir / "shard.json").string());
  else
    fmt::print("compare: {} models; wrote {}\n", s.models, (s.dir / "index.html").string());
}

std::string read_file_text(const fs::path& p) {
  std::ifstream in(p);
  if (!in) throw InputError(fmt::format("merge: cannot read {}", p.string()));
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// A shard's CSV: its header and, per model, its rows (those whose first field is the model's
// name), every row belonging to one of `models`.
struct ShardCsv {
  std::string header;
  std::map<std::string, std::string> rows;  // model -> its lines, each ending in '\n'
};
ShardCsv read_shard_csv(const fs::path& file, const std::vector<std::string>& models) {
  std::istringstream in(read_file_text(file));
  ShardCsv csv;
  std::string line;
  if (!std::getline(in, csv.header))
    throw InputError(
        fmt::format("merge: {} is empty (a compare run's file is expected)", file.string()));
  while (std::getline(in, line)) {
    const std::string model = line.substr(0, line.find(','));
    if (std::find(models.begin(), models.end(), model) == models.end())
      throw InputError(
          fmt::format("merge: {} holds a row of '{}', a model its shard.json does "
                      "not list",
                      file.string(), model));
    csv.rows[model] += line + "\n";
  }
  return csv;
}

constexpr const char* kFooter =
    R"(Every model sees the same scenes: theta_i in {30, 70} deg (quick) or {0, 30, 60, 80} deg
(full), a footprint of side 0.4 in uv at (0.5, 0.5), a 1 deg light cone for area-light models and a
delta light otherwise, the model's default parameters. Per model:
- conformance: the model.<name>.<property> verdicts; with --claims-from DIR the rows of
  DIR/claims.json ("read"), where a row is missing the registry's recorded verdict ("recorded");
  without it, the model's conformance checks run here ("measured"; minutes per glint model,
  every model's checks side by side on --threads, the costliest first; --models '*' at quick:
  about 530 s of CPU, about 4 1/2 minutes on 2 idle cores; --verbose prints where the time went).
- time per evaluation: eval_batch in double precision on the scalar path and on the widest ISA
  (GLINTLAB_ISA if set), best of 3 rounds: a measurement of this machine, ns/eval.
- reference: the albedo (integral of value over the upper hemisphere) by the conformance suite's
  integral, the truth sampler-covers-value uses: cubature about the mirror direction (models
  without a footprint) or Monte Carlo over a fixed mixture about the mirror direction, blocks of
  10^5 (quick) / 2*10^6 (full) draws, up to 4 blocks for 0.4 % relative error (footprint models),
  with its error; flagged as not converged, and not used, above a relative error of 1e-3 / 1e-5
  (cubature) or 0.1 / 0.03 (Monte Carlo standard error).
- equal-time curve: relative RMS error of the model's own sampler's estimate against the reference
  at 1, 4, 16, ... 1024 (quick) / 16384 (full) samples, 8 / 32 repetitions, against wall time,
  beside the reference's own relative error (the curve's floor); and the relative bias at the
  largest count with its standard error.
- stability: each sampler's failure region, from --sweeps-from DIR/stability.json ("read") or swept
  here at the budget ("measured").
Writes DIR/compare.json, compare.csv (one row per model), equal_time.csv, equal_time.png and
index.html; staged and moved into DIR only when complete. Every field but the timings
(scalar_ns_per_eval, best_ns_per_eval, seconds) is identical for any --threads.)";

}  // namespace

CompareSummary run_compare_request(const CompareRequest& o) { return run_compare(o, nullptr); }

void merge_compare_shards(const std::vector<std::string>& dirs,
                          const std::vector<ShardManifest>& manifests, const std::string& out) {
  const ShardManifest& first = manifests.front();
  // Per model, the shard that ran it: its compare.json entry and CSV rows.
  std::map<std::string, nlohmann::ordered_json> entries;
  std::map<std::string, std::string> model_rows, curve_rows;
  nlohmann::ordered_json machine, settings;
  std::string model_header, curve_header, settings_from;
  for (std::size_t i = 0; i < manifests.size(); ++i) {
    const std::vector<std::string>& covered = manifests[i].covered;
    if (covered.empty()) continue;  // an empty shard wrote its manifest alone
    const fs::path dir(dirs[i]);
    nlohmann::ordered_json doc;
    try {
      doc = nlohmann::ordered_json::parse(read_file_text(dir / "compare.json"));
      std::vector<std::string> names;
      for (const auto& m : doc.at("models")) names.push_back(m.at("name").get<std::string>());
      if (names != covered)
        throw InputError(fmt::format("merge: {} does not hold the models its shard.json lists",
                                     (dir / "compare.json").string()));
      if (settings_from.empty()) {
        machine = doc.at("machine");
        settings = doc.at("settings");
        settings_from = dirs[i];
      } else if (doc.at("settings") != settings) {
        throw InputError(
            fmt::format("merge: '{}' belongs to another run than '{}': other "
                        "settings in compare.json",
                        dirs[i], settings_from));
      }
      for (const auto& m : doc.at("models")) entries[m.at("name").get<std::string>()] = m;
    } catch (const nlohmann::json::exception& e) {
      throw InputError(fmt::format("merge: {} is not a compare run's compare.json ({})",
                                   (dir / "compare.json").string(), e.what()));
    }
    const ShardCsv models_csv = read_shard_csv(dir / "compare.csv", covered);
    const ShardCsv curves_csv = read_shard_csv(dir / "equal_time.csv", covered);
    if (model_header.empty()) {
      model_header = models_csv.header;
      curve_header = curves_csv.header;
    }
    for (const std::string& m : covered) {
      if (!models_csv.rows.count(m))
        throw InputError(
            fmt::format("merge: {} lacks the row of '{}'", (dir / "compare.csv").string(), m));
      model_rows[m] = models_csv.rows.at(m);
      curve_rows[m] = curves_csv.rows.count(m) ? curves_csv.rows.at(m) : std::string();
    }
  }
  // One run's files: the models in the run's order (every one is covered: cli/merge.cpp).
  nlohmann::ordered_json models = nlohmann::ordered_json::array();
  std::string model_csv = model_header + "\n", curve_csv = curve_header + "\n";
  for (const std::string& m : first.selection) {
    if (!entries.count(m)) throw InputError(fmt::format("merge: no shard holds the model '{}'", m));
    models.push_back(entries.at(m));
    model_csv += model_rows.at(m);
    curve_csv += curve_rows.at(m);
  }
  nlohmann::ordered_json doc;
  doc["machine"] = machine;
  doc["settings"] = settings;
  doc["models"] = models;
  const fs::path target(out);
  const StagingFolder stage{staging_beside(target)};
  fs::remove_all(stage.dir);
  fs::create_directory(stage.dir);
  io::write_file_atomic(stage.dir / "compare.json", doc.dump(1) + "\n");
  io::write_file_atomic(stage.dir / "compare.csv", model_csv);
  io::write_file_atomic(stage.dir / "equal_time.csv", curve_csv);
  draw_page(stage.dir);
  move_page(stage.dir, target);
  fmt::print("compare: {} models; wrote {}\n", models.size(), (target / "index.html").string());
}

void add_compare_command(CLI::App& app) {
  auto o = std::make_shared<CompareCliOptions>();
  CLI::App* cmd =
      add_command(app, "compare",
                  "Registered models side by side: conformance, time per eval, error against "
                  "each model's reference, equal-time curves, stability");
  add_text_option(cmd, "--out", o->out, "output folder", "DIR");
  add_budget_option(cmd, o->budget,
                    "quick = 2 scenes and up to 1024 samples (seconds per model), full = 4 scenes "
                    "and up to 16384");
  add_text_option(cmd, "--models", o->models,
                  "comma-separated globs over model names (see glintlab models)", "LIST");
  add_threads_option(cmd, o->threads);
  add_bool_flag(cmd, "--verbose", o->verbose,
                "print where the time went on stderr: each measurement of the parallel phase "
                "(worker, start, seconds), the phase's tail, the timed phase per model, the page");
  add_bool_flag(cmd, "--list", o->list,
                "print the models the run (with --shard: the shard) would compare, each with its "
                "weight in the shard plan; run nothing, write nothing");
  add_text_option(cmd, "--claims-from", o->claims_from,
                  "a glintlab verify --out folder whose claims.json gives the conformance verdicts",
                  "DIR");
  add_text_option(cmd, "--sweeps-from", o->sweeps_from,
                  "a glintlab sweep --out folder whose stability.json gives the failure regions",
                  "DIR");
  add_text_option(cmd, "--shard", o->shard,
                  "K/N: run only the K-th of N shards of the selected models (balanced by the "
                  "recorded seconds of each model's conformance checks where this run measures "
                  "them, else by its sweep's measured cost where it sweeps, else every N-th "
                  "model; --list prints the split) and write shard.json "
                  "beside the page; glintlab merge joins the N folders into the page of one run. "
                  "1 <= K <= N <= 10000",
                  "K/N");
  set_footer(cmd, kFooter);
  set_callback(cmd, [cmd, o] { run(cmd, *o); });
}

}  // namespace glintlab::cli
