#include "experiments/compare/compare.h"

#include <fmt/format.h>

#include <sys/resource.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>
#include <time.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <map>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

#include "core/io/atomic_file.h"
#include "core/math/rng.h"
#include "core/model_registry.h"
#include "experiments/compare/albedo_estimates.h"
#include "experiments/compare/eval_timing.h"
#include "experiments/compare/model_findings.h"
#include "experiments/sweeps/stability_run.h"
#include "verify/conformance/common.h"
#include "verify/conformance/conformance.h"
#include "verify/stability/sweep.h"

namespace glintlab::experiments::compare {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::ordered_json;

fs::path claims_name(const CompareOptions& o) {
  return o.claims_shown_as.empty() ? o.claims_from : o.claims_shown_as;
}
fs::path conformance_name(const CompareOptions& o) {
  return o.conformance_shown_as.empty() ? o.conformance_from : o.conformance_shown_as;
}
fs::path sweeps_name(const CompareOptions& o) {
  return o.sweeps_shown_as.empty() ? o.sweeps_from : o.sweeps_shown_as;
}

// A JSON number, or null where it is not finite (JSON has no NaN).
json number(double x) { return std::isfinite(x) ? json(x) : json(nullptr); }

std::uint64_t seed_of(const ModelEntry& m, std::string_view what) {
  return hash_string(fmt::format("compare.{}.{}", m.name, what).c_str());
}

std::string light_of(const ModelEntry& m) {
  return (m.needs & kNeedsAreaLight) ? "1° cone" : "delta";
}

// What the untimed measurements of one model produced (run_measurements), before its timed ones.
struct Measured {
  // Where the suite is not run here: the verdicts read or recorded (conformance_verdicts), taken
  // before anything is measured, so that a malformed file is reported at once.
  std::optional<std::vector<PropertyVerdict>> verdicts;
  std::vector<verify::Check> checks;          // the model's conformance checks run here (or none)
  std::vector<verify::CheckResult> results;   // per check, in checks' order
  std::vector<AlbedoReference> refs;          // b.thetas_deg order
  std::vector<StabilityFinding> stability;
};

// A measurement of the parallel phase: its estimated seconds (the longest start first), the model
// and which of its progress steps it is part of.
enum class Part { kConformance, kReference, kStability };
constexpr const char* kPartNames[] = {"conformance", "reference", "stability"};
struct Job {
  double cost = 0;
  std::size_t model = 0;
  std::vector<Part> parts;
  std::function<void()> run;
  std::string what;  // what the job measures, for the step timings
};

// The step timings of a run (CompareFiles::steps): seconds since the run started.
class StepClock {
 public:
  double now() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }
  // The process's CPU time so far (user + system, every thread), seconds.
  static double cpu() {
    rusage u{};
    ::getrusage(RUSAGE_SELF, &u);
    return double(u.ru_utime.tv_sec + u.ru_stime.tv_sec) +
           1e-6 * double(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
  }
  // The calling thread's CPU time so far, seconds.
  static double thread_cpu() {
    timespec t{};
    ::clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
  }
  // Runs f and records it as a step: a timed one (thread < 0) with the process's CPU time it
  // took, a parallel job with its worker's.
  template <class F>
  void time(const std::string& phase, const std::string& model, const std::string& what,
            int thread, F&& f) {
    const bool timed = thread < 0;
    const double c0 = timed ? cpu() : thread_cpu(), t0 = now();
    f();
    const double t1 = now(), c1 = timed ? cpu() : thread_cpu();
    const std::lock_guard<std::mutex> lock(mutex_);
    steps_.push_back({phase, model, what, thread, t0, t1 - t0, c1 - c0});
  }
  std::vector<StepTiming> steps() const {
    std::vector<StepTiming> s = steps_;
    std::stable_sort(s.begin(), s.end(),
                     [](const StepTiming& a, const StepTiming& b) { return a.start < b.start; });
    return s;
  }

 private:
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
  std::mutex mutex_;
  std::vector<StepTiming> steps_;
};

// Runs the jobs on the run's threads (tbb::global_control's limit), the costliest first, each job
// isolated (a thread waiting in a job's own parallel loop takes only that loop's work), so a long
// job is not left alone at the end. The jobs write to their own slots only, and each is
// deterministic for any thread count, so the results do not depend on the order or the threads.
void run_longest_first(std::vector<Job>& jobs, const std::function<void(const Job&)>& done,
                       const std::vector<std::string>& models, StepClock& clock) {
  std::stable_sort(jobs.begin(), jobs.end(),
                   [](const Job& a, const Job& b) { return a.cost > b.cost; });
  const int workers = int(std::max<std::size_t>(
      1, std::min<std::size_t>(
             std::size_t(tbb::this_task_arena::max_concurrency()),
             tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism))));
  std::atomic<std::size_t> next{0};
  std::atomic<bool> failed{false};  // a job threw: the others start no new job
  tbb::parallel_for(
      0, workers,
      [&](int) {
        for (std::size_t i = next++; i < jobs.size() && !failed; i = next++) {
          try {
            clock.time("parallel", models[jobs[i].model], jobs[i].what,
                       tbb::this_task_arena::current_thread_index(),
                       [&] { tbb::this_task_arena::isolate([&] { jobs[i].run(); }); });
          } catch (...) {
            failed = true;
            throw;
          }
          done(jobs[i]);
        }
      },
      tbb::simple_partitioner());
}

