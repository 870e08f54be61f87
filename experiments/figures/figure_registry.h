// Registry of the figure experiments run by `glintlab figure`: one file per paper in
// experiments/figures/, each entry registered with the paper figure or table it reproduces.
#pragma once

#include <filesystem>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "core/lights/environment_map.h"

namespace glintlab::experiments {

// Bad figure input (unknown id, unwritable output folder); one line.
struct FigureError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct FigureContext {
  std::filesystem::path dir;  // the (staging) folder the experiment writes every file into
  bool quick = false;         // smaller images and budgets (the ctest runs)
  int threads = 0;            // 0 = all cores
  // The environment light of experiments lit by one (`glintlab figure --env FILE`); null = each
  // experiment's default (a procedural sky). `environment_name` describes it in the outputs.
  std::shared_ptr<const EnvironmentMap> environment;
  std::string environment_name;
  // The folder of Google Benchmark JSON the timing figures read (`glintlab figure --bench-from
  // DIR`; the report's own bench/ folder): glints.json of glintlab_bench_glints, kemppinen.json of
  // glintlab_bench_kemppinen. Empty = none given: a figure then says so and reads no fixed path,
  // so its numbers never come from another run. `bench_name` is how the outputs name the folder
  // (the report's staging folder is renamed when done); empty = bench_dir itself.
  std::filesystem::path bench_dir;
  std::string bench_name;
  // (stage, done, total); called from one thread at a time.
  std::function<void(const std::string& stage, long done, long total)> progress;
  // Called on the staging folder once the experiment has written its files, before the folder
  // replaces out_dir/<id> (`glintlab figure` and `glintlab report` draw the figure's charts from
  // its NAME.chart.json specs here: cli/child_process.h draw_figure_charts); empty = nothing. A
  // throw fails the run like one of the experiment's own.
  std::function<void(const std::filesystem::path& dir)> finish;
};

struct FigureEntry {
  std::string_view id;
  std::string_view paper;   // e.g. "Eto & Tokuyoshi 2023"
  std::string_view target;  // e.g. "Fig. 4"
  std::string_view description;
  void (*run)(const FigureContext&);
};

const std::vector<FigureEntry>& registered_figures();
// The entry with `id`; throws FigureError listing the valid ids otherwise.
const FigureEntry& find_figure(std::string_view id);

// Runs `entry` into `out_dir/<id>/`: every file is written to a staging folder beside it that
// replaces `out_dir/<id>` only when the experiment finished, so a failed run leaves no partial
// output. Throws FigureError if `out_dir` cannot be created or written.
std::filesystem::path run_figure(const FigureEntry& entry, const std::filesystem::path& out_dir,
                                 FigureContext context);

// The glintlab version written into every output's metadata.
std::string_view glintlab_version();

}  // namespace glintlab::experiments
