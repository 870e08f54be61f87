// `glintlab verify`: runs the registered checks of the papers' claims, prints a verdict table and
// writes claims.json, claims.csv and claims.md. Exit 0 when every verdict equals the one recorded
// in the repository and every negative control was rejected; 1 otherwise; 2 on bad input.
#include <fnmatch.h>
#include <fmt/format.h>
#include <tbb/global_control.h>
#include <tbb/info.h>

#include <chrono>
#include <filesystem>
#include <memory>
#include <sstream>
#include <thread>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "cli/progress.h"
#include "core/io/atomic_file.h"
#include "verify/calibration.h"
#include "verify/check.h"
#include "verify/results.h"

namespace glintlab::cli {
namespace {

struct VerifyOptions {
  std::string budget = "quick";
  std::string out = "out/verify";
  std::string claims = "*";
  int threads = 0;
  bool list = false;
  std::string calibrate;  // a check id: run its calibration instead of the suite
  int runs = 100;
  double level = 0.05;
};

std::vector<std::string> split_globs(const std::string& s) {
  std::vector<std::string> globs;
  std::stringstream in(s);
  for (std::string g; std::getline(in, g, ',');)
    if (!g.empty()) globs.push_back(g);
  return globs;
}

std::vector<const verify::Check*> select_checks(const std::string& pattern) {
  const auto globs = split_globs(pattern);
  if (globs.empty()) throw InputError("--claims: empty pattern (e.g. 'smooth.*' or 'eto.*,kneiphof.*')");
  std::vector<const verify::Check*> out;
  for (const auto& c : verify::registered_checks())
    for (const auto& g : globs)
      if (fnmatch(g.c_str(), c.id.c_str(), 0) == 0) {
        out.push_back(&c);
        break;
      }
  if (out.empty())
    throw InputError(fmt::format("--claims: '{}' matches no registered claim id (see --list)", pattern));
  return out;
}

std::string machine_description(int threads) {
  return fmt::format("{} hardware thread(s), {} used", std::thread::hardware_concurrency(), threads);
}

// The check `--calibrate ID` names; it must exist and be statistical.
const verify::Check& calibration_check(const std::string& id) {
  for (const auto& c : verify::registered_checks())
    if (c.id == id) {
      if (!verify::is_statistical(c))
        throw InputError(fmt::format(
            "--calibrate: '{}' is a deterministic check (an error bound, no p-value); calibrate one "
            "of the statistical checks (see --list)",
            id));
      return c;
    }
  throw InputError(fmt::format("--calibrate: '{}' is not a registered claim id (see --list)", id));
}

// `--calibrate ID`: the check's test on a known-correct input over `runs` derived seeds; exit 0 when
// the test is valid (calibrated, or conservative: p-values too large, never too small), 1 when it is
// anti-conservative or returned a non-finite p-value.
int run_calibration(const verify::Check& check, const VerifyOptions& o, const std::filesystem::path& dir) {
  Progress progress("calibrate " + check.id, o.runs);
  const verify::CalibrationResult r =
      verify::calibrate(check, std::size_t(o.runs), o.level, 0.99, [&] { progress.step(""); });
  io::write_file_atomic(dir / fmt::format("calibration-{}.json", check.id), verify::to_json(r));
  fmt::print("{}\n", verify::summary(r));
  return r.valid ? 0 : 1;
}

int run(const VerifyOptions& o) {
  if (o.budget != "quick" && o.budget != "full")
    throw InputError(fmt::format("--budget: '{}' is not one of quick|full", o.budget));
  if (o.threads < 0 || o.threads > 1024)
    throw InputError(fmt::format("--threads: {} is out of range (0 = all cores, or 1..1024)", o.threads));
  if (o.runs < 2 || o.runs > 1000000)
    throw InputError(fmt::format("--runs: {} is out of range (2..1000000)", o.runs));
  if (!(o.level > 0 && o.level < 1))
    throw InputError(fmt::format("--level: {} is out of range (0 < level < 1)", o.level));
  const verify::Check* to_calibrate = o.calibrate.empty() ? nullptr : &calibration_check(o.calibrate);
  const auto selected = select_checks(o.claims);
  if (o.list) {
    for (const auto* c : selected)
      fmt::print("{:<30} {:<16} {} — {}{}\n", c->id, verify::to_string(c->expected), c->paper, c->source,
                 c->expected_full ? fmt::format(" (full budget: {})", verify::to_string(*c->expected_full)) : "");
    return 0;
  }
  const int threads = o.threads > 0 ? o.threads : tbb::info::default_concurrency();
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, std::size_t(threads));
  const verify::Budget budget = o.budget == "full" ? verify::Budget::kFull : verify::Budget::kQuick;