std::string property_of(const ModelEntry& m, const std::string& check_id) {
  return check_id.substr(fmt::format("model.{}.", m.name).size());
}

std::vector<ClaimsFolder> claims_folders(const CompareOptions& o) {
  std::vector<ClaimsFolder> folders;
  if (!o.conformance_from.empty()) folders.push_back({o.conformance_from, conformance_name(o)});
  if (!o.claims_from.empty()) folders.push_back({o.claims_from, claims_name(o)});
  return folders;
}

// Every untimed measurement of every model, as jobs run in parallel: each conformance check run
// here (sampler-covers-value and energy in one job, in that order: they share the settings'
// integrals; stability with the failure regions, which reuse its sweep), each scene's reference and
// the stability sweep where no check sweeps. constant-time, a timing, is left to the timed phase.
// What is read from files (verdicts, failure regions) is read first, before any job.
std::vector<Measured> run_measurements(const CompareOptions& o, const CompareBudget& b,
                                       StepClock& clock) {
  std::vector<Measured> out(o.models.size());
  std::vector<Job> jobs;
  const auto cost = [&](const std::string& id) { return o.check_cost ? o.check_cost(id) : 1.0; };
  const std::vector<ClaimsFolder> folders = claims_folders(o);
  const bool conformance_here = o.measure_missing && folders.empty();
  const bool stability_here = o.measure_missing && o.sweeps_from.empty();
  for (std::size_t i = 0; i < o.models.size(); ++i) {
    const ModelEntry& m = find_model(o.models[i]);
    Measured& r = out[i];
    if (!conformance_here)
      r.verdicts = conformance_verdicts(m, o.budget, folders, o.measure_missing);
    if (!stability_here)
      r.stability =
          stability_findings(m, o.budget, o.sweeps_from, sweeps_name(o), o.measure_missing);
  }
  for (std::size_t i = 0; i < o.models.size(); ++i) {
    const ModelEntry& m = find_model(o.models[i]);
    Measured& r = out[i];
    r.refs.resize(b.thetas_deg.size());
    for (std::size_t k = 0; k < b.thetas_deg.size(); ++k) {
      const double theta = b.thetas_deg[k];
      // Cost 0: short (one integral), they fill the gaps at the end.
      jobs.push_back({0, i, {Part::kReference}, [&m, &r, &b, k, theta] {
                        r.refs[k] = reference_albedo(
                            m, theta, b, seed_of(m, fmt::format("reference.{:g}", theta)));
                      }, fmt::format("reference {:g}°", theta)});
    }
    const auto sweep_findings = [&o, &m, &r] {
      r.stability = stability_findings(m, o.budget, o.sweeps_from, sweeps_name(o), true);
    };
    bool swept = !stability_here;  // read (or not measured) above
    if (conformance_here) {
      r.checks = verify::conformance_checks(m);
      r.results.resize(r.checks.size());
      std::optional<std::size_t> covers, energy;
      for (std::size_t c = 0; c < r.checks.size(); ++c) {
        const std::string property = property_of(m, r.checks[c].id);
        const auto run_check = [&o, &r, c] { r.results[c] = r.checks[c].run(o.budget); };
        if (property == "constant-time") continue;  // timed: run_compare runs it alone
        if (property == "sampler-covers-value") {
          covers = c;
        } else if (property == "energy") {
          energy = c;
        } else if (property == "stability") {
          // With the failure regions where they are swept here (the check's sweep, reused).
          const bool with_findings = !swept;
          swept = true;
          std::vector<Part> parts{Part::kConformance};
          if (with_findings) parts.push_back(Part::kStability);
          jobs.push_back({cost(r.checks[c].id), i, parts, [run_check, sweep_findings, with_findings] {
                            run_check();
                            if (with_findings) sweep_findings();
                          }, with_findings ? "stability (+ failure regions)" : "stability"});
        } else {
          jobs.push_back({cost(r.checks[c].id), i, {Part::kConformance}, run_check, property});
        }
      }
      std::vector<std::size_t> shared;
      for (const auto& c : {covers, energy})
        if (c) shared.push_back(*c);
      if (!shared.empty()) {
        double seconds = 0;
        for (std::size_t c : shared) seconds += cost(r.checks[c].id);
        std::string what;
        for (std::size_t c : shared)
          what += (what.empty() ? "" : " + ") + property_of(m, r.checks[c].id);
        jobs.push_back({seconds, i, {Part::kConformance}, [&o, &r, shared] {
                          for (std::size_t c : shared) r.results[c] = r.checks[c].run(o.budget);
                        }, what});
      }
    }
    if (!swept)
      jobs.push_back(
          {cost(fmt::format("model.{}.stability", m.name)), i, {Part::kStability}, sweep_findings,
           "stability sweep (failure regions)"});
  }
  // Progress: a model's step of a part once its last job of that part is done.
  std::vector<std::array<int, 3>> pending(o.models.size(), {0, 0, 0});
  for (const Job& j : jobs)
    for (Part p : j.parts) ++pending[j.model][std::size_t(p)];
  std::mutex mutex;
  const auto step = [&](std::size_t model, Part p) {
    if (o.progress) o.progress(fmt::format("{} {}", o.models[model], kPartNames[std::size_t(p)]));
  };
  for (std::size_t i = 0; i < o.models.size(); ++i)
    for (Part p : {Part::kConformance, Part::kStability})
      if (pending[i][std::size_t(p)] == 0) step(i, p);
  run_longest_first(jobs, [&](const Job& j) {
    const std::lock_guard<std::mutex> lock(mutex);
    for (Part p : j.parts)
      if (--pending[j.model][std::size_t(p)] == 0) step(j.model, p);
  }, o.models, clock);
  return out;
}

