// Google Benchmark JSON rows for the figures (bench_json.h), parsed with nlohmann/json.
#include "experiments/figures/bench_json.h"

#include <fmt/format.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <stdexcept>

namespace glintlab::experiments {

std::optional<std::vector<BenchRow>> read_bench_json(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) return std::nullopt;
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw std::runtime_error(
        fmt::format("benchmark JSON '{}' does not parse ({})", path.string(), e.what()));
  }
  if (!j.contains("benchmarks") || !j["benchmarks"].is_array())
    throw std::runtime_error(
        fmt::format("benchmark JSON '{}' has no \"benchmarks\" array", path.string()));
  static const std::set<std::string> kFields = {"family_index",     "per_family_instance_index",
                                                "repetitions",      "repetition_index",
                                                "threads",          "iterations",
                                                "real_time",        "cpu_time",
                                                "items_per_second", "bytes_per_second"};
  const auto to_ns = [](double t, const std::string& unit) {
    return unit == "s" ? t * 1e9 : unit == "ms" ? t * 1e6 : unit == "us" ? t * 1e3 : t;
  };
  std::vector<BenchRow> iterations, medians;
  for (const auto& b : j["benchmarks"]) {
    const std::string run_type = b.value("run_type", "iteration");
    const std::string aggregate = b.value("aggregate_name", "");
    if (run_type == "aggregate" && aggregate != "median") continue;
    BenchRow r;
    r.name = b.value("run_name", b.value("name", ""));
    r.real_time_ns = to_ns(b.value("real_time", 0.0), b.value("time_unit", "ns"));
    r.items_per_second = b.value("items_per_second", 0.0);
    r.label = b.value("label", "");
    for (const auto& [key, value] : b.items())
      if (value.is_number() && !kFields.count(key)) r.counters[key] = value.get<double>();
    (run_type == "aggregate" ? medians : iterations).push_back(std::move(r));
  }
  if (medians.empty()) return iterations;
  return medians;
}

const BenchRow* find_bench_row(const std::vector<BenchRow>& rows, const std::string& name) {
  for (const BenchRow& r : rows)
    if (r.name == name) return &r;
  return nullptr;
}

BenchSource bench_source(const FigureContext& ctx, std::string_view file) {
  if (ctx.bench_dir.empty()) return {};
  const std::filesystem::path shown =
      ctx.bench_name.empty() ? ctx.bench_dir : std::filesystem::path(ctx.bench_name);
  return {ctx.bench_dir / file, (shown / file).string()};
}

std::string no_bench_data(const BenchSource& s, std::string_view file, std::string_view tool) {
  const std::string why =
      s.path.empty()
          ? std::string(
                "no benchmark folder was given (`glintlab figure --bench-from DIR`, or the "
                "report's bench part)")
          : fmt::format("`{}` does not exist", s.shown_as);
  return fmt::format(
      "No benchmark data: {}; make it with `build/release/experiments/bench/{} "
      "--benchmark_out=out/bench/{} --benchmark_out_format=json` from the repository root, then "
      "rerun this figure with `--bench-from out/bench`.",
      why, tool, file);
}

}  // namespace glintlab::experiments
