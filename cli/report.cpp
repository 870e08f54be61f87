// `glintlab report`: runs (or, with --reuse, reads the cached results of) the claim suite, the
// models' conformance suites,
// benchmarks, every registered figure (the timing ones read those benchmarks) and the stability
// sweeps, then has reports/make_report.py draw the plots and write DIR/index.html and its Markdown
// twin DIR/report.md.
#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <fnmatch.h>
#include <tbb/global_control.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <fstream>
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
#include "core/io/atomic_file.h"
#include "core/model_registry.h"
#include "core/plugin_loader.h"
#include "experiments/compare/compare.h"
#include "experiments/figures/figure_registry.h"
#include "verify/check.h"
#include "verify/claims_schema.h"

namespace glintlab::cli {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

struct ReportOptions {
  std::string out = "out/report";
  BudgetOption budget;
  bool reuse = false;
  std::string claims = "*";
  std::string figures = "*";
  std::string models = "*";  // the models the stability and compare parts cover
  std::string conformance;  // globs over model names: whose conformance suite the report runs
  std::string claims_from;  // a `glintlab verify --out` folder to read instead of running it
  std::string gpu_from;     // a glintlab_gpu_check results folder (docs/gpu.md) to show
  std::string skip;         // comma-separated parts
};

// The parts of a report, in the order they run; each has its own subfolder of DIR. The benchmarks
// run before the figures, which read their JSON (bench/glints.json, bench/kemppinen.json); the
// models' conformance runs before compare, which shows it.
constexpr const char* kParts[] = {"claims", "conformance", "bench", "figures", "stability",
                                  "compare"};
constexpr const char* kPartDirs[] = {"verify", "conformance", "bench", "figures", "stability",
                                     "compare"};
// The file whose presence (and validity, checked by make_report.py) makes a cached part reusable.
constexpr const char* kPartIndex[] = {"claims.json",  "claims.json",    "bench.json",
                                      "figures.json", "stability.json", "compare.json"};
constexpr int kNumParts = 6;
constexpr const char* kPartList = "claims, conformance, bench, figures, stability, compare";

// Models whose conformance suite the report leaves out unless --conformance names them: the two
// Kemppinen models' suites take about 250 s of the about 300 s all nine take at the quick budget
// (row seconds recorded in docs/data/claims-quick.json, 2 cores), which would double the report.
// Their verdicts then show as recorded, in a column of their own.
constexpr const char* kConformanceLeftOutByDefault[] = {"kemppinen_ggx", "kemppinen_beckmann"};

// This glintlab with this process's --plugin options, so that a child run knows the same models
// (GLINTLAB_PLUGINS, the other route, is inherited).
std::vector<std::string> glintlab_command() {
  std::vector<std::string> args = {self_exe().string()};
  for (const std::string& p : plugin_option_paths()) args.insert(args.end(), {"--plugin", p});
  return args;
}

std::string cpu_model() {
  std::ifstream in("/proc/cpuinfo");
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("model name", 0) == 0) {
      const auto colon = line.find(':');
      if (colon != std::string::npos) {
        auto s = line.substr(colon + 1);
        s.erase(0, s.find_first_not_of(' '));
        return s;
      }
    }
  }
  return "unknown CPU";
}

std::string utc_now() {
  const std::time_t t = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%d %H:%M UTC", &tm);
  return buf;
}

json machine_json(int threads) {
  return {{"cpu_model", cpu_model()},
          {"cores", std::thread::hardware_concurrency()},
          {"threads", threads}};
}

// A benchmark tool of experiments/bench/, found beside glintlab in the build tree (cli/ and
// experiments/bench/ are siblings) or in the same folder; empty when it was not built.
fs::path bench_tool(const std::string& name) {
  const fs::path dir = self_exe().parent_path();
  std::error_code ec;
  for (const fs::path& p : {dir.parent_path() / "experiments" / "bench" / name, dir / name}) {
    if (fs::is_regular_file(p, ec) && ::access(p.c_str(), X_OK) == 0) return p;
  }
  return {};
}

