// `glintlab figure IDS --shard K/N` and `glintlab merge`: a selection of figures split into N
// cost-balanced shards (N = 1, 2, 3 and 7, the 7th empty) and merged gives the folders of one
// unsharded run of the selection, byte for byte (none of these figures reports a measured time;
// the charts drawn by matplotlib for N = 2, by a stand-in otherwise);
// a missing, repeated or foreign shard, or a shard without a folder it lists, is one error line
// naming it, and nothing is written.
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

class FigureShardTest : public CliTest {
 protected:
  // Six cheap quick figures (about 1.3 s of CPU together, kneiphof2024-fig10 0.9 s of it), named
  // by ids and a glob: what they compute does not matter to the split and the merge, what their
  // folders hold does (EXRs, montages with their panels, summaries, charts drawn by matplotlib in
  // each shard of 2, a folder of one file: kneiphof2024-table1 without benchmark data). Their
  // measured costs (cli/figure_costs.cpp) differ: kemppinen2025-fig6 and kneiphof2024-fig10 cost
  // most, and every 2nd figure of the selection would put them in one shard.
  static constexpr const char* kFigures =
      "kneiphof2024-fig6,kneiphof2024-fig10,kneiphof2024-table1,kemppinen2025-fig1[45],"
      "kemppinen2025-fig6";
  static inline const std::vector<std::string> kSelection = {
      "kneiphof2024-fig6",  "kneiphof2024-fig10",  "kneiphof2024-table1",
      "kemppinen2025-fig6", "kemppinen2025-fig14", "kemppinen2025-fig15"};

  // Four of them that cost least to run (about 0.4 s of CPU together), for the tests of the
  // merge's checks, which do not depend on what the figures compute.
  static constexpr const char* kCheapFigures =
      "kneiphof2024-fig6,kemppinen2025-fig1[45],kemppinen2025-fig6";

  RunResult figure(const std::string& out, const std::string& shard = "",
                   const std::string& threads = "2", const char* figures = kFigures) const {
    std::vector<std::string> args = {"figure",    figures, "--budget", "quick",
                                     "--threads", threads, "--out",    out};
    if (!shard.empty()) args.insert(args.end(), {"--shard", shard});
    return run(args);
  }

  // `figure IDS --list --shard K/N --budget B`: the ids of the plan and their costs, and the
  // summary line's shard total.
  struct Plan {
    std::vector<std::string> ids;
    std::vector<double> costs;  // of each id
    double cost = 0, total = 0;
  };
  Plan plan(const std::string& ids, int k, int n, const std::string& budget) const {
    const RunResult r = run({"figure", ids, "--list", "--shard",
                             std::to_string(k) + "/" + std::to_string(n), "--budget", budget});
    EXPECT_EQ(r.exit_code, 0) << r.err;
    Plan p;
    const std::regex item(R"(^(\S+) +([0-9.e+-]+) s$)");
    const std::regex summary(
        R"(^shard \d+/\d+: \d+ of \d+ figures, ([0-9.e+-]+) s of ([0-9.e+-]+) s)");
    double listed = 0;
    for (const std::string& line : lines_of(r.out)) {
      std::smatch m;
      if (std::regex_search(line, m, item)) {
        p.ids.push_back(m[1]);
        p.costs.push_back(std::stod(m[2]));
        listed += p.costs.back();
      } else if (std::regex_search(line, m, summary)) {
        p.cost = std::stod(m[1]);
        p.total = std::stod(m[2]);
      } else {
        ADD_FAILURE() << "unexpected plan line: " << line;
      }
    }
    EXPECT_NEAR(listed, p.cost, 1e-6 * (1 + p.cost));
    return p;
  }

  nlohmann::json manifest(const std::string& dir) const {
    return nlohmann::json::parse(read_text(path(dir + "/shard.json")));
  }
};

