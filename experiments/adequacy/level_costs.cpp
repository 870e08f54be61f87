#include "experiments/adequacy/level_costs.h"

#include <fmt/format.h>

#include <algorithm>
#include <optional>
#include <stdexcept>

#include "core/glints/adequacy.h"
#include "core/glints/chermain_chooser.h"
#include "core/glints/cost_chooser.h"
#include "core/models/kemppinen_beckmann.h"
#include "core/models/kemppinen_ggx.h"
#include "experiments/figures/bench_json.h"
#include "verify/adequacy/area_adequacy.h"
#include "verify/adequacy/binomial_adequacy.h"
#include "verify/adequacy/chermain_adequacy.h"
#include "verify/adequacy/kemppinen_adequacy.h"

namespace glintlab::experiments {

std::span<const std::string_view> adequacy_level_names(std::string_view model) {
  namespace adq = verify::adequacy;
  const auto in = [&](const auto& models) {
    return std::find(models.begin(), models.end(), model) != models.end();
  };
  if (in(adq::kBinomialFamilyModels) || in(adq::kAreaFamilyModels)) return kBinomialLevelNames;
  if (in(adq::kKemppinenFamilyModels)) return kKemppinenLevelNames;
  if (in(adq::kChermainFamilyModels)) return kChermainLevelNames;
  return {};
}

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
    const std::span<const std::string_view> levels = adequacy_level_names(m);
    if (levels.empty())
      throw std::invalid_argument(
          fmt::format("--bench-from: {} is the model of no adequacy family", m));
    std::vector<double> ns;
    for (std::string_view level : levels) {
      const std::string name = fmt::format("adequacy/{}/level={}/{}", m, level, isa);
      const BenchRow* r = find_bench_row(*rows, name);
      if (!r || !(r->ns_per_item() > 0))
        throw std::invalid_argument(fmt::format(
            "--bench-from: {} has no row {} (valid: a file written by {})", shown, name, writes));
      ns.push_back(r->ns_per_item());
    }
    c.ns.emplace(m, std::move(ns));
  }
  return c;
}

int cheapest_adequate(std::span<const bool> adequate, std::span<const double> ns) {
  const int n = int(std::min(adequate.size(), ns.size()));
  int best = n - 1;
  for (int l = n - 2; l >= 0; --l)
    if (adequate[std::size_t(l)] && ns[std::size_t(l)] <= ns[std::size_t(best)]) best = l;
  return best;
}

namespace {
// The costs as the choosers take them (a file's row count was checked by read_level_costs).
template <std::size_t N>
std::array<double, N> cost_array(std::span<const double> ns) {
  if (ns.size() != N)
    throw std::invalid_argument(fmt::format("{} level costs for a family of {}", ns.size(), N));
  std::array<double, N> a{};
  std::copy(ns.begin(), ns.end(), a.begin());
  return a;
}
}  // namespace

int kemppinen_engine_level_by_cost(const verify::adequacy::KemppinenCell& c, double tau,
                                   std::span<const double> ns) {
  namespace adq = verify::adequacy;
  const auto cost = cost_array<kKemppinenLevels>(ns);
  const ModelQuery<double> q = adq::kemppinen_cell_query(c, adq::kemppinen_surface_position(c, 0));
  const std::vector<double> v = adq::kemppinen_level_param_values(c, KemppinenLevel::kK16Exact, 0);
  const auto level = [&](auto model) {
    using M = decltype(model);
    return int(choose_kemppinen_model_level_by_cost(M::template params<double>(v), q, tau, cost));
  };
  if (c.model == KemppinenGGX::kName) return level(KemppinenGGX{});
  if (c.model == KemppinenBeckmann::kName) return level(KemppinenBeckmann{});
  throw std::invalid_argument(fmt::format("{} is no model of the Kemppinen family", c.model));
}

int chermain_engine_level_by_cost(const verify::adequacy::ChermainCell& c, double tau,
                                  std::span<const double> ns) {
  namespace adq = verify::adequacy;
  const auto p = adq::chermain_level_params(c, adq::kChermainMostComplete, 0);
  return int(choose_chermain_model_level_by_cost(
      p, adq::chermain_cell_query(c, adq::chermain_surface_position(c, 0)), tau,
      cost_array<kChermainLevels>(ns)));
}

}  // namespace glintlab::experiments
