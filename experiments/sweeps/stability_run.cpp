// The stability sweeps of every selected model × sampler into one folder, staged and then moved.
#include "experiments/sweeps/stability_run.h"

#include <fmt/format.h>
#include <unistd.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <system_error>
#include <thread>
#include <vector>

#include "core/io/atomic_file.h"
#include "experiments/sweeps/stability_maps.h"
#include "verify/stability/failure_region.h"

namespace glintlab::experiments {

namespace fs = std::filesystem;

std::string machine_name() {
  std::string cpu = "unknown CPU";
  std::ifstream in("/proc/cpuinfo");
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("model name", 0) == 0) {
      const auto colon = line.find(':');
      if (colon != std::string::npos) cpu = line.substr(line.find_first_not_of(" \t", colon + 1));
      break;
    }
  }
  return fmt::format("{}, {} hardware threads", cpu, std::thread::hardware_concurrency());
}

SweepRunSummary run_sweeps(const fs::path& out, const SweepRunOptions& o) {
  namespace st = verify::stability;
  const auto targets = st::sweep_targets(o.models);
  if (targets.empty()) {
    std::string names;
    for (const ModelEntry& m : registered_models())
      names += fmt::format("{}{}", names.empty() ? "" : ", ", m.name);
    throw SweepError(fmt::format(
        "--models: '{}' matches no registered model (valid: comma-separated globs over {})",
        o.models, names));
  }
  std::error_code ec;
  fs::create_directories(out, ec);
  if (ec || !fs::is_directory(out)) {
    throw SweepError(fmt::format("--out: cannot create output folder '{}' ({})", out.string(),
                                 ec ? ec.message() : "not a folder"));
  }
  const fs::path staging = out / fmt::format(".stability.tmp.{}", ::getpid());
  fs::remove_all(staging, ec);
  if (!fs::create_directory(staging, ec) || ec) {
    throw SweepError(fmt::format("--out: output folder '{}' is not writable ({})", out.string(),
                                 ec ? ec.message() : "cannot create a folder"));
  }
  struct Cleanup {
    fs::path dir;
    ~Cleanup() {
      std::error_code e;
      fs::remove_all(dir, e);
    }
  } cleanup{staging};

  nlohmann::ordered_json doc;
  doc["machine"] = machine_name();
  doc["budget"] = o.budget == verify::Budget::kQuick ? "quick" : "full";
  doc["models"] = nlohmann::ordered_json::array();
  std::vector<std::string> top;  // top-level entries to move: one folder per model
  std::vector<fs::path> dirs;    // each target's folder in the staging folder
  for (const st::SweepTarget& t : targets) {
    const st::ModelSweep s = st::sweep_model(t, o.budget, [&](long done, long total) {
      if (o.progress) o.progress(t.id(), done, total);
    });
    const fs::path rel = fs::path(std::string(t.model->name)) / t.sampler;
    const auto files = write_stability_maps(s, staging, rel);
    dirs.push_back(staging / rel);
    nlohmann::ordered_json entry;
    entry["model"] = t.model->name;
    entry["sampler"] = t.sampler;
    entry["maps"] = nlohmann::ordered_json::array();
    for (const MapFile& f : files) {
      entry["maps"].push_back({{"quantity", f.quantity},
                               {"png", f.png},
                               {"exr", f.exr},
                               {"csv", f.csv},
                               {"axis", f.axis}});
    }
    entry["failure_region"] = st::describe_failure_region(s);
    entry["verdict"] = verify::to_string(st::stability_verdict(s));
    entry["float_instantiation"] = s.has_float;
    doc["models"].push_back(std::move(entry));
    const std::string model_dir(t.model->name);
    if (top.empty() || top.back() != model_dir) top.push_back(model_dir);
  }
  if (o.finish) o.finish(staging, dirs);
  io::write_file_atomic(staging / "stability.json", doc.dump(2) + "\n");
  // Every target finished: replace the model folders, then the index.
  top.push_back("stability.json");
  for (const std::string& name : top) {
    fs::remove_all(out / name, ec);
    fs::rename(staging / name, out / name, ec);
    if (ec) {
      throw SweepError(fmt::format("--out: cannot move results into '{}' ({})",
                                   (out / name).string(), ec.message()));
    }
  }
  return {targets.size(), out / "stability.json"};
}

}  // namespace glintlab::experiments
