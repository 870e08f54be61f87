// What each registered figure costs to run, measured: the weights `glintlab figure --shard K/N`
// balances its shards by (cli/shard_plan.h). Measured rather than derived from a figure's pixels
// and samples, because the figures differ in kind (renders, tables of an NDF, fits, timing loops):
// a pixel of one costs a thousand of another.
#pragma once

#include <string_view>
#include <vector>

namespace glintlab::cli {

struct FigureCost {
  std::string_view id;
  double quick_seconds;  // CPU seconds of `glintlab figure ID --budget quick --threads 1`
  double full_seconds;   // the same at --budget full
};

// One row per registered figure (tests/cli/figure_shard_test.cpp checks that none is missing).
const std::vector<FigureCost>& figure_costs();

// The figure's cost at the budget; a figure without a row costs the mean of the rows (so that a
// figure registered before it was measured still gets a share).
double figure_cost_seconds(std::string_view id, bool quick);

}  // namespace glintlab::cli
