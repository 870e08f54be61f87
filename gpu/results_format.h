// The device check's results folder (gpu/gpu_check.cpp writes it, the CPU comparison reads it):
// file names, and writers that need nothing but the C and C++ standard libraries (the GPU machine
// has no other). Numbers are written in the shortest form that reads back to the same bits
// (%.9g for float, %.17g for double), so a comparison sees the device's exact results.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "gpu/device_timing.h"
#include "gpu/query_set.h"
#include "gpu/table3_frame.h"

namespace glintlab::gpu {

// The query set's seed: the folder records it, so another seed is a different run.
inline constexpr std::uint64_t kQuerySeed = 0x6770755f636865ULL;

template <class T>
constexpr const char* precision_name() {
  return sizeof(T) == 4 ? "float" : "double";
}

struct RunRecord {
  std::string model, precision, function;  // function: eval, pdf or sample
  std::vector<std::string> columns;        // the output columns, in file order
  DeviceTiming timing;
};

struct CheckSettings {
  std::string device;  // the CUDA device's name
  int compute_major = 0, compute_minor = 0;
  std::string cuda_version;     // the toolkit the kernels were compiled with
  std::size_t rows = 0;         // rows written (the first of the timed set)
  std::size_t timing_rows = 0;  // rows of each timed launch
  std::uint64_t seed = 0;
  int repetitions = 0;
};

// "<model>.<precision>.<function>.csv"
std::string output_file_name(const RunRecord& run);

// queries.csv: the header (kQueryLayout's names, then u1, u2) and the first `rows` queries.
void write_query_csv(const std::filesystem::path& path, const QuerySet& queries, std::size_t rows);
// The first `rows` rows of a device run's output columns (columns[k][i]) under the header `names`.
template <class T>
void write_output_csv(const std::filesystem::path& path, const std::vector<std::string>& names,
                      const std::vector<std::vector<T>>& columns, std::size_t rows);
// table3_pixels.csv: cell (the index into results.json's "table3"), pixel, radiance.
inline constexpr const char* kTable3PixelsFile = "table3_pixels.csv";
void write_table3_pixels_csv(const std::filesystem::path& path,
                             const std::vector<Table3FrameRun>& frames);
// results.json: the settings, every run with its columns and timing, every Table 3 frame's timing.
void write_results_json(const std::filesystem::path& path, const CheckSettings& settings,
                        const std::vector<RunRecord>& runs,
                        const std::vector<Table3FrameRun>& frames);

}  // namespace glintlab::gpu
