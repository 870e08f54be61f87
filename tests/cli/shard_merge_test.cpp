// `glintlab verify --shard K/N` and `glintlab merge`: a run split into N shards balanced by the
// claims' recorded seconds (N = 1, 2, 3 and 7, some shards empty) and merged gives the bytes of one
// unsharded run apart from the timing fields, the suite's Holm–Šidák adjustment included (a
// shard's own adjustment covers only its rows); `verify --list --shard K/N` prints the plan a
// shard runs; a missing, repeated or foreign shard is one error line naming it, and nothing is
// written.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>
#include <string>
#include <vector>

#include "cli/cli_test_util.h"

namespace glintlab::cli_test {
namespace {

namespace fs = std::filesystem;

class ShardMergeTest : public CliTest {
 protected:
  // Six quick claims, three of them with p-values (so that the adjustment spans shards). Their
  // recorded costs (cli/claim_costs_table.cpp) differ: kneiphof.subdivision and
  // podee.brightest-vector cost most.
  static constexpr const char* kClaims =
      "kemppinen.furnace,kemppinen.roulette,kneiphof.subdivision,eto.backfacing-stable-pdf,"
      "kneiphof.cap-probability,podee.brightest-vector";

  RunResult verify(const std::string& out, const std::string& shard = "") const {
    std::vector<std::string> args = {"verify", "--claims", kClaims,  "--budget",
                                     "quick",  "--threads", "2",     "--out", out};
    if (!shard.empty()) args.insert(args.end(), {"--shard", shard});
    return run(args);
  }

  // `verify --claims C --list --shard K/N --budget B`: the ids of the plan, their costs, how many
  // are estimated (no recorded row at the budget), the claim whose measurement each shares (its
  // own id when none), and the summary line's shard total and total.
  struct Plan {
    std::vector<std::string> ids;
    std::vector<double> costs;
    std::vector<std::string> unit;
    int estimated = 0;
    double cost = 0, total = 0;
  };
  Plan plan(const std::string& claims, int k, int n, const std::string& budget) const {
    const RunResult r = run({"verify", "--claims", claims, "--list", "--shard",
                             std::to_string(k) + "/" + std::to_string(n), "--budget", budget});
    EXPECT_EQ(r.exit_code, 0) << r.err;
    Plan p;
    const std::regex item(
        R"(^(\S+) +([0-9.e+-]+) s( \(estimated: no recorded row at this budget\))?)"
        R"((?: \(shares (\S+)'s measurement\))?$)");
    const std::regex summary(
        R"(^shard \d+/\d+: \d+ of \d+ claims, ([0-9.e+-]+) s of ([0-9.e+-]+) s recorded)");
    double listed = 0;
    for (const std::string& line : lines_of(r.out)) {
      std::smatch m;
      if (std::regex_search(line, m, item)) {
        p.ids.push_back(m[1]);
        p.costs.push_back(std::stod(m[2]));
        p.estimated += m[3].matched ? 1 : 0;
        p.unit.push_back(m[4].matched ? m[4].str() : m[1].str());
        listed += p.costs.back();
      } else if (std::regex_search(line, m, summary)) {
        p.cost = std::stod(m[1]);
        p.total = std::stod(m[2]);
      } else {
        ADD_FAILURE() << "unexpected plan line: " << line;
      }
    }
    EXPECT_NEAR(listed, p.cost, 1e-4 * (1 + p.cost));
    return p;
  }

