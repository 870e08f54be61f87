// Shards of a run and their manifests; see shard.h.
#include "cli/shard.h"

#include <fmt/format.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cli/commands.h"
#include "cli/input.h"
#include "core/math/rng.h"
#include "glintlab/version.h"

namespace glintlab::cli {

using nlohmann::json;

Shard parse_shard(std::string_view text, std::string_view option) {
  const auto slash = text.find('/');
  const std::string valid =
      fmt::format("valid: K/N with 1 <= K <= N <= {}, e.g. 2/4", kMaxShards);
  if (slash == std::string_view::npos)
    throw InputError(fmt::format("{}: '{}' is not K/N ({})", option, text, valid));
  Shard s;
  try {
    s.n = integer_option(text.substr(slash + 1), option, 1, kMaxShards);
    s.k = integer_option(text.substr(0, slash), option, 1, s.n);
  } catch (const InputError&) {
    throw InputError(fmt::format("{}: '{}' is not K/N ({})", option, text, valid));
  }
  return s;
}

std::vector<std::size_t> shard_positions(std::size_t count, Shard s) {
  std::vector<std::size_t> out;
  for (std::size_t i = std::size_t(s.k - 1); i < count; i += std::size_t(s.n)) out.push_back(i);
  return out;
}

std::string selection_digest(std::string_view budget, const std::vector<std::string>& ids) {
  std::string all(budget);
  for (const std::string& id : ids) all += "\n" + id;
  return fmt::format("{:016x}", hash_string(all.c_str()));
}

std::string glintlab_version_text() { return GLINTLAB_VERSION; }

std::string to_json(const ShardManifest& m) {
  const json j = {{"command", m.command},
                  {"glintlab_version", m.version},
                  {"budget", m.budget},
                  {"shard", m.shard.k},
                  {"shards", m.shard.n},
                  {"selection_digest", m.selection_digest},
                  {"selection", m.selection},
                  {"covered", m.covered},
                  {"threads", m.threads},
                  {"machine", m.machine}};
  return j.dump(1) + "\n";
}

ShardManifest read_manifest(const std::filesystem::path& dir) {
  const std::filesystem::path file = dir / "shard.json";
  std::ifstream in(file);
  if (!in)
    throw InputError(fmt::format("merge: '{}' holds no shard.json (a folder written by glintlab "
                                 "verify, figure, compare, sweep or adequacy --shard K/N --out "
                                 "DIR is expected)",
                                 dir.string()));
  std::stringstream text;
  text << in.rdbuf();
  try {
    const json j = json::parse(text.str());
    ShardManifest m;
    m.command = j.at("command").get<std::string>();
    m.version = j.at("glintlab_version").get<std::string>();
    m.budget = j.at("budget").get<std::string>();
    m.shard = {j.at("shard").get<std::uint64_t>(), j.at("shards").get<std::uint64_t>()};
    m.selection_digest = j.at("selection_digest").get<std::string>();
    m.selection = j.at("selection").get<std::vector<std::string>>();
    m.covered = j.at("covered").get<std::vector<std::string>>();
    m.threads = j.at("threads").get<int>();
    m.machine = j.at("machine").get<std::string>();
    if (m.shard.n < 1 || m.shard.k < 1 || m.shard.k > m.shard.n)
      throw InputError(fmt::format("merge: {} names shard {}/{}", file.string(), m.shard.k,
                                   m.shard.n));
    return m;
  } catch (const json::exception& e) {
    throw InputError(fmt::format("merge: {} is not a shard manifest ({})", file.string(), e.what()));
  }
}

}  // namespace glintlab::cli