TEST_F(FigureShardTest, MergedShardsAreTheFoldersOfOneRun) {
  // One unsharded run, its charts drawn by matplotlib. Each N in turn merged and compared with it;
  // the charts drawn by matplotlib for N = 2 (the first pass), by the stand-in
  // (CliTest::stand_in_charts) for the others, whose charts are then compared with the bytes of
  // the one run's chart spec and data (matplotlib draws the same spec and data as the same PNG in
  // any run: the first pass, and
  // FigureChartsTest.SeveralFoldersInOneRunAreTheBytesOfSeparateRunsOrNone).
  ASSERT_EQ(figure("one").exit_code, 0);
  const std::map<std::string, std::string> one = file_tree("one");
  std::set<std::string> folders;
  for (const auto& [file, bytes] : one) folders.insert(file.substr(0, file.find('/')));
  ASSERT_EQ(folders, std::set<std::string>(kSelection.begin(), kSelection.end()));
  // The one run's folders as the stand-in draws them: each chart (a PNG beside its chart spec) the
  // bytes of its spec and its CSV; the other PNGs are drawn by the figures themselves.
  std::map<std::string, std::string> one_stand_in = one;
  for (auto& [file, bytes] : one_stand_in) {
    if (!file.ends_with(".png")) continue;
    const auto spec = one.find(file.substr(0, file.size() - 4) + ".chart.json");
    if (spec == one.end()) continue;
    const std::string folder = file.substr(0, file.rfind('/') + 1);
    bytes = spec->second +
            one.at(folder + nlohmann::json::parse(spec->second).at("csv").get<std::string>());
  }
  const auto check = [&](const std::vector<int>& shard_counts, const std::string& tag,
                         const std::map<std::string, std::string>& expected_tree) {
    for (int n : shard_counts) {
      std::vector<std::string> merge = {"merge"};
      std::map<std::string, int> shard_of;  // figure id -> K
      for (int k = n; k >= 1; --k) {        // any order; shard 1 with one thread
        const std::string dir = "s" + tag + std::to_string(n) + "_" + std::to_string(k);
        const RunResult r =
            figure(dir, std::to_string(k) + "/" + std::to_string(n), k == 1 ? "1" : "2");
        ASSERT_EQ(r.exit_code, 0) << r.err;
        const nlohmann::json m = manifest(dir);
        EXPECT_EQ(m["command"], "figure");
        EXPECT_EQ(m["budget"], "quick");
        EXPECT_EQ(m["shard"], k);
        EXPECT_EQ(m["shards"], n);
        EXPECT_EQ(m["selection"].get<std::vector<std::string>>(), kSelection);
        // The shard's folder holds the folders it lists (in selection order) and shard.json alone.
        std::set<std::string> entries;
        for (const auto& e : fs::directory_iterator(path(dir)))
          entries.insert(e.path().filename().string());
        std::set<std::string> expected = {"shard.json"};
        const auto covered = m["covered"].get<std::vector<std::string>>();
        EXPECT_TRUE(std::is_sorted(covered.begin(), covered.end(), [&](auto& a, auto& b) {
          return std::find(kSelection.begin(), kSelection.end(), a) <
                 std::find(kSelection.begin(), kSelection.end(), b);
        }));
        for (const std::string& id : covered) {
          expected.insert(id);
          EXPECT_TRUE(shard_of.emplace(id, k).second) << id << " in two shards of " << n;
        }
        EXPECT_EQ(entries, expected) << dir;
        // The plan that --list --shard prints, running nothing, is what the shard ran.
        EXPECT_EQ(plan(kFigures, k, n, "quick").ids, covered) << dir;
        merge.push_back(dir);
      }
      EXPECT_EQ(shard_of.size(), kSelection.size()) << n;
      if (n >= 2) {  // cost-balanced, not every N-th: the two costliest never share a shard
        EXPECT_NE(shard_of["kemppinen2025-fig6"], shard_of["kneiphof2024-fig10"]) << n;
      }
      const std::string out = "merged" + tag + std::to_string(n);
      merge.insert(merge.end(), {"--out", out});
      const RunResult r = run(merge);
      ASSERT_EQ(r.exit_code, 0) << r.err;
      EXPECT_TRUE(file_tree(out) == expected_tree)
          << n << " shards: the merged folders differ from one run's";
      EXPECT_FALSE(fs::exists(path(out + "/shard.json")));
    }
  };
  check({2}, "", one);
  // The charts of the first pass were matplotlib's: each with its chart record.
  EXPECT_NE(read_text(path("one/kemppinen2025-fig15/furnace.png")).find("glintlab:chart"),
            std::string::npos);
  EXPECT_NE(one_stand_in, one);
  stand_in_charts();
  check({1, 3, 7}, "_", one_stand_in);
  EXPECT_EQ(read_text(path("merged_1/kemppinen2025-fig15/furnace.png"))
                .rfind(read_text(path("one/kemppinen2025-fig15/furnace.csv"))),
            read_text(path("merged_1/kemppinen2025-fig15/furnace.png")).size() -
                read_text(path("one/kemppinen2025-fig15/furnace.csv")).size());
  // Six figures in 7 shards: one shard ran nothing and holds only its manifest.
  int empty = 0;
  for (int k = 1; k <= 7; ++k)
    empty += manifest("s_7_" + std::to_string(k))["covered"].empty() ? 1 : 0;
  EXPECT_EQ(empty, 1);
}

