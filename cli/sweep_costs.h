// What each registered model's stability sweep costs to run, measured: the weights `glintlab sweep
// --shard K/N` balances its shards by (cli/shard_plan.h). Measured rather than derived from a
// model's grid, because a cell of one model costs many of another's (a Kemppinen evaluation sums
// 32 points of a point process, a smooth one evaluates a formula).
#pragma once

#include <string_view>
#include <vector>

namespace glintlab::cli {

struct SweepCost {
  std::string_view model;
  double quick_seconds;  // CPU seconds of `glintlab sweep --models M --budget quick --threads 1`
  double full_seconds;   // the same at --budget full
};

// One row per registered model (tests/cli/sweep_shard_test.cpp checks that none is missing).
const std::vector<SweepCost>& sweep_costs();

// The model's sweep cost at the budget; a model without a row (a plug-in's, a numpy model's) costs
// the mean of the rows, so that it still gets a share.
double sweep_cost_seconds(std::string_view model, bool quick);

}  // namespace glintlab::cli
