// `glintlab figure`, `sweep`, `compare` and `adequacy` as functions: each subcommand's option
// checks and run, without CLI11 and without printing, so that the command line and the Python
// module (python/module.cpp) check the same values with the same messages and write the same
// files. The options are the command line's text; every bad value is an InputError naming the
// option and its valid range. The subcommands print the returned summaries.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>

#include "cli/input.h"
#include "experiments/adequacy/adequacy_outputs.h"
#include "experiments/sweeps/stability_run.h"

namespace glintlab::cli {

// The --budget text: true for "quick", false for "full"; resolve_budget's InputError otherwise
// (without the --quick alias, which only the command line has).
inline bool quick_budget(const std::string& budget) {
  return resolve_budget(nullptr, BudgetOption{budget, false}) == "quick";
}

// `glintlab figure ID`: the figure's files in out/<id>/.
struct FigureRequest {
  std::string id;
  std::string out = "out/figures";
  std::string budget = "full";
  std::string threads = "0";
  std::string env;                        // empty: each experiment's procedural sky
  std::optional<std::string> bench_from;  // unset: not given (no benchmark data)
};
// The figure id's check alone (the command line makes it before resolving --budget).
void check_figure_id(const std::string& id);
// Returns the folder written, out/<id>.
std::filesystem::path run_figure_request(const FigureRequest& r);

// `glintlab sweep`.
struct SweepRequest {
  std::string out = "out/sweeps";
  std::string budget = "full";
  std::string models = "*";
  std::string threads = "0";
};
experiments::SweepRunSummary run_sweep_request(const SweepRequest& r);

// `glintlab compare`.
struct CompareRequest {
  std::string out = "out/compare";
  std::string budget = "quick";
  std::string models = "*";
  std::string threads = "0";
  std::string claims_from, sweeps_from;  // empty: not given
};
struct CompareSummary {
  std::size_t models = 0;
  // out: compare.json, compare.csv, equal_time.csv, equal_time.png and index.html.
  std::filesystem::path dir;
};
CompareSummary run_compare_request(const CompareRequest& r);

// `glintlab adequacy [--calibrate]`.
struct AdequacyRequest {
  std::string out = "out/adequacy";
  std::string budget = "quick";
  std::string models = "*";
  std::string threshold = "0.02";
  std::string threads = "0";
  bool calibrate = false;
  std::optional<std::string> runs;  // unset: not given (2000 with calibrate)
  std::optional<std::string> tables;  // unset: not given (20 with calibrate)
  std::optional<std::string> bench_from;  // a folder holding glints.json (the levels' costs)
  std::optional<std::string> shard;       // K/N: the K-th of N parts of the table's cells
  std::optional<std::string> positions;   // surface positions per cell; unset: the budget's
};
struct AdequacyRunSummary {
  bool calibrate = false;
  double threshold = 0;
  double seconds = 0;                                   // wall time of the measurement
  experiments::AdequacySummary table;                   // without calibrate
  experiments::AdequacyCalibrationSummary calibration;  // with calibrate
  std::string costs_source, costs_isa;  // with --bench-from: the file and ISA that priced levels
  // With --shard: which shard, and how many of the table's cells it measured (out of all).
  std::optional<std::pair<std::uint64_t, std::uint64_t>> shard;
  std::size_t shard_cells = 0, table_cells = 0;
};
AdequacyRunSummary run_adequacy_request(const AdequacyRequest& r);

}  // namespace glintlab::cli