// The merge's checks, not the figures or their charts, are tested here: the cheapest figures
// (kCheapFigures, each shard of 2 and 3 holding at least one), drawn by the stand-in.
TEST_F(FigureShardTest, MissingRepeatedOrForeignShardsAreErrorsAndWriteNothing) {
  stand_in_charts();
  ASSERT_EQ(figure("a1", "1/2", "2", kCheapFigures).exit_code, 0);
  ASSERT_EQ(figure("a2", "2/2", "2", kCheapFigures).exit_code, 0);
  ASSERT_EQ(figure("b1", "1/3", "2", kCheapFigures).exit_code, 0);
  ASSERT_EQ(run({"figure", "kemppinen2025-fig14,kemppinen2025-fig6", "--budget", "quick", "--shard",
                 "2/2", "--out", "c2"})
                .exit_code,
            0);
  // The same figures with --bench-from: their files may differ, so it is another run.
  fs::create_directory(path("bench"));
  ASSERT_EQ(run({"figure", kCheapFigures, "--budget", "quick", "--bench-from", "bench", "--shard",
                 "2/2", "--out", "d2"})
                .exit_code,
            0);
  // A shard of another subcommand (its manifest edited): the first folder's run decides.
  fs::copy(path("a2"), path("v2"), fs::copy_options::recursive);
  write_text(path("v2/shard.json"),
             std::regex_replace(read_text(path("v2/shard.json")),
                                std::regex("\"command\": \"figure\""), "\"command\": \"verify\""));
  // A shard of a subcommand merge does not join.
  fs::copy(path("a1"), path("u1"), fs::copy_options::recursive);
  write_text(path("u1/shard.json"), std::regex_replace(read_text(path("u1/shard.json")),
                                                       std::regex("\"command\": \"figure\""),
                                                       "\"command\": \"report\""));
  fs::create_directory(path("plain"));  // not a shard
  std::set<std::string> before = work_paths();
  expect_input_error(run({"merge", "a1", "--out", "m"}), {"shard 2/2 is missing"}, before);
  expect_input_error(run({"merge", "a1", "a2", "a2", "--out", "m"}),
                     {"shard 2/2 is given twice", "'a2'"}, before);
  expect_input_error(run({"merge", "a1", "b1", "--out", "m"}),
                     {"'b1' belongs to another run", "3 shards (not 2)"}, before);
  expect_input_error(run({"merge", "a1", "c2", "--out", "m"}),
                     {"'c2' belongs to another run", "another selection"}, before);
  expect_input_error(
      run({"merge", "a1", "d2", "--out", "m"}),
      {"'d2' belongs to another run", "another selection of figures or other options"}, before);
  expect_input_error(run({"merge", "u1", "a2", "--out", "m"}),
                     {"'u1' is a shard of report (valid: verify, figure, compare, sweep, adequacy)"},
                     before);
  expect_input_error(run({"merge", "a1", "v2", "--out", "m"}),
                     {"'v2' belongs to another run", "command verify (not figure)"}, before);
  expect_input_error(run({"merge", "a1", "plain", "--out", "m"}), {"'plain' holds no shard.json"},
                     before);
  // A shard without a folder its manifest lists (removed, or the run interrupted).
  const std::string covered = manifest("a2")["covered"][0].get<std::string>();
  fs::remove_all(path("a2/" + covered));
  before.erase("a2/" + covered);
  for (auto it = before.begin(); it != before.end();)
    it = it->rfind("a2/" + covered + "/", 0) == 0 ? before.erase(it) : std::next(it);
  expect_input_error(run({"merge", "a1", "a2", "--out", "m"}),
                     {"'a2' lacks the folder of '" + covered + "'"}, before);
  for (const char* bad : {"0/2", "3/2", "1/0", "x", "1/"})
    expect_input_error(run({"figure", kFigures, "--budget", "quick", "--shard", bad, "--out", "f"}),
                       {"--shard", bad, "K/N"}, before);
  expect_input_error(run({"figure", "--list", "--shard", "0/2"}), {"--shard", "0/2", "K/N"},
                     before);
  expect_input_error(run({"figure", "kemppinen2025-nosuch*", "--budget", "quick", "--out", "f"}),
                     {"'kemppinen2025-nosuch*' matches no figure id"}, before);
}

// Every figure at full in 4 shards: each in exactly one shard's plan, and the costliest shard
// within Graham's bound for a greedy least-loaded assignment (the mean load plus (1 - 1/N) of the
// costliest figure); the plan writes nothing.
TEST_F(FigureShardTest, PlanOfEveryFigureCoversEachOnceWithinTheGreedyBound) {
  const int n = 4;
  std::multiset<std::string> ids;
  double largest_shard = 0, total = 0, sum = 0;
  for (int k = 1; k <= n; ++k) {
    const Plan p = plan("*", k, n, "full");
    ids.insert(p.ids.begin(), p.ids.end());
    largest_shard = std::max(largest_shard, p.cost);
    total = p.total;
    sum += p.cost;
  }
  const Plan all = plan("*", 1, 1, "full");
  const double costliest = *std::max_element(all.costs.begin(), all.costs.end());
  EXPECT_EQ(ids, std::multiset<std::string>(all.ids.begin(), all.ids.end()));
  EXPECT_EQ(std::set<std::string>(ids.begin(), ids.end()).size(), ids.size());
  EXPECT_NEAR(sum, total, 1e-6 * total);
  EXPECT_LE(largest_shard, total / n + (1 - 1.0 / n) * costliest);
  EXPECT_TRUE(unexpected_files(work(), {}).empty());
}

// Every registered figure has a measured cost to balance by, shown by --list.
TEST_F(FigureShardTest, EveryFigureHasAMeasuredCost) {
  const RunResult r = run({"figure", "--list"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::vector<std::string> lines = lines_of(r.out);
  ASSERT_GE(lines.size(), kSelection.size());
  for (const std::string& line : lines)
    EXPECT_TRUE(std::regex_search(line, std::regex(R"(\(CPU quick [0-9.]+ s, full [0-9.]+ s\)$)")))
        << line;
}

}  // namespace
}  // namespace glintlab::cli_test