// A model's entry of compare.json from its untimed measurements, after its timed ones: the
// constant-time check (where the suite runs here), the evaluation timings and the equal-time curve.
json model_json(const ModelEntry& m, const CompareOptions& o, const CompareBudget& b,
                const Measured& pre, StepClock& clock) {
  const auto timed = [&](const std::string& what, const auto& f) {
    clock.time("timed", std::string(m.name), what, -1, f);
  };
  const auto step = [&](const std::string& what) {
    if (o.progress) o.progress(fmt::format("{} {}", m.name, what));
  };
  json j;
  j["name"] = m.name;
  j["source"] = m.source;
  j["footprint"] = (m.needs & kNeedsFootprint) != 0;
  j["light"] = light_of(m);
  j["smooth_limit"] = m.smooth_limit.empty() ? json(nullptr) : json(m.smooth_limit);

  std::map<std::string, verify::CheckResult> measured;
  for (std::size_t c = 0; c < pre.checks.size(); ++c) {
    if (property_of(m, pre.checks[c].id) == "constant-time")
      timed("constant-time", [&] { measured[pre.checks[c].id] = pre.checks[c].run(o.budget); });
    else
      measured[pre.checks[c].id] = pre.results[c];
  }
  json verdicts = json::array();
  for (const PropertyVerdict& v :
       pre.verdicts ? *pre.verdicts
                    : conformance_verdicts(m, o.budget, {}, o.measure_missing, measured))
    verdicts.push_back({{"property", v.property},
                        {"verdict", v.verdict},
                        {"origin", v.origin},
                        {"control_rejected",
                         v.control_rejected ? json(*v.control_rejected) : json(nullptr)},
                        {"detail", v.detail}});
  j["conformance"] = verdicts;

  step("timing");
  EvalTiming t;
  timed("ns/eval", [&] { t = time_evaluations(m, b); });
  j["timing"] = {{"scalar_ns_per_eval", t.scalar_ns},
                 {"best_isa", t.best_isa},
                 {"best_ns_per_eval", t.best_ns},
                 {"batched", t.batched}};

  json references = json::array();
  for (const AlbedoReference& r : pre.refs) {
    // A reference that did not converge is flagged, and its value withheld.
    references.push_back({{"theta_deg", r.theta_deg},
                          {"method", r.method},
                          {"converged", r.converged},
                          {"albedo", r.converged ? number(r.value) : json(nullptr)},
                          {"error", r.converged ? number(r.error) : json(nullptr)}});
  }
  j["reference"] = references;

  step("equal-time curve");
  EqualTimeCurve c;
  timed("equal-time curve", [&] { c = equal_time_curve(m, pre.refs, b, seed_of(m, "sampler")); });
  json points = json::array();
  for (const EqualTimePoint& p : c.points)
    points.push_back(
        {{"samples", p.samples}, {"seconds", p.seconds}, {"relative_rmse", number(p.relative_rmse)}});
  j["equal_time"] = {{"isa", c.isa},
                     {"points", points},
                     {"reference_relative_error",
                      c.reason.empty() ? number(c.reference_relative_error) : json(nullptr)},
                     {"relative_bias", c.reason.empty() ? number(c.relative_bias) : json(nullptr)},
                     {"relative_bias_se",
                      c.reason.empty() ? number(c.relative_bias_se) : json(nullptr)},
                     {"not_shown", c.reason.empty() ? json(nullptr) : json(c.reason)}};

  json stability = json::array();
  for (const StabilityFinding& s : pre.stability)
    stability.push_back({{"sampler", s.sampler},
                         {"verdict", s.verdict},
                         {"origin", s.origin},
                         {"failure_region", s.failure_region}});
  j["stability"] = stability;
  return j;
}