std::string read_text(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// The method rows (names starting "method/") of a Google Benchmark JSON, with its context, written
// to `to`: the file the speed-vs-accuracy section reads per binary.
void write_method_rows(const fs::path& from, const fs::path& to) {
  json doc;
  try {
    doc = json::parse(read_text(from));
  } catch (const json::exception& e) {
    throw std::runtime_error(
        fmt::format("report: the benchmark JSON {} does not parse ({})", from.string(), e.what()));
  }
  json rows = json::array();
  if (doc.contains("benchmarks") && doc["benchmarks"].is_array())
    for (const json& b : doc["benchmarks"])
      if (b.value("name", std::string()).rfind("method/", 0) == 0) rows.push_back(b);
  doc["benchmarks"] = rows;
  io::write_file_atomic(to, doc.dump(1) + "\n");
}

// Removes a folder on scope exit unless disarmed: the staging folder of a failed run.
struct RemoveOnExit {
  fs::path dir;
  bool armed = true;
  ~RemoveOnExit() {
    std::error_code ec;
    if (armed && !dir.empty()) fs::remove_all(dir, ec);
  }
};

class ReportRun {
 public:
  ReportRun(const ReportOptions& o, const CLI::App& root, const CLI::App* cmd, std::string threads)
      : o_(o), root_(root), cmd_(cmd), threads_text_(std::move(threads)) {}
  void run();

 private:
  void validate();
  void run_claims(json& part);
  void run_conformance(json& part);
  void run_figures(json& part);
  void run_bench(json& part);
  void run_stability(json& part);
  void run_compare(json& part);
  json gpu_part(const fs::path& cached, const json& previous);
  // Runs a child; stderr goes to the terminal when there is one (its progress), else to a log.
  int child(const std::vector<std::string>& args, const std::string& log_name);
  [[noreturn]] void child_failed(const std::string& what, int rc, const std::string& log_name);
  bool quick() const { return budget_ == "quick"; }

  const ReportOptions& o_;
  const CLI::App& root_;
  const CLI::App* cmd_;
  std::string threads_text_;
  fs::path out_, stage_, logs_;
  bool tty_ = ::isatty(STDERR_FILENO) == 1;
  int threads_ = 0;
  std::string budget_;
  std::vector<std::string> skip_;
  std::vector<const experiments::FigureEntry*> figures_;
  std::vector<std::string> models_;
  std::vector<std::string> conformance_models_;  // within models_
  std::unique_ptr<Progress> progress_;
};

void ReportRun::validate() {
  budget_ = resolve_budget(cmd_, o_.budget);
  threads_ = resolve_threads(threads_text_);
  if (option_count(cmd_, "--skip") > 0) {
    skip_ = split_list(o_.skip, "--skip", fmt::format("comma-separated parts: {}", kPartList));
    for (const std::string& s : skip_) {
      bool known = false;
      for (const char* p : kParts) known = known || s == p;
      if (!known)
        throw InputError(
            fmt::format("--skip: '{}' is not a part of the report (valid: {})", s, kPartList));
    }
  }
  std::vector<std::string> ids;
  for (const auto& c : verify::registered_checks()) ids.push_back(c.id);
  (void)select_by_globs(o_.claims, "--claims", ids, "claim ids (see glintlab verify --list)");
  ids.clear();
  for (const experiments::FigureEntry& e : experiments::registered_figures())
    ids.emplace_back(e.id);
  const std::vector<std::string> chosen =
      select_by_globs(o_.figures, "--figures", ids, "figure ids (see glintlab figure --list)");
  for (const experiments::FigureEntry& e : experiments::registered_figures())
    if (std::find(chosen.begin(), chosen.end(), std::string(e.id)) != chosen.end())
      figures_.push_back(&e);
  std::vector<std::string> names;
  for (const ModelEntry& m : registered_models()) names.emplace_back(m.name);
  models_ = select_by_globs(o_.models, "--models", names,
                            fmt::format("model names: {}", fmt::join(names, ", ")));
  std::vector<std::string> conformance;
  if (option_count(cmd_, "--conformance") > 0) {
    conformance = select_by_globs(o_.conformance, "--conformance", names,
                                  fmt::format("model names: {}", fmt::join(names, ", ")));
  } else {
    for (const std::string& n : names)
      if (std::find(std::begin(kConformanceLeftOutByDefault),
                    std::end(kConformanceLeftOutByDefault), n) == std::end(kConformanceLeftOutByDefault))
        conformance.push_back(n);
  }
  for (const std::string& n : models_)
    if (std::find(conformance.begin(), conformance.end(), n) != conformance.end())
      conformance_models_.push_back(n);
  if (!o_.gpu_from.empty() && !fs::is_regular_file(fs::path(o_.gpu_from) / "results.json"))
    throw InputError(
        fmt::format("--gpu-from: '{}' holds no results.json (valid: a folder written by "
                    "glintlab_gpu_check, scripts/device_check.sh; docs/gpu.md)",
                    o_.gpu_from));
  if (!o_.claims_from.empty() && !fs::is_regular_file(fs::path(o_.claims_from) / "claims.json"))
    throw InputError(
        fmt::format("--claims-from: '{}' holds no claims.json (a glintlab verify --out "
                    "folder is expected)",
                    o_.claims_from));
}

int ReportRun::child(const std::vector<std::string>& args, const std::string& log_name) {
  return run_process(args, logs_ / (log_name + ".txt"),
                     tty_ ? fs::path() : logs_ / (log_name + ".stderr.txt"));
}

void ReportRun::child_failed(const std::string& what, int rc, const std::string& log_name) {
  const fs::path err = logs_ / (log_name + ".stderr.txt");
  throw std::runtime_error(fmt::format("report: {} failed (exit {}){}", what, rc,
                                       tty_ ? "" : ": " + last_error_line(err)));
}

void ReportRun::run_claims(json& part) {
  const auto start = std::chrono::steady_clock::now();
  if (!o_.claims_from.empty()) {
    fs::copy(o_.claims_from, stage_ / "verify", fs::copy_options::recursive);
    part["status"] = "read";
    part["note"] = fmt::format("read from {} (glintlab verify --out)", o_.claims_from);
    return;
  }
  std::vector<std::string> args = glintlab_command();
  args.insert(args.end(), {"verify", "--claims", o_.claims, "--budget", budget_, "--threads",
                           std::to_string(threads_), "--out", (stage_ / "verify").string()});
  const int rc = child(args, "verify");
  // 1 = a verdict differs from the recorded one: a finding the report shows, not a failure.
  if (rc != 0 && rc != 1) child_failed("glintlab verify", rc, "verify");
  part["status"] = "ran";
  part["exit_code"] = rc;
  part["seconds"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The conformance suites of the chosen models at the report's budget, in a verify child of their
// own (so that it runs whether or not the claims part did, or read them with --claims-from).
void ReportRun::run_conformance(json& part) {
  const auto start = std::chrono::steady_clock::now();
  if (conformance_models_.empty()) {
    part["status"] = "skipped";
    part["note"] = "no model chosen by both --models and --conformance";
    return;
  }
  std::vector<std::string> globs;
  for (const std::string& n : conformance_models_) globs.push_back(fmt::format("model.{}.*", n));
  std::vector<std::string> args = glintlab_command();
  args.insert(args.end(), {"verify", "--claims", fmt::format("{}", fmt::join(globs, ",")),
                           "--budget", budget_, "--threads", std::to_string(threads_), "--out",
                           (stage_ / "conformance").string()});
  const int rc = child(args, "conformance");
  // 1: a verdict differs from the recorded one; 3: a check could not run (its row says why, e.g.
  // a plug-in's eval that throws). Both are results the comparison shows.
  if (rc != 0 && rc != 1 && rc != 3) child_failed("glintlab verify (conformance)", rc, "conformance");
  part["status"] = "ran";
  part["exit_code"] = rc;
  part["models"] = conformance_models_;
  std::vector<std::string> left;
  for (const std::string& n : models_)
    if (std::find(conformance_models_.begin(), conformance_models_.end(), n) ==
        conformance_models_.end())
      left.push_back(n);
  if (!left.empty())
    part["note"] = fmt::format("not measured (left out by --conformance): {}", fmt::join(left, ", "));
  part["seconds"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void ReportRun::run_figures(json& part) {
  json list = json::array();
  for (const experiments::FigureEntry* e : figures_) {
    const auto start = std::chrono::steady_clock::now();
    experiments::FigureContext ctx;
    ctx.quick = quick();
    ctx.threads = threads_;
    // This run's benchmarks (ran, or reused with them); none when that part was skipped or could
    // not run, which the timing figures then say.
    if (fs::is_directory(stage_ / "bench")) {
      ctx.bench_dir = stage_ / "bench";
      ctx.bench_name = (out_ / "bench").string();
    }
    ctx.finish = draw_figure_charts;  // its charts, as glintlab figure draws them
    try {
      experiments::run_figure(*e, stage_ / "figures", ctx);
    } catch (const std::exception& ex) {
      throw std::runtime_error(fmt::format("report: figure {} failed: {}", e->id, ex.what()));
    }
    const double s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    list.push_back({{"id", e->id},
                    {"paper", e->paper},
                    {"target", e->target},
                    {"description", e->description},
                    {"quick", quick()},
                    {"seconds", s}});
    progress_->step(std::string(e->id));
  }
  io::write_file_atomic(stage_ / "figures" / "figures.json", list.dump(1) + "\n");
  part["status"] = "ran";
}

void ReportRun::run_bench(json& part) {
  const fs::path bench = bench_tool("glintlab_bench_kernels");
  const fs::path accuracy = bench_tool("glintlab_accuracy");
  if (bench.empty() || accuracy.empty()) {
    part["status"] = "unavailable";
    part["note"] =
        "the benchmark tools glintlab_bench_kernels and glintlab_accuracy were not found beside "
        "glintlab (build the targets of experiments/bench/)";
    return;
  }
  const fs::path dir = stage_ / "bench";
  fs::create_directories(dir);
  // quick: one short repetition per benchmark; full: what scripts/bench.sh runs.
  std::vector<std::string> args = {bench.string(),
                                   "--benchmark_out=" + (dir / "bench.json").string(),
                                   "--benchmark_out_format=json"};
  if (quick()) {
    args.insert(args.end(), {"--benchmark_min_time=0.01", "--benchmark_repetitions=1"});
  } else {
    args.insert(args.end(), {"--benchmark_min_time=0.05", "--benchmark_repetitions=5",
                             "--benchmark_report_aggregates_only=true"});
  }
  int rc = child(args, "bench");
  if (rc != 0) child_failed("glintlab_bench_kernels", rc, "bench");
  progress_->step("benchmarks");
  rc = child({accuracy.string(), "--n", quick() ? "20000" : "200000", "--out",
              (dir / "accuracy.csv").string()},
             "accuracy");
  if (rc != 0) child_failed("glintlab_accuracy", rc, "accuracy");
  // The method rows (experiments/bench/METHOD_BENCHMARKS.md) of every binary that has them, as
  // scripts/speed_accuracy.sh runs them; quick = their small query sets (GLINTLAB_BENCH_QUICK).
  // glints and kemppinen also run the rows the timing figures read (Table 1, Table 3, the cost
  // against footprint) in the same run, into glints.json and kemppinen.json, whose method rows
  // are copied into methods/: one run, one set of numbers for the figures and this section.
  struct MethodTool {
    const char* name;
    const char* figure_json;  // null: method rows only
    const char* figure_rows;  // the figures' rows, a regex alternative
  };
  constexpr MethodTool kTools[] = {
      {"glintlab_bench_glints", "glints.json", "table1/|adequacy/"},
      {"glintlab_bench_chermain", nullptr, nullptr},
      {"glintlab_bench_podee", nullptr, nullptr},
      {"glintlab_bench_kemppinen", "kemppinen.json", "table3/|BM_Kemppinen"}};
  fs::create_directories(dir / "methods");
  if (quick()) ::setenv("GLINTLAB_BENCH_QUICK", "1", 1);
  for (const MethodTool& t : kTools) {
    const fs::path tool = bench_tool(t.name);
    if (tool.empty()) continue;
    const fs::path methods_json = dir / "methods" / (std::string(t.name) + ".json");
    const fs::path out = t.figure_json ? dir / t.figure_json : methods_json;
    std::vector<std::string> margs = {
        tool.string(),
        t.figure_json ? fmt::format("--benchmark_filter=^(method/|{})", t.figure_rows)
                      : std::string("--benchmark_filter=^method/"),
        "--benchmark_out=" + out.string(), "--benchmark_out_format=json"};
    if (quick())
      margs.insert(margs.end(), {"--benchmark_min_time=0.01", "--benchmark_repetitions=1"});
    else
      margs.insert(margs.end(), {"--benchmark_min_time=0.05", "--benchmark_repetitions=3",
                                 "--benchmark_report_aggregates_only=true"});
    rc = child(margs, t.name);
    if (rc != 0) child_failed(t.name, rc, t.name);
    if (t.figure_json) write_method_rows(out, methods_json);
  }
  if (quick()) ::unsetenv("GLINTLAB_BENCH_QUICK");
  part["status"] = "ran";
  part["settings"] = quick() ? "1 repetition of >= 0.01 s per benchmark; 20000 accuracy rows"
                             : "median of 5 repetitions of >= 0.05 s; 200000 accuracy rows";
  part["settings"] = part["settings"].get<std::string>() +
                     (quick() ? "; method rows: quick query sets, 1 repetition"
                              : "; method rows: median of 3 repetitions");
}

void ReportRun::run_stability(json& part) {
  // The sweeps are their own subcommand; a build without it gets a report that says so.
  const auto sweep =
      root_.get_subcommands([](const CLI::App* sub) { return sub->get_name() == "sweep"; });
  if (sweep.empty()) {
    part["status"] = "unavailable";
    part["note"] = "this glintlab has no sweep subcommand (stability sweeps not built in)";
    return;
  }
  std::vector<std::string> args = glintlab_command();
  args.insert(args.end(), {"sweep", "--out", (stage_ / "stability").string()});
  args.insert(args.end(), {"--budget", budget_, "--threads", std::to_string(threads_),
                           "--models", fmt::format("{}", fmt::join(models_, ","))});
  const int rc = child(args, "sweep");
  if (rc != 0) child_failed("glintlab sweep", rc, "sweep");
  part["status"] = "ran";
}

// Every registered model side by side, in this process (plug-ins loaded here are included). It
// reads the conformance verdicts and failure regions the report's conformance, verify and sweep
// parts wrote and never runs a suite itself: a verdict the report did not measure shows as
// recorded.
void ReportRun::run_compare(json& part) {
  const auto start = std::chrono::steady_clock::now();
  experiments::compare::CompareOptions c;
  c.budget = quick() ? verify::Budget::kQuick : verify::Budget::kFull;
  c.models = models_;
  c.measure_missing = false;
  if (fs::is_regular_file(stage_ / "verify" / "claims.json")) c.claims_from = stage_ / "verify";
  if (fs::is_regular_file(stage_ / "conformance" / "claims.json"))
    c.conformance_from = stage_ / "conformance";
  if (fs::is_regular_file(stage_ / "stability" / "stability.json"))
    c.sweeps_from = stage_ / "stability";
  c.claims_shown_as = out_ / "verify";  // the staging folder becomes out_
  c.conformance_shown_as = out_ / "conformance";
  c.sweeps_shown_as = out_ / "stability";
  fs::create_directories(stage_ / "compare");
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, std::size_t(threads_));
  try {
    experiments::compare::run_compare(stage_ / "compare", c);
  } catch (const json::exception& e) {
    throw InputError(
        fmt::format("report: compare cannot read a verify or sweep output ({})", e.what()));
  }
  part["status"] = "ran";
  part["seconds"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The GPU section's data: a device check's results folder (--gpu-from), else with --reuse the
// folder a previous report copied (it has no other source: no GPU runs here), else none.
json ReportRun::gpu_part(const fs::path& cached, const json& previous) {
  json part = {{"status", "skipped"},
               {"note", "no device check results given (--gpu-from DIR: a folder written by "
                        "glintlab_gpu_check on a GPU machine, docs/gpu.md)"}};
  if (!o_.gpu_from.empty()) {
    fs::copy(o_.gpu_from, stage_ / "gpu", fs::copy_options::recursive);
    part = {{"status", "read"},
            {"note", fmt::format("read from {} (glintlab_gpu_check results folder)", o_.gpu_from)}};
  } else if (o_.reuse && fs::is_regular_file(cached / "results.json")) {
    fs::copy(cached, stage_ / "gpu", fs::copy_options::recursive);
    if (previous.contains("parts") && previous["parts"].contains("gpu") &&
        previous["parts"]["gpu"].is_object())
      part = previous["parts"]["gpu"];
    part["status"] = "reused";
  }
  return part;
}

void ReportRun::run() {
  validate();
  out_ = fs::path(o_.out);
  if (out_.filename().empty()) out_ = out_.parent_path();
  std::error_code ec;
  // The report replaces DIR by a rename, so DIR must be a named folder below its parent.
  const fs::path full = fs::absolute(out_, ec).lexically_normal();
  const std::string leaf = full.filename().string();
  if (ec || leaf.empty() || leaf == "." || leaf == "..")
    throw InputError(fmt::format(
        "--out: '{}' does not name a folder the report can replace (give e.g. out/report)",
        o_.out));
  if (fs::exists(out_, ec) && !fs::is_directory(out_, ec))
    throw InputError(fmt::format("--out: '{}' exists and is not a folder", o_.out));
  const fs::path parent = out_.has_parent_path() ? out_.parent_path() : fs::path(".");
  // --reuse needs something to reuse: at least one part that is not skipped has its results.
  if (o_.reuse) {
    bool any = false;
    std::string looked;
    for (int i = 0; i < kNumParts; ++i) {
      if (std::find(skip_.begin(), skip_.end(), kParts[i]) != skip_.end()) continue;
      const fs::path index = out_ / kPartDirs[i] / kPartIndex[i];
      any = any || fs::is_regular_file(index, ec);
      looked += fmt::format("{}{}", looked.empty() ? "" : ", ", index.string());
    }
    if (!any)
      throw InputError(fmt::format(
          "--reuse: '{}' holds no results to reuse (valid: a report folder with one of {})", o_.out,
          looked));
  }
  check_output_dir(parent, "--out");
  fs::create_directories(parent, ec);
  register_staging_parent(parent);
  stage_ = parent / fmt::format(".{}.tmp.{}", out_.filename().string(), ::getpid());
  fs::remove_all(stage_, ec);
  if (!fs::create_directory(stage_, ec) || ec)
    throw InputError(fmt::format("--out: the folder '{}' is not writable ({})", parent.string(),
                                 ec ? ec.message() : "cannot create a folder"));
  RemoveOnExit cleanup{stage_};
  logs_ = stage_ / "logs";
  fs::create_directory(logs_);

  json previous;  // the cached report's run.json: where and how each reused part was made
  if (o_.reuse && fs::is_regular_file(out_ / "run.json")) {
    try {
      previous = json::parse(read_text(out_ / "run.json"));
    } catch (const json::exception& e) {
      throw InputError(fmt::format("--reuse: cached {} is malformed ({})",
                                   (out_ / "run.json").string(), e.what()));
    }
    if (!previous.is_object() || !previous.contains("parts") || !previous["parts"].is_object())
      throw InputError(
          fmt::format("--reuse: cached {} has no \"parts\" object", (out_ / "run.json").string()));
  }

  const json machine = machine_json(threads_);
  const std::string date = utc_now();
  progress_ = std::make_unique<Progress>("report", long(kNumParts + figures_.size() + 1));
  json parts = json::object();
  for (int i = 0; i < kNumParts; ++i) {
    const std::string name = kParts[i];
    json part = {{"status", ""}, {"budget", budget_}, {"machine", machine}, {"date", date}};
    const fs::path cached = out_ / kPartDirs[i];
    bool skipped = false;
    for (const std::string& s : skip_) skipped = skipped || s == name;
    if (skipped) {
      part["status"] = "skipped";
      part["note"] = "left out with --skip";
    } else if (o_.reuse && fs::is_regular_file(cached / kPartIndex[i]) &&
               !(name == "claims" && !o_.claims_from.empty())) {
      fs::copy(cached, stage_ / kPartDirs[i], fs::copy_options::recursive);
      // Where, when and at which budget the cached part was made, from the cached run.json.
      if (previous.contains("parts") && previous["parts"].contains(name) &&
          previous["parts"][name].is_object())
        part = previous["parts"][name];
      else
        part = {{"machine", "unknown (cached without run.json)"}, {"budget", "unknown"}};
      part["status"] = "reused";
      part["note"] = fmt::format("cached results reused from {} (--reuse)", cached.string());
      if (name == "figures") {
        for (std::size_t k = 0; k < figures_.size(); ++k) progress_->step("cached figure");
      }
    } else if (name == "claims") {
      run_claims(part);
    } else if (name == "conformance") {
      run_conformance(part);
    } else if (name == "figures") {
      run_figures(part);
    } else if (name == "bench") {
      run_bench(part);
    } else if (name == "stability") {
      run_stability(part);
    } else {
      run_compare(part);
    }
    parts[name] = part;
    progress_->step(name);
  }
  parts["gpu"] = gpu_part(out_ / "gpu", previous);
  const json run_info = {{"glintlab_version", experiments::glintlab_version()},
                         {"date", date},
                         {"budget", budget_},
                         {"machine", machine},
                         {"parts", parts}};
  io::write_file_atomic(stage_ / "run.json", run_info.dump(1) + "\n");
  // The schema of claims.json as this program prints it (glintlab schema claims.json): the report
  // checks this run's and any reused claims.json against it.
  fs::create_directories(stage_ / "schemas");
  io::write_file_atomic(stage_ / "schemas" / "claims.schema.json", verify::claims_json_schema());

  // The HTML report and the Markdown twin; make_report.py validates every input and fails with one
  // line (exit 2) on a malformed one, which becomes this command's error.
  const fs::path script = reports_dir() / "make_report.py";
  if (!fs::is_regular_file(script))
    throw std::runtime_error(fmt::format(
        "report: {} not found (set GLINTLAB_REPORTS_DIR to the reports/ folder)", script.string()));
  const fs::path err = logs_ / "make_report.stderr.txt";
  const int rc = run_process({"/usr/bin/python3", script.string(), "--dir", stage_.string()},
                             logs_ / "make_report.txt", err);
  if (rc != 0) {
    const std::string msg = last_error_line(err);
    if (rc == 2) throw InputError(msg);
    throw std::runtime_error(fmt::format("report: make_report.py failed (exit {}): {}", rc, msg));
  }
  progress_->step("html");
  progress_.reset();

  // Swap the finished report in: the old one (if any) moves aside, then goes.
  const fs::path old = parent / fmt::format(".{}.old.{}", out_.filename().string(), ::getpid());
  const bool had_old = fs::exists(out_, ec);
  if (had_old) {
    fs::rename(out_, old, ec);
    if (ec)
      throw std::runtime_error(
          fmt::format("--out: cannot move the old report '{}' aside ({})", o_.out, ec.message()));
  }
  fs::rename(stage_, out_, ec);
  if (ec) {
    std::error_code ec2;
    if (had_old) fs::rename(old, out_, ec2);
    throw std::runtime_error(
        fmt::format("--out: cannot move the report into '{}' ({})", o_.out, ec.message()));
  }
  cleanup.armed = false;
  if (had_old) fs::remove_all(old, ec);
  for (const auto& [name, part] : parts.items()) {
    fmt::print("{:<12} {}{}\n", name, part.value("status", ""),
               part.contains("note") ? " (" + part.value("note", "") + ")" : "");
  }
  fmt::print("report: wrote {} and {}\n", (out_ / "index.html").string(),
             (out_ / "report.md").string());
}

constexpr const char* kFooter =
    R"(DIR (default out/report) gets index.html (static, no script, relative links only) and its
Markdown twin report.md, and beside them every input: verify/ (claims.json, .csv, .md),
conformance/ (the same files for the --conformance models' suites, model.<name>.*),
figures/<id>/ (EXR, PNG, CSV of each figure), bench/ (bench.json, accuracy.csv, glints.json and
kemppinen.json, run before the figures, whose timing tables read them, methods/*.json), stability/
(stability.json and its maps), compare/ (glintlab compare of the --models, from the conformance,
verify and stability parts' outputs: compare.json, compare.csv, equal_time.csv), gpu/ (the --gpu-from folder as given), schemas/
(claims.schema.json, the schema every claims.json is checked against: glintlab schema), plots/ (the charts drawn by reports/make_report.py: convergence
log-log plots, speed_accuracy.png, speed_accuracy_methods.png and speed_accuracy.csv), logs/ and run.json (machine, budget,
date and status of each part). The report is staged in a hidden folder beside DIR and replaces DIR only when it is
complete: a bad option, a failed part or a malformed cached file leaves DIR as it was.)";

}  // namespace

void add_report_command(CLI::App& app) {
  auto o = std::make_shared<ReportOptions>();
  CLI::App* cmd = add_command(
      app, "report",
      "Run the claim suite, the models' conformance suites, every figure, the benchmarks and the "
      "stability sweeps (or reuse their cached results) and write a static HTML report with a Markdown twin");
  add_text_option(cmd, "--out", o->out, "output folder", "DIR");
  add_budget_option(cmd, o->budget,
                    "quick = quick figures, a short benchmark run, quick claims; full = all full");
  add_bool_flag(cmd, "--reuse", o->reuse,
                "reuse the parts whose results are already in --out (verify/claims.json, "
                "conformance/claims.json, figures/figures.json, bench/bench.json, stability/stability.json, "
                "compare/compare.json) instead of running them");
  add_text_option(cmd, "--claims", o->claims,
                  "comma-separated globs over claim ids (see glintlab verify --list)", "LIST");
  add_text_option(cmd, "--figures", o->figures,
                  "comma-separated globs over figure ids (see glintlab figure --list)", "LIST");
  add_text_option(cmd, "--models", o->models,
                  "comma-separated globs over model names (see glintlab models): the models the "
                  "stability and compare parts cover",
                  "LIST");
  add_text_option(cmd, "--conformance", o->conformance,
                  "comma-separated globs over model names: of the --models, those whose "
                  "conformance suite (glintlab verify --claims 'model.<name>.*') the report runs "
                  "at its budget for the comparison; when not given, every model but kemppinen_ggx and "
                  "kemppinen_beckmann (their suites take about 250 s of the about 300 s all nine "
                  "take at quick on 2 cores); '*' runs all. A model left out shows its recorded "
                  "verdicts, marked as recorded",
                  "LIST");
  add_text_option(cmd, "--claims-from", o->claims_from,
                  "a glintlab verify --out folder whose claims.json the report shows instead of "
                  "running the suite",
                  "DIR");
  add_text_option(cmd, "--gpu-from", o->gpu_from,
                  "a results folder of the device check (glintlab_gpu_check, "
                  "scripts/device_check.sh: results.json and its CSVs, docs/gpu.md) whose GPU "
                  "timings the report shows; without it the report has no GPU section",
                  "DIR");
  add_text_option(cmd, "--skip", o->skip,
                  "comma-separated parts to leave out: claims, conformance, bench, figures, "
                  "stability, compare",
                  "LIST");
  auto threads = std::make_shared<std::string>();
  add_threads_option(cmd, *threads);
  set_footer(cmd, kFooter);
  const CLI::App* root = &app;
  set_callback(cmd, [o, root, cmd, threads] { ReportRun(*o, *root, cmd, *threads).run(); });
}

}  // namespace glintlab::cli
