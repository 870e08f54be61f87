// glintlab_gpu_check: the device check run on a GPU machine (scripts/device_check.sh). For every
// built-in model with device kernels (gpu/device_support.h), in float and double, runs eval, pdf
// and sample over the fixed query set (gpu/query_set.h) on the device and writes, into --out:
//   queries.csv                      the query set's rows (every column, exact decimal form)
//   <model>.<precision>.<function>.csv  the device's output columns, one row per query
//   table3_pixels.csv                the Table 3 analogue frames' radiance at the first rows pixels
//   results.json                     the device, the toolkit, the settings, each run's timing and
//                                    each Table 3 frame's (gpu/table3_frame.h)
// The folder is written under a temporary name and renamed when complete. Needs only the CUDA
// runtime and the core headers (no fmt, TBB, OpenEXR or the CLI): the GPU machine has nothing else.
// The CPU side reads the folder back (glintlab_gpu_compare) and compares it with the CPU batches.
#include <array>
#include <cerrno>
#include <cinttypes>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "core/model_layout.h"
#include "gpu/device_models.h"
#include "gpu/device_support.h"
#include "gpu/query_set.h"
#include "gpu/results_format.h"
#include "gpu/table3_frame.h"

namespace fs = std::filesystem;
using namespace glintlab;

namespace {

struct Options {
  fs::path out;
  std::size_t rows = 2048;             // written: enough to compare, small enough to commit
  std::size_t timing_rows = 1u << 20;  // timed: enough to fill the device
  int repetitions = 20;
  std::uint64_t seed = gpu::kQuerySeed;
};

[[noreturn]] void fail_input(const std::string& message) {
  std::fprintf(stderr, "glintlab_gpu_check: error: %s\n", message.c_str());
  std::exit(2);
}

std::uint64_t parse_count(const char* option, const char* text, std::uint64_t lo,
                          std::uint64_t hi) {
  char* end = nullptr;
  errno = 0;
  const unsigned long long v = std::strtoull(text, &end, 10);
  if (errno != 0 || end == text || *end != '\0' || text[0] == '-' || v < lo || v > hi)
    fail_input(std::string(option) + " '" + text + "' is not an integer in [" + std::to_string(lo) +
               ", " + std::to_string(hi) + "]");
  return v;
}

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string_view a = argv[i];
    const auto value = [&]() -> const char* {
      if (i + 1 >= argc) fail_input(std::string(a) + " needs a value");
      return argv[++i];
    };
    if (a == "--out") {
      o.out = value();
    } else if (a == "--rows") {
      o.rows = parse_count("--rows", value(), 1, std::uint64_t(1) << 26);
    } else if (a == "--timing-rows") {
      o.timing_rows = parse_count("--timing-rows", value(), 1, std::uint64_t(1) << 26);
    } else if (a == "--repetitions") {
      o.repetitions = static_cast<int>(parse_count("--repetitions", value(), 1, 1000));
    } else if (a == "-h" || a == "--help") {
      std::printf(
          "Usage: glintlab_gpu_check --out DIR [--rows N] [--timing-rows M] [--repetitions R]\n"
          "Runs every device-capable model's eval, pdf and sample (float and double) over a\n"
          "fixed query set of M rows (default 1048576, 1 <= M <= 67108864) on the first CUDA\n"
          "device, times R launches of each (default 20, 1 <= R <= 1000), and writes the\n"
          "first N rows (default 2048, 1 <= N <= M) of every result to DIR (queries.csv,\n"
          "<model>.<precision>.<function>.csv, results.json); then renders and times every cell\n"
          "of the Table 3 analogue (Kemppinen et al. 2025: 1920x1080, 3 point lights, k = 4) as\n"
          "R frames, keeping N pixels of each (table3_pixels.csv); docs/gpu.md.\n");
      std::exit(0);
    } else {
      fail_input("unknown argument '" + std::string(a) +
                 "' (valid: --out DIR, --rows N, --repetitions R)");
    }
  }
  if (o.rows > o.timing_rows)
    fail_input("--rows " + std::to_string(o.rows) + " is above --timing-rows " +
               std::to_string(o.timing_rows) + " (valid: 1 <= N <= M)");
  if (o.out.empty()) fail_input("--out DIR is required (the folder to write)");
  if (fs::exists(o.out)) fail_input("--out '" + o.out.string() + "' exists (give a new folder)");
  return o;
}

template <class T>
void run_precision(const std::string& model, const std::vector<double>& params,
                   const gpu::QuerySet& queries, const Options& o, const fs::path& dir,
                   std::vector<gpu::RunRecord>& runs) {
  for (gpu::Function f : {gpu::Function::kEval, gpu::Function::kPdf, gpu::Function::kSample}) {
    gpu::DeviceTiming timing;
    const auto columns = gpu::run_on_device<T>(model, params, f, queries, o.repetitions, &timing);
    gpu::RunRecord run{model, gpu::precision_name<T>(), std::string(gpu::function_name(f)),
                       gpu::output_column_names(model, f), timing};
    gpu::write_output_csv(dir / gpu::output_file_name(run), run.columns, columns, o.rows);
    std::printf("%-18s %-6s %-6s %9.3f ms  %8.1f M rows/s\n", model.c_str(), run.precision.c_str(),
                run.function.c_str(), timing.median_ms, timing.items_per_second * 1e-6);
    runs.push_back(std::move(run));
  }
}

}  // namespace

int main(int argc, char** argv) {
  const Options o = parse(argc, argv);
  const gpu::DeviceInfo device = gpu::find_device();
  if (!device.present) {
    std::fprintf(stderr, "glintlab_gpu_check: error: no CUDA device (%s); nothing written\n",
                 device.why_absent.c_str());
    return 3;
  }
  const fs::path staging = o.out.parent_path() / ("." + o.out.filename().string() + ".partial");
  try {
    fs::remove_all(staging);
    fs::create_directories(staging);
    // Counter-based: the first rows of the timed set are the written set.
    const gpu::QuerySet queries = gpu::make_query_set(o.timing_rows, o.seed);
    gpu::write_query_csv(staging / "queries.csv", queries, o.rows);
    std::vector<gpu::RunRecord> runs;
    for (const gpu::DeviceSupport& s : gpu::kDeviceSupport) {
      if (!s.why_not.empty()) continue;
      const std::string model(s.model);
      const std::vector<double> params = gpu::default_params(model);
      run_precision<float>(model, params, queries, o, staging, runs);
      run_precision<double>(model, params, queries, o, staging, runs);
    }
    // The Table 3 analogue: every cell as a whole 1080p frame (the first --rows pixels kept).
    const std::vector<gpu::Table3FrameRun> frames = gpu::run_table3_frames(o.repetitions, o.rows);
    for (const gpu::Table3FrameRun& f : frames)
      std::printf("%-58s %9.3f ms per frame\n", f.cell.c_str(), f.timing.median_ms);
    gpu::write_table3_pixels_csv(staging / gpu::kTable3PixelsFile, frames);
    gpu::CheckSettings settings{device.name,
                                device.compute_major,
                                device.compute_minor,
                                gpu::cuda_compiler_version(),
                                o.rows,
                                o.timing_rows,
                                o.seed,
                                o.repetitions};
    gpu::write_results_json(staging / "results.json", settings, runs, frames);
    fs::rename(staging, o.out);
  } catch (const std::exception& e) {
    std::error_code ignored;
    fs::remove_all(staging, ignored);
    std::fprintf(stderr, "glintlab_gpu_check: error: %s\n", e.what());
    return 1;
  }
  std::printf("wrote %s\n", o.out.c_str());
  return 0;
}
