// `glintlab verify`: runs the registered checks of the papers' claims, prints a verdict table and
// writes claims.json, claims.csv and claims.md. Exit 0 when every verdict equals the one recorded
// in the repository and every negative control was rejected; 3 when a check could not run
// (verdict error: an exception, or NaN where a number is required; the other checks still run
// and the files are written), whatever the other verdicts; 1 otherwise; 2 on bad input.
#include <fmt/format.h>
#include <fnmatch.h>
#include <tbb/global_control.h>
#include <tbb/info.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <memory>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "cli/args.h"
#include "cli/claim_costs.h"
#include "cli/commands.h"
#include "cli/input.h"
#include "cli/progress.h"
#include "cli/shard.h"
#include "cli/verify_output.h"
#include "core/io/atomic_file.h"
#include "verify/calibration.h"
#include "verify/check.h"
#include "verify/results.h"
#include "verify/stability/sweep.h"

namespace glintlab::cli {
namespace {

struct VerifyOptions {
  BudgetOption budget;
  std::string out = "out/verify";
  std::string claims = "*";
  std::string threads;
  bool list = false;
  bool json = false;  // with --list: the registry as JSON
  std::string calibrate;  // a check id: run its calibration instead of the suite
  std::string runs = "100";
  std::string level = "0.05";
  std::string shard;  // K/N: run the K-th of N shards of the selection
};

// The papers' claims (and adequacy) form the claim suite; a model's conformance checks
// (model.<name>.<property>, verify/conformance/) run for minutes per model and are selected only
// by a list that names them (an item starting with "model."), never by '*' alone.
std::vector<const verify::Check*> select_checks(const std::string& pattern) {
  const bool conformance = pattern.find("model.") != std::string::npos;
  std::vector<std::string> ids;
  for (const auto& c : verify::registered_checks())
    if (conformance || c.family.empty()) ids.push_back(c.id);
  const std::vector<std::string> chosen =
      select_by_globs(pattern, "--claims", ids, "claim ids (see glintlab verify --list)");
  std::vector<const verify::Check*> out;
  for (const auto& c : verify::registered_checks())
    if (std::find(chosen.begin(), chosen.end(), c.id) != chosen.end()) out.push_back(&c);
  return out;
}

std::string machine_description(int threads) {
  return fmt::format("{} hardware thread(s), {} used", std::thread::hardware_concurrency(),
                     threads);
}

// The check `--calibrate ID` names; it must exist and be statistical.
const verify::Check& calibration_check(const std::string& id) {
  for (const auto& c : verify::registered_checks())
    if (c.id == id) {
      if (!verify::is_statistical(c))
        throw InputError(
            fmt::format("--calibrate: '{}' is a deterministic check (an error bound, no p-value); "
                        "calibrate one "
                        "of the statistical checks (see --list)",
                        id));
      return c;
    }
  throw InputError(fmt::format("--calibrate: '{}' is not a registered claim id (see --list)", id));
}

// `--calibrate ID`: the check's test on a known-correct input over `runs` derived seeds; exit 0
// when the test is valid (calibrated, or conservative: p-values too large, never too small), 1 when
// it is anti-conservative or returned a non-finite p-value.
int run_calibration(const verify::Check& check, std::uint64_t runs, double level,
                    const std::filesystem::path& dir) {
  Progress progress("calibrate " + check.id, long(runs));
  const verify::CalibrationResult r =
      verify::calibrate(check, std::size_t(runs), level, 0.99, [&] { progress.step(""); });
  io::write_file_atomic(dir / fmt::format("calibration-{}.json", check.id), verify::to_json(r));
  fmt::print("{}\n", verify::summary(r));
  return r.valid ? 0 : 1;
}

int run(const CLI::App* cmd, const VerifyOptions& o) {
  const std::string budget_name = resolve_budget(cmd, o.budget);
  const int threads = resolve_threads(o.threads);
  const std::uint64_t runs = integer_option(o.runs, "--runs", 2, 1000000);
  const double level = number_option(o.level, "--level", 0, 1, true, true);
  if (option_count(cmd, "--calibrate") > 0 && o.calibrate.empty())
    throw InputError(
        "--calibrate: '' is not a claim id (valid: a statistical check's id, see --list)");
  const verify::Check* to_calibrate =
      o.calibrate.empty() ? nullptr : &calibration_check(o.calibrate);
  auto selected = select_checks(o.claims);
  const bool sharded = option_count(cmd, "--shard") > 0;
  const Shard shard = sharded ? parse_shard(o.shard, "--shard") : Shard{};
  if (sharded && (o.json || to_calibrate))
    throw InputError(
        "--shard: only for a run of the suite or its plan (--list), not with --json or "
        "--calibrate");
  if (o.json && !o.list)
    throw InputError("--json: only with --list (valid: glintlab verify --list --json)");
  if (o.list && o.json) {
    fmt::print("{}", verify::registry_to_json(selected));
    return 0;
  }
  const bool quick = budget_name != "full";
  if (o.list && sharded) {
    std::vector<std::string> ids;
    for (const auto* c : selected) ids.push_back(c->id);
    print_claim_shard_plan(ids, shard, quick);
    return 0;
  }
  if (o.list) {
    for (const auto* c : selected)
      fmt::print(
          "{:<30} {:<16} {} — {}{}\n", c->id, verify::to_string(c->expected), c->paper, c->source,
          c->expected_full ? fmt::format(" (full budget: {})", verify::to_string(*c->expected_full))
                           : "");
    return 0;
  }
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, std::size_t(threads));
  const verify::Budget budget = quick ? verify::Budget::kQuick : verify::Budget::kFull;

