#include "gpu/cpu_comparison.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "core/model_layout.h"
#include "core/model_registry.h"
#include "core/simd/model_batch.h"
#include "experiments/bench/kemppinen2025_table3_scene.h"
#include "gpu/results_format.h"

namespace glintlab::gpu {
namespace {

namespace fs = std::filesystem;

struct Csv {
  std::vector<std::string> header;
  std::vector<std::vector<double>> columns;  // columns[k][i]
};

Csv read_csv(const fs::path& path) {
  std::ifstream in(path);
  if (!in) throw ResultsError(path.string() + ": cannot be read");
  Csv csv;
  std::string line;
  if (!std::getline(in, line)) throw ResultsError(path.string() + ": empty (no header)");
  std::stringstream names(line);
  for (std::string name; std::getline(names, name, ',');) csv.header.push_back(name);
  csv.columns.resize(csv.header.size());
  std::size_t row = 0;
  while (std::getline(in, line)) {
    ++row;
    const char* p = line.c_str();
    for (std::size_t k = 0; k < csv.header.size(); ++k) {
      char* end = nullptr;
      const double v = std::strtod(p, &end);
      const char expected = k + 1 < csv.header.size() ? ',' : '\0';
      if (end == p || *end != expected)
        throw ResultsError(path.string() + ": row " + std::to_string(row) + ", column '" +
                           csv.header[k] + "' is not a number followed by '" +
                           (expected == ',' ? "," : "the end of the line") + "'");
      csv.columns[k].push_back(v);
      p = end + (expected == ',' ? 1 : 0);
    }
  }
  return csv;
}

const std::vector<double>& column(const Csv& csv, const std::string& name, const fs::path& path) {
  const auto it = std::find(csv.header.begin(), csv.header.end(), name);
  if (it == csv.header.end()) throw ResultsError(path.string() + ": no column '" + name + "'");
  return csv.columns[static_cast<std::size_t>(it - csv.header.begin())];
}

// The CPU's columns for one run (eval: value, pdf, intermediates; pdf: eval's pdf column;
// sample: the kSampleColumns), in precision T, on the folder's queries.
template <class T>
std::vector<std::vector<double>> cpu_columns(const ModelEntry& m, const std::string& function,
                                             const Csv& queries, const fs::path& qpath) {
  const std::size_t n = queries.columns.empty() ? 0 : queries.columns[0].size();
  std::vector<std::vector<T>> query(kQueryLayout.size(), std::vector<T>(n));
  std::vector<simd::Column<T>> query_columns;
  for (std::size_t k = 0; k < kQueryLayout.size(); ++k) {
    const auto& c = column(queries, std::string(kQueryLayout[k].name), qpath);
    std::transform(c.begin(), c.end(), query[k].begin(),
                   [](double v) { return static_cast<T>(v); });
    query_columns.push_back({query[k].data(), 1});
  }
  const std::vector<double> params = resolve_params(m, {});
  const bool sample = function == "sample";
  const std::size_t count = sample ? simd::kSampleColumns.size() : 2 + m.intermediates.size();
  std::vector<std::vector<T>> out(count, std::vector<T>(n));
  std::vector<T*> outputs;
  for (auto& o : out) outputs.push_back(o.data());
  if (sample) {
    std::vector<T> u1(n), u2(n);
    const auto& c1 = column(queries, "u1", qpath);
    const auto& c2 = column(queries, "u2", qpath);
    std::transform(c1.begin(), c1.end(), u1.begin(), [](double v) { return static_cast<T>(v); });
    std::transform(c2.begin(), c2.end(), u2.begin(), [](double v) { return static_cast<T>(v); });
    simd::sample_batch(m, params, query_columns, {u1.data(), 1}, {u2.data(), 1}, outputs, n,
                       simd::Isa::kScalar);
  } else {
    simd::eval_batch(m, params, query_columns, outputs, n, simd::Isa::kScalar);
  }
  if (function == "pdf") out = {out[1]};
  std::vector<std::vector<double>> wide;
  for (const auto& o : out) wide.emplace_back(o.begin(), o.end());
  return wide;
}

ColumnComparison compare_column(const std::string& name, const std::vector<double>& cpu,
                                const std::vector<double>& gpu, ComparisonBudget budget) {
  ColumnComparison c;
  c.column = name;
  double largest = 0;
  for (double v : cpu)
    if (std::isfinite(v)) largest = std::max(largest, std::fabs(v));
  const double floor = std::max(budget.floor_of_max * largest, 1e-300);
  for (std::size_t i = 0; i < cpu.size(); ++i) {
    const double a = cpu[i], b = gpu[i];
    double d = 0;
    if (std::isnan(a) || std::isnan(b)) {
      d = std::isnan(a) && std::isnan(b) ? 0 : INFINITY;
    } else if (std::isinf(a) || std::isinf(b)) {
      d = a == b ? 0 : INFINITY;
    } else {
      d = std::fabs(b - a) / std::max(std::fabs(a), floor);
    }
    if (d > budget.relative) ++c.rows_over;
    if (i == 0 || d > c.max_relative) {
      c.max_relative = d;
      c.worst_row = i;
      c.cpu = a;
      c.gpu = b;
    }
  }
  return c;
}

// The Table 3 frames' pixels (table3_pixels.csv) against shade_pixel on the CPU, cell by cell.
std::vector<RunComparison> compare_frames(const fs::path& folder, const nlohmann::json& table3) {
  namespace t3 = kemppinen_table3;
  const fs::path path = folder / kTable3PixelsFile;
  const Csv pixels = read_csv(path);
  const auto& cell_column = column(pixels, "cell", path);
  const auto& pixel_column = column(pixels, "pixel", path);
  const auto& radiance_column = column(pixels, "radiance", path);
  std::vector<RunComparison> out;
  for (std::size_t index = 0; index < table3.size(); ++index) {
    const std::string name = table3[index].at("cell").get<std::string>();
    const std::vector<t3::Cell> cells = t3::cells();
    const auto cell = std::find_if(cells.begin(), cells.end(),
                                   [&](const t3::Cell& c) { return t3::cell_name(c) == name; });
    if (cell == cells.end())
      throw ResultsError(folder.string() + "/results.json: Table 3 cell '" + name +
                         "' is not a cell of this build");
    std::vector<double> gpu, cpu;
    std::vector<std::uint64_t> which;
    for (std::size_t i = 0; i < cell_column.size(); ++i)
      if (cell_column[i] == double(index)) {
        which.push_back(static_cast<std::uint64_t>(pixel_column[i]));
        gpu.push_back(radiance_column[i]);
      }
    if (which.empty()) throw ResultsError(path.string() + ": no pixel of cell " + name);
    t3::with_cell(*cell, [&](const auto& shade) {
      for (std::uint64_t p : which) cpu.push_back(shade(p));
    });
    RunComparison run;
    run.model = name;
    run.precision = "double";
    run.function = "frame";
    run.columns.push_back(compare_column("radiance", cpu, gpu, kDoubleBudget));
    run.within_budget = run.columns[0].rows_over == 0;
    out.push_back(std::move(run));
  }
  return out;
}

}  // namespace

FolderComparison compare_with_cpu(const fs::path& folder) {
  const fs::path results_path = folder / "results.json";
  std::ifstream in(results_path);
  if (!in) throw ResultsError(results_path.string() + ": cannot be read");
  nlohmann::json results;
  try {
    in >> results;
  } catch (const nlohmann::json::exception& e) {
    throw ResultsError(results_path.string() + ": not JSON (" + e.what() + ")");
  }
  FolderComparison out;
  const fs::path qpath = folder / "queries.csv";
  const Csv queries = read_csv(qpath);
  try {
    out.device = results.at("device").get<std::string>();
    out.cuda_version = results.at("cuda_version").get<std::string>();
    out.rows = results.at("rows").get<std::size_t>();
    const std::size_t got = queries.columns.empty() ? 0 : queries.columns[0].size();
    if (got != out.rows)
      throw ResultsError(qpath.string() + ": " + std::to_string(got) + " rows, results.json says " +
                         std::to_string(out.rows));
    for (const nlohmann::json& r : results.at("runs")) {
      RunComparison run;
      run.model = r.at("model").get<std::string>();
      run.precision = r.at("precision").get<std::string>();
      run.function = r.at("function").get<std::string>();
      if (run.precision != "float" && run.precision != "double")
        throw ResultsError(results_path.string() + ": precision '" + run.precision +
                           "' (valid: float, double)");
      if (run.function != "eval" && run.function != "pdf" && run.function != "sample")
        throw ResultsError(results_path.string() + ": function '" + run.function +
                           "' (valid: eval, pdf, sample)");
      const fs::path path = folder / r.at("file").get<std::string>();
      Csv device = read_csv(path);
      // A float is written with 9 digits, which name it uniquely but read back as a nearby
      // double: round to float again for its exact value.
      if (run.precision == "float")
        for (auto& c : device.columns)
          for (double& v : c) v = static_cast<double>(static_cast<float>(v));
      const ModelEntry* m = nullptr;
      for (const ModelEntry& e : registered_models())
        if (e.name == run.model) m = &e;
      if (m == nullptr)
        throw ResultsError(results_path.string() + ": model '" + run.model +
                           "' is not a registered model of this build");
      const bool is_float = run.precision == "float";
      const auto cpu = is_float ? cpu_columns<float>(*m, run.function, queries, qpath)
                                : cpu_columns<double>(*m, run.function, queries, qpath);
      if (device.header.size() != cpu.size())
        throw ResultsError(path.string() + ": " + std::to_string(device.header.size()) +
                           " columns, the CPU batch writes " + std::to_string(cpu.size()));
      for (std::size_t k = 0; k < cpu.size(); ++k) {
        if (device.columns[k].size() != out.rows)
          throw ResultsError(path.string() + ": " + std::to_string(device.columns[k].size()) +
                             " rows, results.json says " + std::to_string(out.rows));
        ColumnComparison c = compare_column(device.header[k], cpu[k], device.columns[k],
                                            is_float ? kFloatBudget : kDoubleBudget);
        if (c.rows_over > 0) run.within_budget = false;
        run.columns.push_back(std::move(c));
      }
      out.within_budget = out.within_budget && run.within_budget;
      out.runs.push_back(std::move(run));
    }
    if (results.contains("table3")) {
      out.frames = compare_frames(folder, results.at("table3"));
      for (const RunComparison& f : out.frames)
        out.within_budget = out.within_budget && f.within_budget;
    }
  } catch (const nlohmann::json::exception& e) {
    throw ResultsError(results_path.string() + ": " + e.what());
  }
  if (out.runs.empty()) throw ResultsError(results_path.string() + ": no runs");
  return out;
}

std::string describe(const FolderComparison& c) {
  std::string s = "device: " + c.device + ", CUDA " + c.cuda_version + ", " +
                  std::to_string(c.rows) + " queries\n";
  char line[512];
  std::snprintf(line, sizeof line, "%-54s %-7s %-8s %-14s %12s %10s %8s\n", "model or Table 3 cell",
                "prec", "function", "column", "max rel diff", "rows over", "verdict");
  s += line;
  std::vector<const RunComparison*> all;
  for (const RunComparison& r : c.runs) all.push_back(&r);
  for (const RunComparison& r : c.frames) all.push_back(&r);
  for (const RunComparison* rp : all)
    for (const ColumnComparison& col : rp->columns) {
      const RunComparison& r = *rp;
      std::snprintf(line, sizeof line, "%-54s %-7s %-8s %-14s %12.3g %10zu %8s\n", r.model.c_str(),
                    r.precision.c_str(), r.function.c_str(), col.column.c_str(), col.max_relative,
                    col.rows_over, r.within_budget ? "within" : "BEYOND");
      s += line;
    }
  s += c.within_budget ? "every run within its budget\n" : "some run beyond its budget\n";
  return s;
}

}  // namespace glintlab::gpu
