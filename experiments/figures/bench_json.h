// Rows of a Google Benchmark JSON file (--benchmark_out_format=json) for the figures that put our
// timings beside a paper's table: name, time per iteration, items/s, label and user counters.
#pragma once

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "experiments/figures/figure_registry.h"

namespace glintlab::experiments {

struct BenchRow {
  std::string name;         // run_name (without aggregate suffixes)
  double real_time_ns;      // per iteration
  double items_per_second;  // 0 when the benchmark sets no items
  std::string label;
  std::map<std::string, double> counters;  // every other numeric field (user counters)
  // ns per processed item (1e9 / items_per_second), else the iteration time.
  double ns_per_item() const {
    return items_per_second > 0 ? 1e9 / items_per_second : real_time_ns;
  }
};

// The iteration rows of the file (aggregates skipped, except that a file of repetitions gives
// each name's median aggregate instead of its repetitions). nullopt when the file cannot be read;
// throws std::runtime_error naming the file when it is not benchmark JSON.
std::optional<std::vector<BenchRow>> read_bench_json(const std::filesystem::path& path);

// The row named `name`, or null.
const BenchRow* find_bench_row(const std::vector<BenchRow>& rows, const std::string& name);

// Where a figure's benchmark file lies: `file` in ctx.bench_dir (`glintlab figure --bench-from`),
// and that path as the figure's outputs name it. `path` is empty when no folder was given.
struct BenchSource {
  std::filesystem::path path;
  std::string shown_as;
};
BenchSource bench_source(const FigureContext& ctx, std::string_view file);

// The one sentence a figure without benchmark data writes: why it has none (no --bench-from
// folder, or the folder lacks the file) and how to make it: `tool` (a benchmark binary with its
// filter), writing `file`, then the figure rerun with --bench-from.
std::string no_bench_data(const BenchSource& s, std::string_view file, std::string_view tool);

}  // namespace glintlab::experiments