  std::error_code ec;
  std::filesystem::create_directories(o.out, ec);
  if (ec) throw InputError(fmt::format("--out: cannot create directory '{}': {}", o.out, ec.message()));

  if (to_calibrate) return run_calibration(*to_calibrate, o, o.out);

  std::vector<verify::RunRecord> records;
  Progress progress("verify", long(selected.size()));
  for (const auto* c : selected) {
    const auto t0 = std::chrono::steady_clock::now();
    verify::CheckResult r = c->run(budget);
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    records.push_back({c, std::move(r), s, budget});
    progress.step(c->id);
  }
  verify::adjust_for_suite(records);
  const verify::RunInfo info{o.budget, threads, machine_description(threads)};
  const std::filesystem::path dir(o.out);
  io::write_file_atomic(dir / "claims.json", verify::to_json(records, info));
  io::write_file_atomic(dir / "claims.csv", verify::to_csv(records));
  io::write_file_atomic(dir / "claims.md", verify::to_markdown(records, info));

  int unexpected = 0;
  fmt::print("{:<30} {:<16} {:>10} {:>10} {:>10}  {}\n", "claim", "verdict", "measured", "p",
             "control p", "control");
  for (const auto& r : records) {
    const auto& x = r.result;
    const bool ok = verify::as_expected(r);
    unexpected += ok ? 0 : 1;
    fmt::print("{:<30} {:<16} {:>10.3g} {:>10} {:>10}  {}{}\n", r.check->id, verify::to_string(x.verdict),
               x.value, x.p_value ? fmt::format("{:.3g}", *x.p_value) : "—",
               x.control_p_value ? fmt::format("{:.3g}", *x.control_p_value) : "—",
               x.control_rejected ? "rejected" : "NOT REJECTED (check is broken)",
               x.verdict == r.check->expected_for(budget)
                   ? ""
                   : fmt::format("  [recorded verdict: {}]", verify::to_string(r.check->expected_for(budget))));
  }
  fmt::print("{} claims, budget {}, {} thread(s); results in {}/claims.{{json,csv,md}}\n", records.size(),
             o.budget, threads, o.out);
  if (unexpected) {
    fmt::print(stderr,
               "glintlab: error: {} claim(s) differ from their recorded verdict or did not reject "
               "their negative control\n",
               unexpected);
    return 1;
  }
  return 0;
}

}  // namespace

void add_verify_command(CLI::App& app) {
  auto opts = std::make_shared<VerifyOptions>();
  CLI::App* sub = app.add_subcommand(
      "verify",
      "Run the registered checks of the papers' claims (ids from shared/CLAIMS.md). Each reports "
      "what it measured, its p-value or error bound, a verdict (holds, holds-within, "
      "holds-in-regime, fails, inconclusive) and whether its negative control (a deliberately "
      "wrong input) was rejected. Writes <out>/claims.json, claims.csv and claims.md. Exit 0 when "
      "every verdict equals the verdict recorded in the repository, 1 when one differs, 2 on bad "
      "input.");
  sub->add_option("--claims", opts->claims, "comma-separated globs over claim ids, e.g. 'eto.*'")
      ->capture_default_str();
  sub->add_option("--budget", opts->budget, "quick (CI: minutes) or full (>= 1e7 samples per chi-square)")
      ->capture_default_str();
  sub->add_option("--out", opts->out, "output directory")->capture_default_str();
  sub->add_option("--threads", opts->threads, "worker threads (0 = all cores); results do not depend on it")
      ->capture_default_str();
  sub->add_flag("--list", opts->list, "list the matching claims with their recorded verdicts and exit");
  sub->add_option("--calibrate", opts->calibrate,
                  "a statistical check's id: run its test on a known-correct input over --runs "
                  "derived seeds, test the p-values for uniformity (KS) and print the measured "
                  "false-positive rate at --level with its 99 % interval; writes "
                  "<out>/calibration-ID.json; exit 0 when the test is calibrated or conservative, 1 "
                  "when anti-conservative (too many small p-values)");
  sub->add_option("--runs", opts->runs, "calibration runs (2..1000000)")->capture_default_str();
  sub->add_option("--level", opts->level, "nominal level for the calibration's false-positive rate")
      ->capture_default_str();
  sub->callback([opts] {
    const int rc = run(*opts);
    if (rc != 0) throw CLI::RuntimeError(rc);
  });
}

}  // namespace glintlab::cli