  std::vector<std::string> covered(const std::string& dir) const {
    return nlohmann::json::parse(read_text(path(dir + "/shard.json")))["covered"]
        .get<std::vector<std::string>>();
  }
};

// The timing fields blanked: "seconds" in claims.json, the last column of claims.csv, the time
// column of claims.md.
std::string without_timing(const std::string& file, std::string text) {
  if (file == "claims.json")
    return std::regex_replace(text, std::regex("\"seconds\": [-0-9.e+]+"), "\"seconds\": T");
  if (file == "claims.csv") return std::regex_replace(text, std::regex(",[0-9.]+\n"), ",T\n");
  return std::regex_replace(text, std::regex("\\| [0-9.]+ s \\|"), "| T |");
}

TEST_F(ShardMergeTest, MergedShardsAreTheBytesOfOneRun) {
  ASSERT_EQ(verify("one").exit_code, 0);
  for (int n : {1, 2, 3, 7}) {
    std::vector<std::string> merge = {"merge"};
    std::map<std::string, int> shard_of;  // claim id -> K
    for (int k = n; k >= 1; --k) {        // any order
      const std::string dir = "s" + std::to_string(n) + "_" + std::to_string(k);
      const RunResult r = verify(dir, std::to_string(k) + "/" + std::to_string(n));
      ASSERT_EQ(r.exit_code, 0) << r.err;
      ASSERT_TRUE(fs::exists(path(dir + "/shard.json"))) << dir;
      // The plan that --list --shard prints, running nothing, is what the shard ran.
      EXPECT_EQ(plan(kClaims, k, n, "quick").ids, covered(dir)) << dir;
      for (const std::string& id : covered(dir))
        EXPECT_TRUE(shard_of.emplace(id, k).second) << id << " in two shards of " << n;
      merge.push_back(dir);
    }
    EXPECT_EQ(shard_of.size(), 6u) << n;
    if (n >= 2) {  // balanced by cost, not every N-th: the two costliest never share a shard
      EXPECT_NE(shard_of["kneiphof.subdivision"], shard_of["podee.brightest-vector"]) << n;
    }
    const std::string out = "merged" + std::to_string(n);
    merge.insert(merge.end(), {"--out", out});
    const RunResult r = run(merge);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    for (const char* f : {"claims.json", "claims.csv", "claims.md"})
      EXPECT_EQ(without_timing(f, read_text(path(out + "/" + f))),
                without_timing(f, read_text(path(std::string("one/") + f))))
          << n << " shards: " << f;
    EXPECT_FALSE(fs::exists(path(out + "/shard.json")));
  }
  // With 7 shards of 6 claims one is empty (the 7th: each claim goes to the first shard with the
  // least load). A shard's own adjustment covers its rows only: the merge's is computed over
  // every shard's p-values, as one run's.
  EXPECT_EQ(read_text(path("s7_7/claims.json")), "[]\n");
  EXPECT_TRUE(covered("s7_7").empty());
  auto adjusted = [&](const std::string& file) {
    for (const auto& row : nlohmann::json::parse(read_text(path(file))))
      if (row["id"] == "kemppinen.roulette") return row["suite_adjusted_p_value"].get<double>();
    return -1.0;
  };
  double in_shard = -1;
  for (int k = 1; k <= 3; ++k)
    in_shard = std::max(in_shard, adjusted("s3_" + std::to_string(k) + "/claims.json"));
  ASSERT_GT(in_shard, 0);
  EXPECT_NE(in_shard, adjusted("merged3/claims.json"));
  EXPECT_EQ(adjusted("one/claims.json"), adjusted("merged3/claims.json"));
}

TEST_F(ShardMergeTest, MissingRepeatedOrForeignShardsAreErrorsAndWriteNothing) {
  ASSERT_EQ(verify("a1", "1/2").exit_code, 0);
  ASSERT_EQ(verify("a2", "2/2").exit_code, 0);
  ASSERT_EQ(verify("b1", "1/3").exit_code, 0);
  ASSERT_EQ(verify("one").exit_code, 0);
  const std::set<std::string> before = work_paths();
  expect_input_error(run({"merge", "a1", "--out", "m"}), {"shard 2/2 is missing"}, before);
  expect_input_error(run({"merge", "a1", "a2", "a2", "--out", "m"}),
                     {"shard 2/2 is given twice", "'a2'"}, before);
  expect_input_error(run({"merge", "a1", "a2", "b1", "--out", "m"}),
                     {"'b1' belongs to another run", "3 shards (not 2)"}, before);
  expect_input_error(run({"merge", "a1", "one", "--out", "m"}), {"'one' holds no shard.json"},
                     before);
  expect_input_error(run({"merge", "--out", "m"}), {"no shard folder given"}, before);
  // A shard whose rows are not the ones its manifest lists (edited, or another run's).
  write_text(path("a2/claims.json"), read_text(path("a1/claims.json")));
  expect_input_error(run({"merge", "a1", "a2", "--out", "m"}),
                     {"a2/claims.json does not hold the rows its shard.json lists"}, before);
  for (const char* bad : {"0/2", "3/2", "1/0", "x", "1/"})
    expect_input_error(run({"verify", "--claims", kClaims, "--shard", bad, "--out", "v"}),
                       {"--shard", bad, "K/N"}, before);
  expect_input_error(run({"verify", "--list", "--shard", "0/2"}), {"--shard", "0/2", "K/N"},
                     before);
  expect_input_error(run({"verify", "--list", "--json", "--shard", "1/2"}),
                     {"--shard", "not with --json"}, before);
}

// Every claim of the suite and every conformance check at full in 4 shards: each in exactly one
// shard's plan, the claims that share a measurement in one shard, and the costliest shard within
// Graham's bound for a greedy least-loaded assignment (the mean load plus (1 - 1/N) of the
// costliest unit: a claim, or a group sharing a measurement); the plan writes nothing.
TEST_F(ShardMergeTest, PlanOfEveryClaimCoversEachOnceWithinTheGreedyBound) {
  const int n = 4;
  const std::string every = "*,model.*";
  std::multiset<std::string> ids;
  std::map<std::string, std::set<int>> shards_of_unit;
  double largest_shard = 0, total = 0, sum = 0;
  for (int k = 1; k <= n; ++k) {
    const Plan p = plan(every, k, n, "full");
    ids.insert(p.ids.begin(), p.ids.end());
    for (const std::string& u : p.unit) shards_of_unit[u].insert(k);
    largest_shard = std::max(largest_shard, p.cost);
    total = p.total;
    sum += p.cost;
  }
  for (const auto& [unit, shards] : shards_of_unit) EXPECT_EQ(shards.size(), 1u) << unit;
  const Plan all = plan(every, 1, 1, "full");
  std::map<std::string, double> unit_cost;
  for (std::size_t i = 0; i < all.ids.size(); ++i) unit_cost[all.unit[i]] += all.costs[i];
  double costliest = 0;
  for (const auto& [unit, cost] : unit_cost) costliest = std::max(costliest, cost);
  // The three groups: the stability sweep's four claims and the two Chermain pairs.
  EXPECT_EQ(all.ids.size() - unit_cost.size(), 5u);
  const auto unit_of = [&](const std::string& id) {
    return all.unit.at(
        std::size_t(std::find(all.ids.begin(), all.ids.end(), id) - all.ids.begin()));
  };
  EXPECT_EQ(unit_of("all.variance"), "all.stability");
  EXPECT_EQ(unit_of("chermain.ggaa-sk"), "chermain.ggaa-derivatives");
  EXPECT_EQ(unit_of("chermain.ggaa-shimmer"), "chermain.ggaa-error");
  EXPECT_EQ(ids, std::multiset<std::string>(all.ids.begin(), all.ids.end()));
  EXPECT_EQ(std::set<std::string>(ids.begin(), ids.end()).size(), ids.size());
  EXPECT_NEAR(sum, total, 1e-4 * total);
  EXPECT_LE(largest_shard, total / n + (1 - 1.0 / n) * costliest);
  EXPECT_TRUE(unexpected_files(work(), {}).empty());
}

// Every registered claim has a recorded cost at quick, and every claim of the suite at full
// (cli/claim_costs_table.cpp, generated from docs/data by scripts/claim_costs.py); conformance
// checks without a full row get an estimate, marked in the plan.
TEST_F(ShardMergeTest, EveryClaimHasARecordedCost) {
  const Plan quick = plan("*,model.*", 1, 1, "quick");
  EXPECT_GT(quick.ids.size(), 100u);
  EXPECT_EQ(quick.estimated, 0);
  const Plan suite = plan("*", 1, 1, "full");
  EXPECT_GT(suite.ids.size(), 40u);
  EXPECT_EQ(suite.estimated, 0);
  for (double c : suite.costs) EXPECT_GE(c, 0);
}

}  // namespace
}  // namespace glintlab::cli_test
