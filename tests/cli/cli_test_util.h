// Helpers for the CLI tests: run the real `glintlab` executable in a fresh temporary directory
// per test and inspect its exit code, stdout, stderr and the files it leaves behind.
#pragma once

#include <gtest/gtest.h>

#include <array>
#include <filesystem>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "cli/build_paths.h"
#include "core/io/csv.h"

namespace glintlab::cli_test {

struct RunResult {
  int exit_code = -1;  // the process's exit status; -1 if it did not exit normally
  std::string out;     // everything it wrote to stdout
  std::string err;     // everything it wrote to stderr
};

// Lines of a text, without their line ends (a final line end does not start a new line).
std::vector<std::string> lines_of(const std::string& text);
std::string read_text(const std::filesystem::path& path);
void write_text(const std::filesystem::path& path, const std::string& text);

// A Google Benchmark JSON file of glintlab_bench_glints' adequacy rows for each of `models` on every
// ISA, with the given ns per evaluation (smooth, realtime, small_count, exact); rows whose name
// contains `skip` are left out.
std::string level_costs_json(const std::vector<std::string>& models,
                             const std::array<double, 4>& ns, const std::string& skip = "");

// A numeric cell of an output file; unlike CsvTable::number also reads "nan", "-nan", "inf" and
// "-inf", which the executable prints for non-finite results.
double cell_value(const io::CsvTable& table, std::size_t row, std::size_t col);
// a == b, or both NaN.
bool same_value(double a, double b);

// Names of the entries of `dir` (recursively, relative to it) that are not in `expected`.
std::vector<std::string> unexpected_files(const std::filesystem::path& dir,
                                          const std::set<std::string>& expected);

class CliTest : public ::testing::Test {
 protected:
  void SetUp() override;
  void TearDown() override;

  // Runs `glintlab args...` with the working directory work(); arguments are shell-quoted.
  RunResult run(const std::vector<std::string>& args) const;

  // The directory the executable runs in; empty at the start of each test.
  const std::filesystem::path& work() const { return work_; }
  // Every file under `dir` (a path in work()): relative path -> bytes; for byte-comparing two runs.
  std::map<std::string, std::string> file_tree(const std::string& dir) const;
  // Every path (files and folders) under work(), relative: what a failed run must leave as it is.
  std::set<std::string> work_paths() const;
  std::filesystem::path path(const std::string& name) const { return work_ / name; }

  // Asserts a failed run: exit code 2, nothing on stdout, exactly one stderr line of the form
  // "glintlab: error: <message>" whose message contains every string of `needles`, and that
  // work() holds exactly the files in `expected_files` (no output file, no temporary file).
  void expect_input_error(const RunResult& r, const std::vector<std::string>& needles,
                          const std::set<std::string>& expected_files) const;

  // From this call to the end of the test, the runs' charts (reports/figure_charts.py: a figure's
  // charts, a sweep's maps) are "drawn" by a stand-in that writes each chart spec's bytes followed
  // by its CSV's as NAME.png, without matplotlib (its start-up and drawing cost 1–3 s of CPU per
  // run). For tests of what runs compute and write, not of the drawing: a chart's bytes are then
  // those of its spec and data, which the real drawing turns into the same PNG in any run
  // (FigureChartsTest.SeveralFoldersInOneRunAreTheBytesOfSeparateRunsOrNone). Likewise compare's
  // page (reports/compare_page.py, about 1 s a run): its index.html and equal_time.png are then
  // the bytes of the compare.json they are drawn from, the page's only input.
  void stand_in_charts();

 private:
  std::filesystem::path root_;     // per-test temporary directory
  std::filesystem::path work_;     // root_/work: the executable's working directory
  std::filesystem::path capture_;  // root_/capture: stdout and stderr of the runs
  std::filesystem::path reports_;  // GLINTLAB_REPORTS_DIR of the runs, when not empty
};

}  // namespace glintlab::cli_test
