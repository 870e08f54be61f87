// `glintlab compare`: the registered models side by side on the same scenes, footprints and
// lights (compare_budget.h): conformance verdicts, time per evaluation (scalar and best ISA), the
// albedo reference and the sampler's error against it, equal-time error curves, and the
// stability failure regions. Written as compare.json (everything), compare.csv (one row per
// model) and equal_time.csv (one row per model and sample count); reports/compare_page.py draws
// the chart and the HTML page from them.
#pragma once

#include <filesystem>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "verify/check.h"

namespace glintlab::experiments::compare {

struct CompareOptions {
  verify::Budget budget = verify::Budget::kQuick;
  std::vector<std::string> models;        // registered model names, in the order shown
  std::filesystem::path claims_from;      // a `glintlab verify --out` folder; empty: see below
  // A second `glintlab verify --out` folder holding the models' conformance rows (the report's
  // conformance part), read before claims_from; empty: none.
  std::filesystem::path conformance_from;
  std::filesystem::path sweeps_from;      // a `glintlab sweep --out` folder; empty: see below
  // How the two folders are named in the outputs, where that differs from where they are read
  // (the report reads its staging folder but shows the folder it becomes); empty: as given.
  std::filesystem::path claims_shown_as, conformance_shown_as, sweeps_shown_as;
  // Without claims_from, conformance_from / sweeps_from: run each model's conformance checks (minutes per glint
  // model) and sweeps here; when false, show the recorded verdicts only and no failure region
  // (the report: it never runs a suite it did not run itself).
  bool measure_missing = true;
  std::function<void(const std::string& step)> progress;  // never called by two threads at once
  // The estimated seconds of a conformance check (by id, e.g. the recorded ones of
  // cli/claim_costs.h): the measurements run in parallel start with the costliest, so a long one
  // is not left alone at the end; empty: all equal. Only the run's duration depends on it.
  std::function<double(const std::string& check_id)> check_cost;
};

// What one step of a run took: a job of the parallel phase (every untimed measurement, on the
// run's threads) or a step of the timed phase (one model at a time, nothing else running). Seconds
// from the start of run_compare; `thread` is the worker that ran a parallel job (TBB's thread
// index), -1 in the timed phase; cpu_seconds: the process's CPU time (user + system) during a
// timed step (nothing else runs then), the worker's own CPU time during a parallel job (without
// the parts of its parallel loops that another worker took; below its wall time where it waited).
struct StepTiming {
  std::string phase;  // "parallel" or "timed"
  std::string model, what;
  int thread = -1;
  double start = 0, seconds = 0, cpu_seconds = 0;
};

struct CompareFiles {
  std::filesystem::path json, csv, equal_time_csv;
  std::vector<StepTiming> steps;  // in the order they started
  // Wall and process CPU seconds of the two phases (the CPU over the wall says how many threads
  // were busy on average; on a shared machine, also how much of them the run got).
  double parallel_seconds = 0, parallel_cpu_seconds = 0, timed_seconds = 0, timed_cpu_seconds = 0;
};

// Measures every model and writes the three files into `dir` (each atomically). The numbers that
// are not timings are the same for any thread count. Throws std::runtime_error on an unreadable
// or malformed claims_from / sweeps_from file.
CompareFiles run_compare(const std::filesystem::path& dir, const CompareOptions& options);

// The fields of compare.json that are wall-clock measurements (left out by determinism checks).
inline constexpr const char* kTimingFields[] = {"scalar_ns_per_eval", "best_ns_per_eval",
                                                "seconds"};

}  // namespace glintlab::experiments::compare