  check_output_dir(o.out, "--out");
  std::error_code ec;
  std::filesystem::create_directories(o.out, ec);
  if (ec)
    throw InputError(fmt::format("--out: cannot create directory '{}': {}", o.out, ec.message()));
  register_staging_parent(o.out);

  if (to_calibrate) return run_calibration(*to_calibrate, runs, level, o.out);

  // A shard runs its part of the selection and records which run it belongs to (shard.json).
  ShardManifest manifest;
  if (sharded) {
    manifest.command = "verify";
    manifest.version = glintlab_version_text();
    manifest.budget = budget_name;
    for (const auto* c : selected) manifest.selection.push_back(c->id);
    manifest.selection_digest = selection_digest(budget_name, manifest.selection);
    manifest.shard = shard;
    manifest.threads = threads;
    manifest.machine = machine_description(threads);
    // Balanced by each claim's recorded seconds at this budget (cli/claim_costs.h).
    std::vector<ClaimCostEstimate> costs;
    std::vector<const verify::Check*> part;
    for (std::size_t i : claim_shard_positions(manifest.selection, shard, quick, costs))
      part.push_back(selected[i]);
    selected = part;
    for (const auto* c : selected) manifest.covered.push_back(c->id);
  }

  std::vector<verify::RunRecord> records;
  {
    // all.stability and each model.<name>.stability sweep the same models: measured once.
    const verify::stability::SweepReuse one_sweep_per_model;
    // Scoped so that its line is ended before the table is printed.
    Progress progress("verify", long(selected.size()));
    for (const auto* c : selected) {
      const auto t0 = std::chrono::steady_clock::now();
      verify::CheckResult r = c->run(budget);
      const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      records.push_back({c, std::move(r), s, budget});
      progress.step(c->id);
    }
  }
  const verify::RunInfo info{budget_name, threads, machine_description(threads)};
  const int rc = write_verify_run(records, info, o.out);
  if (sharded) io::write_file_atomic(std::filesystem::path(o.out) / "shard.json", to_json(manifest));
  return rc;
}

}  // namespace

void add_verify_command(CLI::App& app) {
  auto opts = std::make_shared<VerifyOptions>();
  CLI::App* sub = add_command(
      app, "verify",
      "Run the registered checks of the papers' claims (ids and recorded verdicts: --list, "
      "docs/claims.md; how the suite decides: docs/verification.md). Each reports "
      "what it measured, its p-value or error bound, a verdict (holds, holds-within, "
      "holds-in-regime, fails, inconclusive; a model's conformance also not-claimed) and "
      "whether its negative control (a deliberately wrong input) was rejected; a check that "
      "cannot run (an exception, e.g. from a plug-in's eval, or NaN where a number is required) "
      "reports verdict error with the cause. Writes "
      "<out>/claims.json, claims.csv and claims.md. Exit 0 when every verdict equals the verdict "
      "recorded in the repository, 1 when one differs, 3 when a check reported error (whatever "
      "the others; the other checks still run and the files are written), 2 on bad input.");
  add_text_option(sub, "--claims", opts->claims,
                  "comma-separated globs over claim ids (see --list), e.g. 'eto.*'; the models' "
                  "conformance checks only when an item names them: 'model.*', "
                  "'model.<name>.*'",
                  "LIST");
  add_budget_option(sub, opts->budget, "quick = CI, minutes; full = >= 1e7 samples per chi-square");
  add_text_option(sub, "--out", opts->out, "output folder", "DIR");
  add_threads_option(sub, opts->threads);
  add_bool_flag(sub, "--list", opts->list,
                "list the matching claims with their recorded verdicts and exit");
  add_bool_flag(sub, "--json", opts->json,
                "with --list: print the registry as JSON (id, paper, source, kind, recorded "
                "verdicts per budget, paper_quote, stronger_reading, alternatives, correction)");
  add_text_option(
      sub, "--calibrate", opts->calibrate,
      "a statistical check's id: run its test on a known-correct input over --runs "
      "derived seeds, test the p-values for uniformity (KS) and print the measured "
      "false-positive rate at --level with its 99 % interval; writes "
      "<out>/calibration-ID.json; exit 0 when the test is calibrated or conservative, 1 "
      "when anti-conservative (too many small p-values)",
      "ID");
  add_text_option(sub, "--runs", opts->runs, "calibration runs: an integer in [2, 1000000]", "INT");
  add_text_option(sub, "--level", opts->level,
                  "nominal level for the calibration's false-positive rate: a number in (0, 1)",
                  "NUMBER");
  add_text_option(sub, "--shard", opts->shard,
                  "K/N: run only the K-th of N shards of the selected claims, balanced by each "
                  "claim's recorded seconds at the budget (cli/claim_costs_table.cpp), and write "
                  "shard.json beside the rows; glintlab merge joins the N folders into the files "
                  "of one run; with --list: the claims that shard would run and their costs, "
                  "running nothing. 1 <= K <= N <= 10000",
                  "K/N");
  set_callback(sub, [sub, opts] {
    const int rc = run(sub, *opts);
    if (rc != 0) exit_with_code(rc);
  });
}

}  // namespace glintlab::cli
