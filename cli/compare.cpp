// `glintlab compare --models A,B[,…] [--budget quick|full] [--out DIR] [--threads N]
// [--claims-from DIR] [--sweeps-from DIR]`: the models side by side (experiments/compare/), drawn
// as one page by reports/compare_page.py.
#include "experiments/compare/compare.h"

#include <fmt/format.h>
#include <tbb/global_control.h>
#include <unistd.h>

#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli/child_process.h"
#include "cli/commands.h"
#include "cli/input.h"
#include "cli/progress.h"
#include "cli/suite_runs.h"
#include "core/model_registry.h"

namespace glintlab::cli {
namespace {

namespace fs = std::filesystem;

struct CompareCliOptions {
  std::string out = "out/compare";
  BudgetOption budget;
  std::string models = "*";
  std::string threads;
  std::string claims_from, sweeps_from;
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

void run(const CLI::App* cmd, const CompareCliOptions& o) {
  CompareRequest r;
  r.out = o.out;
  r.budget = resolve_budget(cmd, o.budget);
  r.models = o.models;
  r.threads = o.threads;
  r.claims_from = o.claims_from;
  r.sweeps_from = o.sweeps_from;
  const CompareSummary s = run_compare_request(r);
  fmt::print("compare: {} models; wrote {}\n", s.models, (s.dir / "index.html").string());
}

constexpr const char* kFooter =
    R"(Every model sees the same scenes: theta_i in {30, 70} deg (quick) or {0, 30, 60, 80} deg
(full), a footprint of side 0.4 in uv at (0.5, 0.5), a 1 deg light cone for area-light models and a
delta light otherwise, the model's default parameters. Per model:
- conformance: the model.<name>.<property> verdicts; with --claims-from DIR the rows of
  DIR/claims.json ("read"), where a row is missing the registry's recorded verdict ("recorded");
  without it, the model's conformance checks run here ("measured"; minutes per glint model).
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

CompareSummary run_compare_request(const CompareRequest& o) {
  experiments::compare::CompareOptions c;
  c.budget = quick_budget(o.budget) ? verify::Budget::kQuick : verify::Budget::kFull;
  std::vector<std::string> names;
  for (const ModelEntry& m : registered_models()) names.emplace_back(m.name);
  c.models = select_by_globs(o.models, "--models", names,
                             fmt::format("model names: {}", fmt::join(names, ", ")));
  const int threads = resolve_threads(o.threads);
  check_input_folder(o.claims_from, "--claims-from", "claims.json", "glintlab verify --out");
  check_input_folder(o.sweeps_from, "--sweeps-from", "stability.json", "glintlab sweep --out");
  c.claims_from = o.claims_from;
  c.sweeps_from = o.sweeps_from;
  const fs::path out(o.out);
  check_output_dir(out, "--out");
  // Staged beside DIR, so a failed run leaves no DIR behind.
  const fs::path absolute = fs::absolute(out).lexically_normal();
  const fs::path parent =
      absolute.has_filename() ? absolute.parent_path() : absolute.parent_path().parent_path();
  fs::create_directories(parent);
  register_staging_parent(parent);
  const StagingFolder stage{parent / fmt::format(".compare.tmp.{}", ::getpid())};
  fs::remove_all(stage.dir);
  fs::create_directory(stage.dir);

  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, std::size_t(threads));
  Progress bar("compare", long(c.models.size()) * 5);
  c.progress = [&](const std::string& step) { bar.step(step); };
  try {
    experiments::compare::run_compare(stage.dir, c);
  } catch (const nlohmann::json::exception& e) {
    throw InputError(
        fmt::format("--claims-from/--sweeps-from: a file there is malformed ({})", e.what()));
  }
  draw_page(stage.dir);
  fs::create_directories(out);
  for (const char* f : kPageFiles) fs::rename(stage.dir / f, out / f);
  return {c.models.size(), out};
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
  add_text_option(cmd, "--claims-from", o->claims_from,
                  "a glintlab verify --out folder whose claims.json gives the conformance verdicts",
                  "DIR");
  add_text_option(cmd, "--sweeps-from", o->sweeps_from,
                  "a glintlab sweep --out folder whose stability.json gives the failure regions",
                  "DIR");
  set_footer(cmd, kFooter);
  set_callback(cmd, [cmd, o] { run(cmd, *o); });
}

}  // namespace glintlab::cli
