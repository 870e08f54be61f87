// `glintlab sweep`: the stability sweeps of every registered model × sampler (claim
// all.stability) written into one folder — per target the maps of stability_maps.h under
// <model>/<sampler>/, and stability.json listing them with each target's failure region in words.
#pragma once

#include <filesystem>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "verify/check.h"

namespace glintlab::experiments {

// Bad sweep input (no model matches, unwritable output folder); one line.
struct SweepError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct SweepRunOptions {
  verify::Budget budget = verify::Budget::kQuick;
  std::string models;  // comma-separated fnmatch globs over model names; empty = all
  // (target id, plane done, planes total); called from one thread at a time.
  std::function<void(const std::string& target, long done, long total)> progress;
  // Called once every target's files are written, with the staging folder and each target's
  // folder in it, in the run's order (glintlab sweep: draws all the maps' charts in one run of
  // the chart script); a throw fails the run and leaves `out` as it was.
  std::function<void(const std::filesystem::path& staging,
                     const std::vector<std::filesystem::path>& dirs)>
      finish;
};

struct SweepRunSummary {
  std::size_t targets = 0;
  std::filesystem::path json;  // DIR/stability.json
};

// Sweeps every selected target and writes the files into `out`. Everything is written into a
// staging folder inside `out` first and moved into place only when every target finished, so a
// failed run leaves `out` as it was. stability.json holds no timings: for one budget and model
// set it is identical for any thread count. Throws SweepError.
SweepRunSummary run_sweeps(const std::filesystem::path& out, const SweepRunOptions& options);

// "<CPU model>, <n> hardware threads" (from /proc/cpuinfo where readable).
std::string machine_name();

}  // namespace glintlab::experiments
