#include "gpu/results_format.h"

#include <algorithm>
#include <cstdio>
#include <memory>
#include <stdexcept>

#include "core/model_layout.h"

namespace glintlab::gpu {
namespace {

using File = std::unique_ptr<std::FILE, int (*)(std::FILE*)>;

File open_for_writing(const std::filesystem::path& path) {
  File f(std::fopen(path.c_str(), "w"), &std::fclose);
  if (!f) throw std::runtime_error("cannot write " + path.string());
  return f;
}

void close(File& f, const std::filesystem::path& path) {
  if (std::fclose(f.release()) != 0) throw std::runtime_error("cannot write " + path.string());
}

void put(std::FILE* f, float v) { std::fprintf(f, "%.9g", static_cast<double>(v)); }
void put(std::FILE* f, double v) { std::fprintf(f, "%.17g", v); }

std::string json_string(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    if (static_cast<unsigned char>(c) < 0x20) continue;  // a device name has no control characters
    out += c;
  }
  return out + "\"";
}

}  // namespace

std::string output_file_name(const RunRecord& run) {
  return run.model + "." + run.precision + "." + run.function + ".csv";
}

void write_query_csv(const std::filesystem::path& path, const QuerySet& queries, std::size_t rows) {
  File f = open_for_writing(path);
  for (const QueryColumn& c : kQueryLayout)
    std::fprintf(f.get(), "%.*s,", int(c.name.size()), c.name.data());
  std::fprintf(f.get(), "u1,u2\n");
  for (std::size_t i = 0; i < std::min(rows, queries.rows); ++i) {
    for (const auto& column : queries.columns) {
      put(f.get(), column[i]);
      std::fputc(',', f.get());
    }
    put(f.get(), queries.u1[i]);
    std::fputc(',', f.get());
    put(f.get(), queries.u2[i]);
    std::fputc('\n', f.get());
  }
  close(f, path);
}

template <class T>
void write_output_csv(const std::filesystem::path& path, const std::vector<std::string>& names,
                      const std::vector<std::vector<T>>& columns, std::size_t rows) {
  if (names.size() != columns.size())
    throw std::logic_error("write_output_csv: " + std::to_string(names.size()) + " names for " +
                           std::to_string(columns.size()) + " columns");
  File f = open_for_writing(path);
  for (std::size_t k = 0; k < names.size(); ++k)
    std::fprintf(f.get(), "%s%c", names[k].c_str(), k + 1 < names.size() ? ',' : '\n');
  if (!columns.empty()) rows = std::min(rows, columns[0].size());
  for (std::size_t i = 0; i < rows; ++i)
    for (std::size_t k = 0; k < columns.size(); ++k) {
      put(f.get(), columns[k][i]);
      std::fputc(k + 1 < columns.size() ? ',' : '\n', f.get());
    }
  close(f, path);
}
template void write_output_csv<float>(const std::filesystem::path&, const std::vector<std::string>&,
                                      const std::vector<std::vector<float>>&, std::size_t);
template void write_output_csv<double>(const std::filesystem::path&,
                                       const std::vector<std::string>&,
                                       const std::vector<std::vector<double>>&, std::size_t);

void write_table3_pixels_csv(const std::filesystem::path& path,
                             const std::vector<Table3FrameRun>& frames) {
  File f = open_for_writing(path);
  std::fprintf(f.get(), "cell,pixel,radiance\n");
  for (std::size_t c = 0; c < frames.size(); ++c)
    for (std::size_t i = 0; i < frames[c].pixels.size(); ++i) {
      std::fprintf(f.get(), "%zu,%llu,", c, static_cast<unsigned long long>(frames[c].pixels[i]));
      put(f.get(), frames[c].radiance[i]);
      std::fputc('\n', f.get());
    }
  close(f, path);
}

void write_results_json(const std::filesystem::path& path, const CheckSettings& settings,
                        const std::vector<RunRecord>& runs,
                        const std::vector<Table3FrameRun>& frames) {
  File f = open_for_writing(path);
  std::FILE* o = f.get();
  std::fprintf(o, "{\n  \"device\": %s,\n  \"compute_capability\": \"%d.%d\",\n",
               json_string(settings.device).c_str(), settings.compute_major,
               settings.compute_minor);
  std::fprintf(o, "  \"cuda_version\": %s,\n  \"rows\": %zu,\n  \"timing_rows\": %zu,\n",
               json_string(settings.cuda_version).c_str(), settings.rows, settings.timing_rows);
  std::fprintf(o, "  \"seed\": %llu,\n", static_cast<unsigned long long>(settings.seed));
  std::fprintf(o, "  \"repetitions\": %d,\n  \"runs\": [", settings.repetitions);
  for (std::size_t r = 0; r < runs.size(); ++r) {
    const RunRecord& run = runs[r];
    std::fprintf(o, "%s\n    {\"model\": %s, \"precision\": %s, \"function\": %s, \"file\": %s,",
                 r == 0 ? "" : ",", json_string(run.model).c_str(),
                 json_string(run.precision).c_str(), json_string(run.function).c_str(),
                 json_string(output_file_name(run)).c_str());
    std::fprintf(o, " \"columns\": [");
    for (std::size_t k = 0; k < run.columns.size(); ++k)
      std::fprintf(o, "%s%s", k == 0 ? "" : ", ", json_string(run.columns[k]).c_str());
    std::fprintf(o, "],\n     \"median_ms\": %.6g, \"min_ms\": %.6g, \"rows_per_second\": %.6g}",
                 run.timing.median_ms, run.timing.min_ms, run.timing.items_per_second);
  }
  std::fprintf(o, "\n  ],\n  \"table3_pixels\": %s,\n  \"table3\": [",
               json_string(kTable3PixelsFile).c_str());
  for (std::size_t c = 0; c < frames.size(); ++c)
    std::fprintf(o,
                 "%s\n    {\"cell\": %s, \"median_ms\": %.6g, \"min_ms\": %.6g, "
                 "\"pixels_per_second\": %.6g}",
                 c == 0 ? "" : ",", json_string(frames[c].cell).c_str(), frames[c].timing.median_ms,
                 frames[c].timing.min_ms, frames[c].timing.items_per_second);
  std::fprintf(o, "\n  ]\n}\n");
  close(f, path);
}

}  // namespace glintlab::gpu
