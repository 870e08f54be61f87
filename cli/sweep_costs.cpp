// The measured cost of every registered model's sweep; see sweep_costs.h.
#include "cli/sweep_costs.h"

#include <algorithm>

namespace glintlab::cli {

// CPU seconds (user + system, GNU time, the maps' drawing by matplotlib included) of `glintlab
// sweep --models M --budget B --threads 1`, release build of 2e4e6b5, 2026-12-07, on the shared
// 2-core machine of docs/building.md under load 5-9 (CPU time, not wall time, so that the load
// matters little), one run each. Only the ratios matter: the shards' balance, never a map or a
// verdict, depends on these numbers. Re-measure a row when its model's sweep grid or its
// samplers change.
const std::vector<SweepCost>& sweep_costs() {
  // clang-format off
  static const std::vector<SweepCost> kCosts = {
      // model                    quick    full
      {"smooth_ggx",               5.95,    11.8},
      {"smooth_beckmann",          3.33,    11.7},
      {"podee",                    3.33,    12.1},
      {"deliot_belcour",           4.23,     7.3},
      {"kneiphof_klein",           6.57,    51.6},
      {"kneiphof_klein_area",      3.78,     9.9},
      {"chermain",                 4.48,    11.7},
      {"kemppinen_ggx",            9.23,   107.2},
      {"kemppinen_beckmann",      11.56,   125.8},
  };
  // clang-format on
  return kCosts;
}

double sweep_cost_seconds(std::string_view model, bool quick) {
  const std::vector<SweepCost>& costs = sweep_costs();
  const auto it = std::find_if(costs.begin(), costs.end(),
                               [&](const SweepCost& c) { return c.model == model; });
  if (it != costs.end()) return quick ? it->quick_seconds : it->full_seconds;
  double sum = 0;
  for (const SweepCost& c : costs) sum += quick ? c.quick_seconds : c.full_seconds;
  return costs.empty() ? 1.0 : sum / double(costs.size());
}

}  // namespace glintlab::cli
