// Shards balanced by cost: for the subcommands whose items cost very different times (a figure at
// full runs from a second to ten minutes, a claim from a millisecond to thirteen minutes), shard K
// of N runs the items that a greedy longest-first assignment gives it, instead of the every-N-th
// split of compare and sweep (cli/shard.h). The manifest, its checks and `glintlab merge` are the
// same for both: a merge only needs each shard's `covered` items, never how they were chosen.
#pragma once

#include <cstddef>
#include <vector>

#include "cli/shard.h"

namespace glintlab::cli {

// The positions, in selection order, that shard s runs when item i costs costs[i] (any unit, >= 0):
// the items taken costliest first (equal costs: the earlier item first), each given to the shard
// whose items cost least so far (equal sums: the lowest K). Deterministic, and every item is in
// exactly one of the N shards; the costliest shard costs at most 4/3 of the best split's (Graham's
// bound for longest-processing-time-first).
std::vector<std::size_t> cost_balanced_positions(const std::vector<double>& costs, Shard s);

}  // namespace glintlab::cli
