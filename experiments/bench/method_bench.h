// Helpers for the method-level speed-vs-accuracy benchmarks
// (experiments/bench/METHOD_BENCHMARKS.md): the row name
// `method/<method>/<setting>`, the query seed hashed from the method id, the error statistics
// err_max / err_rms / err_p99 / err_n and the quick mode of ctest.
#pragma once

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <functional>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "core/math/rng.h"

namespace glintlab::bench {

// Error of one method and setting against its reference over a fixed query set.
struct ErrorStats {
  double max = 0, rms = 0, p99 = 0;
  double n = 0;                                            // number of queries compared
  std::vector<std::pair<std::string, double>> extra = {};  // further counters (finite values)
};

// max, RMS and the 99th percentile (nearest rank, ⌈0.99 n⌉-th smallest) of non-negative errors;
// a non-finite error is kept (it makes max and RMS non-finite: a broken method must show).
inline ErrorStats error_stats(std::vector<double> e) {
  ErrorStats s;
  s.n = double(e.size());
  if (e.empty()) return s;
  double sum = 0;
  for (double v : e) sum += v * v;  // index order: deterministic
  s.rms = std::sqrt(sum / double(e.size()));
  std::sort(e.begin(), e.end(), [](double a, double b) {
    return std::isnan(b) ? !std::isnan(a) : a < b;  // NaN last
  });
  s.max = e.back();
  const std::size_t rank = std::size_t(std::ceil(0.99 * double(e.size())));
  s.p99 = e[std::max<std::size_t>(rank, 1) - 1];
  return s;
}

// |y − r| / max(|r|, floor): relative error, absolute at `floor` near zero.
inline double relative_error(double y, double r, double floor) {
  return std::abs(y - r) / std::max(std::abs(r), floor);
}

// The seed of a method's query set: hashed from its id, never picked.
inline std::uint64_t method_seed(const std::string& method) { return hash_string(method.c_str()); }

// GLINTLAB_BENCH_QUICK=1 (ctest): small query sets and references; the numbers are then not the
// ones to report.
inline bool quick_mode() {
  const char* v = std::getenv("GLINTLAB_BENCH_QUICK");
  return v != nullptr && std::string(v) == "1";
}

// `method` and `setting` as the schema names them: no '/' or spaces inside either.
inline std::string method_row_name(const std::string& method, const std::string& setting) {
  for (const std::string* s : {&method, &setting})
    if (s->empty() || s->find_first_of("/ ") != std::string::npos)
      throw std::invalid_argument("method benchmark name part '" + *s +
                                  "' is empty or has '/' or ' '");
  return "method/" + method + "/" + setting;
}

// Sets the schema's counters and label (call once per run, outside the timed loop).
inline void report_error(benchmark::State& state, const ErrorStats& e, const std::string& label) {
  state.counters["err_max"] = e.max;
  state.counters["err_rms"] = e.rms;
  state.counters["err_p99"] = e.p99;
  state.counters["err_n"] = e.n;
  for (const auto& [name, value] : e.extra) state.counters[name] = value;
  state.SetLabel(label);
}

// Errors computed once per row, the first time the row runs (Google Benchmark calls a benchmark
// function several times while it picks the iteration count), so that a filtered-out row costs
// nothing and the timed loop never includes the reference.
inline const ErrorStats& cached_error(const std::string& row,
                                      const std::function<ErrorStats()>& compute) {
  static std::map<std::string, ErrorStats> cache;
  auto it = cache.find(row);
  if (it == cache.end()) it = cache.emplace(row, compute()).first;
  return it->second;
}

// Registers `method/<method>/<setting>`: `run(state)` is the timed loop (it calls
// SetItemsProcessed with the evaluations done), `errors()` the error against the reference.
inline void register_method(const std::string& method, const std::string& setting,
                            const std::string& label, std::function<void(benchmark::State&)> run,
                            std::function<ErrorStats()> errors) {
  const std::string name = method_row_name(method, setting);
  benchmark::RegisterBenchmark(name.c_str(), [name, label, run, errors](benchmark::State& s) {
    const ErrorStats& e = cached_error(name, errors);
    run(s);
    report_error(s, e, label);
  });
}

// The main() of a benchmark binary whose rows are registered at run time, after registering them.
inline int run_benchmarks(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}

}  // namespace glintlab::bench