// "holds 7, fails 1, not-claimed 2" over a model's conformance rows.
std::string verdict_counts(const json& verdicts) {
  std::vector<std::pair<std::string, int>> counts;
  for (const json& v : verdicts) {
    const std::string origin = v.at("origin");
    const std::string verdict =
        v.at("verdict").get<std::string>() + (origin == kMeasured ? "" : " (" + origin + ")");
    auto it = std::find_if(counts.begin(), counts.end(),
                           [&](const auto& c) { return c.first == verdict; });
    if (it == counts.end())
      counts.emplace_back(verdict, 1);
    else
      ++it->second;
  }
  std::string out;
  for (const auto& [v, n] : counts) out += fmt::format("{}{} {}", out.empty() ? "" : "; ", v, n);
  return out;
}

std::string csv_field(const std::string& s) {
  std::string q = "\"";
  for (char ch : s) q += ch == '"' ? std::string("\"\"") : std::string(1, ch);
  return q + "\"";
}

std::string csv_number(const json& x) { return x.is_null() ? "" : fmt::format("{:.6g}", x.get<double>()); }

std::string models_csv(const json& models) {
  std::ostringstream s;
  s << "model,conformance,scalar_ns_per_eval,best_isa,best_ns_per_eval,reference_converged,"
       "relative_rmse_at_max_samples,relative_bias,relative_bias_se,stability\n";
  for (const json& m : models) {
    bool converged = true;
    for (const json& r : m["reference"]) converged = converged && r["converged"].get<bool>();
    const json& points = m["equal_time"]["points"];
    std::string stability;
    for (const json& st : m["stability"])
      stability += fmt::format("{}{}: {}", stability.empty() ? "" : "; ",
                               st["sampler"].get<std::string>(), st["verdict"].get<std::string>());
    s << m["name"].get<std::string>() << ',' << csv_field(verdict_counts(m["conformance"])) << ','
      << csv_number(m["timing"]["scalar_ns_per_eval"]) << ','
      << m["timing"]["best_isa"].get<std::string>() << ','
      << csv_number(m["timing"]["best_ns_per_eval"]) << ',' << (converged ? "yes" : "no") << ','
      << (points.empty() ? "" : csv_number(points.back()["relative_rmse"])) << ','
      << csv_number(m["equal_time"]["relative_bias"]) << ','
      << csv_number(m["equal_time"]["relative_bias_se"]) << ',' << csv_field(stability) << '\n';
  }
  return s.str();
}

