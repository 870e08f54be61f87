// What each registered claim costs to check, as recorded: the weights `glintlab verify --shard K/N`
// balances its shards by, with the greedy longest-first assignment of figures (cli/shard_plan.h).
// The seconds are the recorded rows' (docs/data/claims-*.json), compiled into
// cli/claim_costs_table.cpp by scripts/claim_costs.py. Only the balance depends on them, never a
// verdict or a file a run writes.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "cli/shard.h"

namespace glintlab::cli {

// No recorded row at that budget.
inline constexpr double kNotRecorded = -1.0;

struct ClaimCost {
  std::string_view id;
  double quick_seconds;  // the row's seconds in docs/data/claims-quick.json, or kNotRecorded
  double full_seconds;   // the same in docs/data/claims-full.json
};

// One row per claim recorded at either budget (cli/claim_costs_table.cpp, generated).
const std::vector<ClaimCost>& claim_costs();

// A claim's cost at the budget, and whether it was recorded there. Not recorded at this budget but
// at the other: the other's seconds times the ratio of the two budgets' totals over the claims
// recorded at both. Recorded at neither: the mean of the claims recorded at this budget.
struct ClaimCostEstimate {
  double seconds = 0;
  bool recorded = false;
};
ClaimCostEstimate claim_cost(std::string_view id, bool quick);

// For each of `ids` (a run's ordered selection), the position of the first of them that shares
// its measurement (a claim of a group of cli/claim_costs.cpp), or its own.
std::vector<std::size_t> shared_measurement_leaders(const std::vector<std::string>& ids);

// The positions of `ids` that shard s runs, balanced by their costs at the budget, claims that
// share a measurement always in one shard; `costs` gets every id's cost. In selection order.
std::vector<std::size_t> claim_shard_positions(const std::vector<std::string>& ids, Shard s,
                                               bool quick, std::vector<ClaimCostEstimate>& costs);

// `glintlab verify --list --shard K/N --budget B`: the claims shard s would run, each with its cost
// (marked when estimated, and with the claim whose measurement it shares), and the shard's share
// of the selection's total. Runs nothing.
void print_claim_shard_plan(const std::vector<std::string>& ids, Shard s, bool quick);

}  // namespace glintlab::cli
