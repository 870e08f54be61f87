// Greedy longest-first assignment of items to shards; see shard_plan.h.
#include "cli/shard_plan.h"

#include <algorithm>
#include <numeric>

namespace glintlab::cli {

std::vector<std::size_t> cost_balanced_positions(const std::vector<double>& costs, Shard s) {
  std::vector<std::size_t> order(costs.size());
  std::iota(order.begin(), order.end(), std::size_t(0));
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return costs[a] > costs[b]; });
  const std::size_t n = std::size_t(s.n);
  std::vector<double> load(n, 0.0);
  std::vector<std::size_t> out;
  for (std::size_t item : order) {
    // The first shard with the least load: min_element returns the first of equal minima.
    const std::size_t to = std::size_t(std::min_element(load.begin(), load.end()) - load.begin());
    load[to] += costs[item];
    if (to + 1 == std::size_t(s.k)) out.push_back(item);
  }
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace glintlab::cli
