// Claims' costs and verify's shard plan; see claim_costs.h.
#include "cli/claim_costs.h"

#include <fmt/format.h>

#include <algorithm>

#include "cli/shard_plan.h"

namespace glintlab::cli {
namespace {

// Claims decided on one measurement that a process makes once and keeps (a static cache in
// verify/claims/): the first to run pays for it and the others' recorded seconds are near zero,
// so in different shards each would measure again. Each group is one unit of the plan, in the
// shard of its members' summed cost. tests/verify/registry_test.cpp runs the same groups together.
const std::vector<std::vector<std::string_view>>& shared_measurements() {
  static const std::vector<std::vector<std::string_view>> kGroups = {
      // The stability sweep of every registered model (verify/claims/across/common.h suite_sweeps).
      {"all.stability", "all.energy-gain", "all.probability", "all.variance"},
      // The GGAA renders' replicates (verify/claims/chermain/common.h replicate).
      {"chermain.ggaa-error", "chermain.ggaa-shimmer"},
      // The normal-mapped tubes' replicates (the same header's BumpyGgaaReplicate replicate).
      {"chermain.ggaa-derivatives", "chermain.ggaa-sk"},
  };
  return kGroups;
}

double recorded_at(const ClaimCost& c, bool quick) {
  return quick ? c.quick_seconds : c.full_seconds;
}

// The defaults of claim_cost for a claim without a row at a budget.
struct Defaults {
  double quick_per_full = 1, full_per_quick = 1;  // ratio of the totals recorded at both
  double mean_quick = 1, mean_full = 1;           // mean of the rows recorded at a budget
};

Defaults defaults() {
  double both_quick = 0, both_full = 0, sum_quick = 0, sum_full = 0;
  std::size_t n_quick = 0, n_full = 0;
  for (const ClaimCost& c : claim_costs()) {
    const bool q = c.quick_seconds >= 0, f = c.full_seconds >= 0;
    if (q) sum_quick += c.quick_seconds, ++n_quick;
    if (f) sum_full += c.full_seconds, ++n_full;
    if (q && f) both_quick += c.quick_seconds, both_full += c.full_seconds;
  }
  Defaults d;
  if (both_quick > 0 && both_full > 0) {
    d.quick_per_full = both_quick / both_full;
    d.full_per_quick = both_full / both_quick;
  }
  if (n_quick > 0) d.mean_quick = sum_quick / double(n_quick);
  if (n_full > 0) d.mean_full = sum_full / double(n_full);
  return d;
}

}  // namespace

ClaimCostEstimate claim_cost(std::string_view id, bool quick) {
  static const Defaults d = defaults();
  const std::vector<ClaimCost>& costs = claim_costs();
  const auto it =
      std::find_if(costs.begin(), costs.end(), [&](const ClaimCost& c) { return c.id == id; });
  if (it == costs.end()) return {quick ? d.mean_quick : d.mean_full, false};
  if (recorded_at(*it, quick) >= 0) return {recorded_at(*it, quick), true};
  if (recorded_at(*it, !quick) >= 0)
    return {recorded_at(*it, !quick) * (quick ? d.quick_per_full : d.full_per_quick), false};
  return {quick ? d.mean_quick : d.mean_full, false};
}

std::vector<std::size_t> shared_measurement_leaders(const std::vector<std::string>& ids) {
  std::vector<std::size_t> leader(ids.size());
  for (std::size_t i = 0; i < ids.size(); ++i) {
    leader[i] = i;
    for (const auto& group : shared_measurements()) {
      if (std::find(group.begin(), group.end(), ids[i]) == group.end()) continue;
      for (std::size_t j = 0; j < i; ++j)
        if (std::find(group.begin(), group.end(), ids[j]) != group.end()) {
          leader[i] = j;
          break;
        }
    }
  }
  return leader;
}

std::vector<std::size_t> claim_shard_positions(const std::vector<std::string>& ids, Shard s,
                                               bool quick, std::vector<ClaimCostEstimate>& costs) {
  costs.clear();
  for (const std::string& id : ids) costs.push_back(claim_cost(id, quick));
  // One unit per claim that leads its group (or has none), costing its members' sum.
  const std::vector<std::size_t> leader = shared_measurement_leaders(ids);
  std::vector<std::size_t> unit_of(ids.size());
  std::vector<double> unit_seconds;
  for (std::size_t i = 0; i < ids.size(); ++i) {
    if (leader[i] == i) {
      unit_of[i] = unit_seconds.size();
      unit_seconds.push_back(0.0);
    } else {
      unit_of[i] = unit_of[leader[i]];
    }
    unit_seconds[unit_of[i]] += costs[i].seconds;
  }
  const std::vector<std::size_t> units = cost_balanced_positions(unit_seconds, s);
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i < ids.size(); ++i)
    if (std::binary_search(units.begin(), units.end(), unit_of[i])) out.push_back(i);
  return out;
}

void print_claim_shard_plan(const std::vector<std::string>& ids, Shard s, bool quick) {
  std::vector<ClaimCostEstimate> costs;
  const std::vector<std::size_t> mine = claim_shard_positions(ids, s, quick, costs);
  const std::vector<std::size_t> leader = shared_measurement_leaders(ids);
  double total = 0, shard_total = 0;
  for (const ClaimCostEstimate& c : costs) total += c.seconds;
  for (std::size_t i : mine) {
    fmt::print("{:<44} {:g} s{}{}\n", ids[i], costs[i].seconds,
               costs[i].recorded ? "" : " (estimated: no recorded row at this budget)",
               leader[i] == i ? "" : fmt::format(" (shares {}'s measurement)", ids[leader[i]]));
    shard_total += costs[i].seconds;
  }
  fmt::print(
      "shard {}/{}: {} of {} claims, {:g} s of {:g} s recorded at --budget {} "
      "(cli/claim_costs_table.cpp)\n",
      s.k, s.n, mine.size(), ids.size(), shard_total, total, quick ? "quick" : "full");
}

}  // namespace glintlab::cli
