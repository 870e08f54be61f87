#include "experiments/adequacy/level_costs.h"

#include <fmt/format.h>

#include <stdexcept>

#include "experiments/figures/bench_json.h"

namespace glintlab::experiments {

LevelCosts read_level_costs(const std::filesystem::path& dir, std::string_view shown_as,
                            std::string_view isa, const std::vector<std::string>& models) {
  const std::filesystem::path path = dir / kLevelCostsFile;
  const std::string shown = (std::filesystem::path(shown_as) / kLevelCostsFile).string();
  const std::string writes = fmt::format(
      "glintlab_bench_glints --benchmark_filter=^adequacy/ --benchmark_out={} "
      "--benchmark_out_format=json",
      shown);
  std::optional<std::vector<BenchRow>> rows;
  try {
    rows = read_bench_json(path);
  } catch (const std::exception& e) {
    throw std::invalid_argument(fmt::format("--bench-from: {}", e.what()));
  }
  if (!rows)
    throw std::invalid_argument(
        fmt::format("--bench-from: no {} (valid: a folder holding it; written by {})", shown,
                    writes));
  LevelCosts c;
  c.source = shown;
  c.isa = std::string(isa);
  for (const std::string& m : models) {
    std::array<double, kBinomialLevels> ns{};
    for (int l = 0; l < kBinomialLevels; ++l) {
      const std::string name =
          fmt::format("adequacy/{}/level={}/{}", m, kBinomialLevelNames[std::size_t(l)], isa);
      const BenchRow* r = find_bench_row(*rows, name);
      if (!r || !(r->ns_per_item() > 0))
        throw std::invalid_argument(fmt::format(
            "--bench-from: {} has no row {} (valid: a file written by {})", shown, name, writes));
      ns[std::size_t(l)] = r->ns_per_item();
    }
    c.ns.emplace(m, ns);
  }
  return c;
}

int cheapest_adequate(const std::array<bool, kBinomialLevels>& adequate,
                      const std::array<double, kBinomialLevels>& ns) {
  int best = int(BinomialLevel::kExact);
  // Ties go to the level earlier in the GPU order (the cheaper one there).
  for (int l = kBinomialLevels - 2; l >= 0; --l)
    if (adequate[std::size_t(l)] && ns[std::size_t(l)] <= ns[std::size_t(best)]) best = l;
  return best;
}

}  // namespace glintlab::experiments