std::string equal_time_csv(const json& models) {
  std::ostringstream s;
  s << "model,samples,seconds,relative_rmse\n";
  for (const json& m : models)
    for (const json& p : m["equal_time"]["points"])
      s << m["name"].get<std::string>() << ',' << p["samples"].get<std::uint64_t>() << ','
        << fmt::format("{:.6g}", p["seconds"].get<double>()) << ','
        << csv_number(p["relative_rmse"]) << '\n';
  return s.str();
}

json settings_json(const CompareOptions& o, const CompareBudget& b) {
  json s = {{"budget", o.budget == verify::Budget::kQuick ? "quick" : "full"},
          {"theta_deg", b.thetas_deg},
          {"footprint_side_uv", kSceneFootprint},
          {"quantity", "albedo: ∫ value dωo over the upper hemisphere (white furnace)"},
          {"reference_monte_carlo_block", verify::conformance::reference_block(o.budget)},
          {"reference_monte_carlo_max_blocks", verify::conformance::kMaxReferenceBlocks},
          {"reference_monte_carlo_target_relative_error",
           verify::conformance::kReferenceRelativeError},
          {"cubature_converged_relative_error", b.cubature_converged_rel},
          {"monte_carlo_converged_relative_error", b.monte_carlo_converged_rel},
          {"max_samples", b.max_samples},
          {"repetitions", b.repetitions},
          {"timing_rows", b.timing_rows},
          {"timing_seconds_per_round", b.timing_seconds},
          {"claims_from", o.claims_from.empty() ? json(nullptr) : json(claims_name(o).string())},
          {"sweeps_from", o.sweeps_from.empty() ? json(nullptr) : json(sweeps_name(o).string())}};
  if (!o.conformance_from.empty()) s["conformance_from"] = conformance_name(o).string();
  return s;
}

}  // namespace

CompareFiles run_compare(const fs::path& dir, const CompareOptions& o) {
  const CompareBudget b = compare_budget(o.budget);
  // A model's stability is swept once: by its conformance suite's stability property where that
  // runs here, and the same sweep gives the failure regions.
  const verify::stability::SweepReuse one_sweep_per_model;
  // First everything that is not a timing, in parallel; then, one model at a time with nothing
  // else running, the timings (constant-time, time per evaluation, the equal-time curve).
  StepClock clock;
  const double cpu0 = StepClock::cpu();
  const std::vector<Measured> measured = run_measurements(o, b, clock);
  const double parallel_end = clock.now(), cpu1 = StepClock::cpu();
  json models = json::array();
  for (std::size_t i = 0; i < o.models.size(); ++i)
    models.push_back(model_json(find_model(o.models[i]), o, b, measured[i], clock));
  const double timed_end = clock.now(), cpu2 = StepClock::cpu();
  json doc;
  doc["machine"] = machine_name();
  doc["settings"] = settings_json(o, b);
  doc["models"] = models;
  CompareFiles files{dir / "compare.json", dir / "compare.csv", dir / "equal_time.csv",
                     clock.steps()};
  files.parallel_seconds = parallel_end;
  files.parallel_cpu_seconds = cpu1 - cpu0;
  files.timed_seconds = timed_end - parallel_end;
  files.timed_cpu_seconds = cpu2 - cpu1;
  io::write_file_atomic(files.json, doc.dump(1) + "\n");
  io::write_file_atomic(files.csv, models_csv(models));
  io::write_file_atomic(files.equal_time_csv, equal_time_csv(models));
  return files;
}

}  // namespace glintlab::experiments::compare
