// `glintlab merge DIR... --out DIR`: joins the folders of a sharded run (verify, figure, compare,
// sweep or adequacy --shard K/N; the subcommand is read from the shards' shard.json) into the
// files one unsharded run writes, the same bytes apart from the timing fields. For verify: the
// rows in the run's order and the suite's Holm–Šidák adjustment computed here over every shard's
// p-values; for figure: each figure's folder, copied from the shard that ran it; for compare and
// sweep: the models' entries in the run's order, with the page drawn from them or the models'
// folders of maps; for adequacy: the table and its maps written from every shard's cells
// (cli/shard_merge.h). Every shard
// must be there exactly once and belong to the same run (command, version, budget and selection),
// and every item of the selection must be covered by exactly one shard; otherwise one error line
// names the folder, and nothing is written.
#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "cli/input.h"
#include "cli/shard.h"
#include "cli/shard_merge.h"
#include "cli/verify_output.h"
#include "verify/results_read.h"

namespace glintlab::cli {
namespace {

namespace fs = std::filesystem;

struct MergeOptions {
  std::vector<std::string> dirs;
  std::string out;
};

std::string read_text(const fs::path& p) {
  std::ifstream in(p);
  if (!in) throw InputError(fmt::format("merge: cannot read {}", p.string()));
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// What the subcommand's selection is made of.
std::string items_of(const std::string& command) {
  return command == "verify"     ? "claims"
         : command == "figure"   ? "figures"
         : command == "adequacy" ? "cells"
                                 : "models";
}

// The field where manifest `m` of `dir` differs from the first shard's, or empty.
std::string foreign_field(const ShardManifest& first, const ShardManifest& m) {
  if (m.command != first.command)
    return fmt::format("command {} (not {})", m.command, first.command);
  if (m.version != first.version)
    return fmt::format("glintlab version {} (not {})", m.version, first.version);
  if (m.budget != first.budget) return fmt::format("budget {} (not {})", m.budget, first.budget);
  if (m.shard.n != first.shard.n)
    return fmt::format("{} shards (not {})", m.shard.n, first.shard.n);
  if (m.selection_digest != first.selection_digest || m.selection != first.selection)
    return fmt::format("another selection of {} or other options", items_of(first.command));
  return "";
}

// Each figure of the selection exactly once: its folder, <shard>/<id>/, copied to <out>/<id>/
// as one run writes it (through a staging folder beside it, replacing an older one). Every check
// is made before the first copy.
int merge_figures(const MergeOptions& o, const std::vector<ShardManifest>& manifests) {
  const ShardManifest& first = manifests.front();
  std::map<std::string, std::size_t> from;  // figure id -> index in o.dirs
  for (std::size_t i = 0; i < manifests.size(); ++i)
    for (const std::string& id : manifests[i].covered) {
      if (std::find(first.selection.begin(), first.selection.end(), id) == first.selection.end())
        throw InputError(
            fmt::format("merge: '{}' covers '{}', which its run's selection lacks", o.dirs[i], id));
      const auto [at, added] = from.emplace(id, i);
      if (!added)
        throw InputError(fmt::format("merge: '{}' is in two shards ('{}' and '{}')", id,
                                     o.dirs[at->second], o.dirs[i]));
      std::error_code ec;
      if (!fs::is_directory(fs::path(o.dirs[i]) / id, ec))
        throw InputError(
            fmt::format("merge: '{}' lacks the folder of '{}', which its shard.json "
                        "lists",
                        o.dirs[i], id));
    }
  for (const std::string& id : first.selection)
    if (!from.count(id)) throw InputError(fmt::format("merge: no shard holds the figure '{}'", id));
  std::error_code ec;
  fs::create_directories(o.out, ec);
  if (ec)
    throw InputError(fmt::format("--out: cannot create directory '{}': {}", o.out, ec.message()));
  register_staging_parent(o.out);
  for (const std::string& id : first.selection) {
    const fs::path target = fs::path(o.out) / id;
    const fs::path staging = fs::path(o.out) / fmt::format(".{}.tmp.{}", id, ::getpid());
    fs::remove_all(staging, ec);
    fs::copy(fs::path(o.dirs[from[id]]) / id, staging, fs::copy_options::recursive, ec);
    if (!ec) fs::remove_all(target, ec);
    if (!ec) fs::rename(staging, target, ec);
    if (ec) {
      const std::string why = ec.message();
      fs::remove_all(staging, ec);
      throw InputError(fmt::format("--out: cannot write '{}': {}", target.string(), why));
    }
    fmt::print("{}: wrote {}\n", id, target.string());
  }
  return 0;
}

int run(const MergeOptions& o) {
  if (o.dirs.empty())
    throw InputError(
        "merge: no shard folder given (valid: the --out folders of glintlab verify, "
        "figure, compare, sweep or adequacy --shard K/N, one per K)");
  check_output_dir(o.out, "--out");
  std::vector<ShardManifest> manifests;
  for (const std::string& d : o.dirs) manifests.push_back(read_manifest(d));
  const ShardManifest& first = manifests.front();
  if (first.command != "verify" && first.command != "figure" && first.command != "compare" &&
      first.command != "sweep" && first.command != "adequacy")
    throw InputError(fmt::format(
        "merge: '{}' is a shard of {} (valid: verify, figure, compare, sweep, adequacy)",
        o.dirs.front(), first.command));
  std::map<std::uint64_t, std::size_t> by_shard;  // K -> index in o.dirs
  for (std::size_t i = 0; i < manifests.size(); ++i) {
    const std::string why = foreign_field(first, manifests[i]);
    if (!why.empty())
      throw InputError(fmt::format("merge: '{}' belongs to another run than '{}': {}", o.dirs[i],
                                   o.dirs.front(), why));
    const auto [at, added] = by_shard.emplace(manifests[i].shard.k, i);
    if (!added)
      throw InputError(fmt::format("merge: shard {}/{} is given twice ('{}' and '{}')",
                                   manifests[i].shard.k, first.shard.n, o.dirs[at->second],
                                   o.dirs[i]));
  }
  for (std::uint64_t k = 1; k <= first.shard.n; ++k)
    if (!by_shard.count(k))
      throw InputError(fmt::format("merge: shard {}/{} is missing (given: {})", k, first.shard.n,
                                   fmt::join(o.dirs, ", ")));

  if (first.command == "figure") return merge_figures(o, manifests);
  if (first.command == "compare") {
    merge_compare_shards(o.dirs, manifests, o.out);
    return 0;
  }
  if (first.command == "sweep") {
    merge_sweep_shards(o.dirs, manifests, o.out);
    return 0;
  }
  if (first.command == "adequacy") {
    merge_adequacy_shards(o.dirs, manifests, o.out);
    return 0;
  }

  // Every row of the selection exactly once, each from the shard that covers it.
  const verify::Budget budget =
      first.budget == "full" ? verify::Budget::kFull : verify::Budget::kQuick;
  std::map<std::string, verify::RunRecord> rows;
  std::map<std::string, std::string> from;
  for (std::size_t i = 0; i < manifests.size(); ++i) {
    const fs::path file = fs::path(o.dirs[i]) / "claims.json";
    std::vector<verify::RunRecord> records;
    try {
      records = verify::read_records(read_text(file), budget, file.string());
    } catch (const std::invalid_argument& e) {
      throw InputError(fmt::format("merge: {}", e.what()));
    }
    std::vector<std::string> ids;
    for (const verify::RunRecord& r : records) ids.push_back(r.check->id);
    if (ids != manifests[i].covered)
      throw InputError(
          fmt::format("merge: {} does not hold the rows its shard.json lists", file.string()));
    for (verify::RunRecord& r : records) {
      const std::string id = r.check->id;
      if (from.count(id))
        throw InputError(
            fmt::format("merge: '{}' is in two shards ('{}' and '{}')", id, from[id], o.dirs[i]));
      from[id] = o.dirs[i];
      rows.emplace(id, std::move(r));
    }
  }
  std::vector<verify::RunRecord> records;
  for (const std::string& id : first.selection) {
    auto it = rows.find(id);
    if (it == rows.end())
      throw InputError(fmt::format("merge: no shard holds the row of '{}'", id));
    records.push_back(std::move(it->second));
  }
  std::error_code ec;
  fs::create_directories(o.out, ec);
  if (ec)
    throw InputError(fmt::format("--out: cannot create directory '{}': {}", o.out, ec.message()));
  const verify::RunInfo info{first.budget, first.threads, first.machine};
  return write_verify_run(records, info, o.out);
}

}  // namespace

void add_merge_command(CLI::App& app) {
  auto o = std::make_shared<MergeOptions>();
  CLI::App* cmd = add_command(
      app, "merge",
      "Join the folders of a sharded run (glintlab verify, figure, compare, sweep or adequacy "
      "--shard K/N --out DIR, one folder per K; the subcommand is read from their shard.json) "
      "into the files one unsharded run writes, the same bytes apart from the timing fields. "
      "verify: claims.json, "
      "claims.csv and claims.md, the suite's Holm–Šidák adjustment computed over every shard's "
      "p-values; prints the verdict table; exit status as verify's (0 as recorded, 1 a verdict "
      "differs, 3 a check could not run). figure: each figure's folder, <out>/<id>/. compare: "
      "compare.json, compare.csv, equal_time.csv, equal_time.png and index.html. sweep: "
      "stability.json and each model's folder of maps. adequacy: adequacy.csv, adequacy.json and "
      "the maps. Exit 2 on bad "
      "input: a missing, repeated or foreign shard, named, and nothing written");
  add_positional_list(cmd, "dirs", o->dirs, "the shards' folders, in any order", "DIR...");
  set_required(add_text_option(cmd, "--out", o->out, "output folder", "DIR"));
  set_callback(cmd, [o] {
    const int rc = run(*o);
    if (rc != 0) exit_with_code(rc);
  });
}

}  // namespace glintlab::cli
