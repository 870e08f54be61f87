// `glintlab verify`: runs the registered checks of the papers' claims and writes their verdicts
// (CSV for tools, Markdown for people). Exit 0 when every check ran and every negative control
// was rejected; 1 when a control was not rejected (the check could not have failed).
#include <fmt/format.h>

#include <chrono>
#include <filesystem>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "cli/progress.h"
#include "core/io/atomic_file.h"
#include "verify/check.h"

namespace glintlab::cli {
namespace {

struct VerifyOptions {
  std::string budget = "quick";
  std::string out = "out/verify";
  std::string only;
  bool list = false;
};

struct Row {
  const verify::Check* check;
  verify::CheckResult result;
  double seconds;
};

std::string csv_field(const std::string& s) {
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

std::string md_cell(const std::string& s) {
  std::string r;
  for (char c : s) r += c == '|' ? std::string("\\|") : std::string(1, c);
  return r;
}

void write_results(const std::filesystem::path& dir, const std::vector<Row>& rows,
                   const std::string& budget) {
  std::string csv =
      "id,paper,source,verdict,statistic,value,bound,configurations,control_rejected,control,"
      "evidence,seconds\n";
  std::string md = fmt::format("# glintlab verify — budget {}\n\n", budget);
  md += "| claim | paper | source | verdict | measured | bound | control | evidence | time |\n";
  md += "| --- | --- | --- | --- | --- | --- | --- | --- | --- |\n";
  for (const Row& r : rows) {
    const auto& c = *r.check;
    const auto& x = r.result;
    csv += fmt::format("{},{},{},{},{},{:.17g},{:.17g},{},{},{},{},{:.3f}\n", c.id, csv_field(c.paper),
                       csv_field(c.source), csv_field(verify::to_string(x.verdict)),
                       csv_field(x.statistic), x.value, x.bound, x.configurations,
                       x.control_rejected ? 1 : 0, csv_field(x.control), csv_field(x.evidence),
                       r.seconds);
    md += fmt::format("| {} | {} | {} | **{}** | {} = {:.3g} | {:.3g} | {} | {} | {:.1f} s |\n", c.id,
                      md_cell(c.paper), md_cell(c.source), verify::to_string(x.verdict),
                      md_cell(x.statistic), x.value, x.bound, md_cell(x.control),
                      md_cell(x.evidence), r.seconds);
  }
  std::filesystem::create_directories(dir);
  io::write_file_atomic(dir / "verdicts.csv", csv);
  io::write_file_atomic(dir / "verdicts.md", md);
}

int run(const VerifyOptions& o) {
  if (o.budget != "quick" && o.budget != "full")
    throw InputError(fmt::format("--budget: '{}' is not one of quick|full", o.budget));
  const verify::Budget budget = o.budget == "full" ? verify::Budget::kFull : verify::Budget::kQuick;
  std::vector<const verify::Check*> selected;
  for (const auto& c : verify::registered_checks())
    if (o.only.empty() || c.id.rfind(o.only, 0) == 0) selected.push_back(&c);
  if (selected.empty())
    throw InputError(fmt::format("--only: no registered check id starts with '{}' (see --list)", o.only));
  if (o.list) {
    for (const auto* c : selected) fmt::print("{:<28} {} — {}\n", c->id, c->paper, c->source);
    return 0;
  }
  std::error_code ec;
  std::filesystem::create_directories(o.out, ec);
  if (ec) throw InputError(fmt::format("--out: cannot create directory '{}': {}", o.out, ec.message()));

  std::vector<Row> rows;
  Progress progress("verify", long(selected.size()));
  for (const auto* c : selected) {
    const auto t0 = std::chrono::steady_clock::now();
    verify::CheckResult r = c->run(budget);
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    rows.push_back({c, std::move(r), s});
    progress.step(c->id);
  }
  write_results(o.out, rows, o.budget);

  int broken = 0;
  fmt::print("{:<28} {:<24} {:>11} {:>10}  {}\n", "claim", "verdict", "measured", "bound", "control");
  for (const Row& r : rows) {
    fmt::print("{:<28} {:<24} {:>11.3g} {:>10.3g}  {}\n", r.check->id,
               verify::to_string(r.result.verdict), r.result.value, r.result.bound,
               r.result.control_rejected ? "rejected" : "NOT REJECTED");
    broken += r.result.control_rejected ? 0 : 1;
  }
  fmt::print("{} checks, budget {}; verdicts in {}/verdicts.md and verdicts.csv\n", rows.size(),
             o.budget, o.out);
  if (broken) {
    fmt::print(stderr, "glintlab: error: {} negative control(s) not rejected: those checks cannot fail\n",
               broken);
    return 1;
  }
  return 0;
}

}  // namespace

void add_verify_command(CLI::App& app) {
  auto opts = std::make_shared<VerifyOptions>();
  CLI::App* sub = app.add_subcommand(
      "verify",
      "Run the registered checks of the papers' claims (ids from shared/CLAIMS.md). Each reports the "
      "statistic it measured, the bound it is held to, a verdict (holds, holds within tolerance, "
      "holds only in regime, fails, inconclusive), and whether its negative control (a "
      "deliberately wrong input) was rejected. Writes <out>/verdicts.csv and <out>/verdicts.md.");
  sub->add_option("--budget", opts->budget, "quick (CI, minutes) or full (denser grids)")
      ->capture_default_str();
  sub->add_option("--out", opts->out, "output directory")->capture_default_str();
  sub->add_option("--only", opts->only, "run only the checks whose id starts with this prefix");
  sub->add_flag("--list", opts->list, "list the registered checks and exit");
  sub->callback([opts] {
    const int rc = run(*opts);
    if (rc != 0) throw CLI::RuntimeError(rc);
  });
}

}  // namespace glintlab::cli
