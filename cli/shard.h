// A run split into shards (`--shard K/N`): shard K of N runs its part of the run's ordered
// selection (verify and figure: balanced by cost, cli/shard_plan.h; compare and sweep: every N-th
// item from the K-th) and writes its rows and a manifest (shard.json) that `glintlab merge` checks
// before it joins the shards into the files of one run.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace glintlab::cli {

struct Shard {
  std::uint64_t k = 1, n = 1;  // shard k of n, 1 <= k <= n
};

// "K/N" with 1 <= K <= N <= kMaxShards; InputError naming `option` otherwise.
inline constexpr std::uint64_t kMaxShards = 10000;
Shard parse_shard(std::string_view text, std::string_view option);

// The positions in a selection of `count` items that shard s runs: k-1, k-1+n, k-1+2n, ...
// (interleaved: compare's and sweep's models, whose costs are not known before they run).
std::vector<std::size_t> shard_positions(std::size_t count, Shard s);

// What a shard's folder records besides its rows: which run it belongs to and what it covers.
struct ShardManifest {
  std::string command;  // the subcommand that ran it ("verify")
  std::string version;  // glintlab's version
  std::string budget;
  std::string selection_digest;    // of the whole run's ordered selection and budget
  std::vector<std::string> selection;  // the whole run's ordered ids
  std::vector<std::string> covered;    // the ids this shard ran, in selection order
  Shard shard;
  int threads = 0;
  std::string machine;
};

std::string selection_digest(std::string_view budget, const std::vector<std::string>& ids);
// This glintlab's version (GLINTLAB_VERSION), recorded in each shard's manifest.
std::string glintlab_version_text();
// shard.json's text, and its reading back (InputError naming `dir` on a malformed one).
std::string to_json(const ShardManifest& m);
ShardManifest read_manifest(const std::filesystem::path& dir);

}  // namespace glintlab::cli
