// The merges of `glintlab merge` that belong with their subcommand's files: each takes the shards'
// folders and manifests, already checked to be every shard of one run exactly once
// (cli/merge.cpp), checks what the folders hold, and writes into `out` the files one unsharded run
// writes; an InputError naming the folder, with nothing written, otherwise.
#pragma once

#include <string>
#include <vector>

#include "cli/shard.h"

namespace glintlab::cli {

// `glintlab compare --shard K/N` (cli/compare.cpp): compare.json, compare.csv and equal_time.csv
// with every shard's models in the run's order, and the page drawn from them.
void merge_compare_shards(const std::vector<std::string>& dirs,
                          const std::vector<ShardManifest>& manifests, const std::string& out);

// `glintlab sweep --shard K/N` (cli/sweep.cpp): each model's folder of maps, copied from the
// shard that swept it, and stability.json with every target in the run's order.
// `glintlab adequacy --shard K/N` (cli/adequacy.cpp): adequacy.csv, adequacy.json and the maps,
// written from every shard's cells (experiments/adequacy/adequacy_shards.h) as one run writes them.
void merge_adequacy_shards(const std::vector<std::string>& dirs,
                           const std::vector<ShardManifest>& manifests, const std::string& out);

void merge_sweep_shards(const std::vector<std::string>& dirs,
                        const std::vector<ShardManifest>& manifests, const std::string& out);

}  // namespace glintlab::cli
