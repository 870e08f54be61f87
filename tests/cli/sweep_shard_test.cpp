// `glintlab sweep --shard K/N` and `glintlab merge`: the models of a sweep split into N shards
// (N = 1, 2, 3 and 4, the 4th empty) and merged give the files of one unsharded run byte for byte
// (the sweep writes no timing; its maps drawn by matplotlib for N = 2 on two models with few
// maps, by a stand-in otherwise); a missing, repeated or foreign shard, or one whose files are not
// the models its manifest lists, is one error line naming it, and nothing is written.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <numeric>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "cli/cli_test_util.h"

namespace glintlab::cli_test {
namespace {

namespace fs = std::filesystem;

class SweepShardTest : public CliTest {
 protected:
  // The three cheapest models to sweep (smooth_ggx with its four samplers, two with one), six
  // model × sampler targets.
  static constexpr const char* kModels = "smooth_ggx,deliot_belcour,kneiphof_klein_area";

  RunResult sweep(const std::string& out, const std::string& shard = "",
                  const std::string& models = kModels, const std::string& threads = "2") const {
    std::vector<std::string> args = {"sweep",     "--models", models,  "--budget", "quick",
                                     "--threads", threads,    "--out", out};
    if (!shard.empty()) args.insert(args.end(), {"--shard", shard});
    return run(args);
  }

  // `sweep --list`: the models the run (or its shard) would sweep and their costs, in order.
  std::vector<std::pair<std::string, double>> plan(const std::string& shard,
                                                   const std::string& budget,
                                                   const std::string& models = "*") const {
    const RunResult r =
        run({"sweep", "--list", "--models", models, "--budget", budget, "--shard", shard});
    EXPECT_EQ(r.exit_code, 0) << r.err;
    std::vector<std::pair<std::string, double>> rows;
    std::istringstream in(r.out);
    for (std::string line; std::getline(in, line);) {
      if (line.starts_with("shard ")) {
        EXPECT_NE(line.find("measured at --budget " + budget), std::string::npos) << line;
        continue;
      }
      std::istringstream words(line);
      std::string model;
      double seconds = -1;
      words >> model >> seconds;
      rows.emplace_back(model, seconds);
    }
    return rows;
  }
};

TEST_F(SweepShardTest, MergedShardsAreTheFilesOfOneRun) {
  // Each N in turn merged and compared with one run; the maps drawn by matplotlib for N = 2 (the
  // first pass: smooth_beckmann and podee, one model in each shard, the models with the fewest
  // maps: 20 each, 40 a run), by the stand-in (CliTest::stand_in_charts) for the others (on the
  // three cheapest models to sweep, kModels).
  const auto check = [&](const std::vector<std::string>& models, const std::vector<int>& counts,
                         const std::string& tag) {
    std::string list;
    for (const std::string& m : models) list += (list.empty() ? "" : ",") + m;
    ASSERT_EQ(sweep("one" + tag, "", list).exit_code, 0);
    const std::map<std::string, std::string> one = file_tree("one" + tag);
    ASSERT_TRUE(one.count("stability.json"));
    for (int n : counts) {
      std::vector<std::string> merge = {"merge"};
      for (int k = n; k >= 1; --k) {  // any order; shard 1 with one thread
        const std::string dir = "s" + tag + std::to_string(n) + "_" + std::to_string(k);
        const RunResult r =
            sweep(dir, std::to_string(k) + "/" + std::to_string(n), list, k == 1 ? "1" : "2");
        ASSERT_EQ(r.exit_code, 0) << r.err;
        const auto m = nlohmann::json::parse(read_text(path(dir + "/shard.json")));
        EXPECT_EQ(m["command"], "sweep");
        EXPECT_EQ(m["selection"], nlohmann::json(models));
        if (n == 2) {
          EXPECT_EQ(m["covered"].size(), 1u) << dir;
        }
        // The plan that --list --shard prints, running nothing, is what the shard ran.
        std::vector<std::string> listed;
        for (const auto& [model, seconds] :
             plan(std::to_string(k) + "/" + std::to_string(n), "quick", list))
          listed.push_back(model);
        EXPECT_EQ(nlohmann::json(listed), m["covered"]) << dir;
        merge.push_back(dir);
      }
      const std::string out = "merged" + tag + std::to_string(n);
      merge.insert(merge.end(), {"--out", out});
      const RunResult r = run(merge);
      ASSERT_EQ(r.exit_code, 0) << r.err;
      EXPECT_TRUE(file_tree(out) == one) << n << " shards: the merged files differ from one run's";
    }
  };
  check({"smooth_beckmann", "podee"}, {2}, "");
  // The maps of the first pass were matplotlib's: each with its chart record.
  EXPECT_NE(read_text(path("one/smooth_beckmann/ndf/alpha_variance.png")).find("glintlab:chart"),
            std::string::npos);
  EXPECT_NE(read_text(path("one/podee/default/footprint_variance.png")).find("glintlab:chart"),
            std::string::npos);
  stand_in_charts();
  check({"smooth_ggx", "deliot_belcour", "kneiphof_klein_area"}, {1, 3, 4}, "_");
  EXPECT_EQ(read_text(path("one_/smooth_ggx/ndf/alpha_variance.png"))
                .rfind(read_text(path("one_/smooth_ggx/ndf/alpha_maps.csv"))),
            read_text(path("one_/smooth_ggx/ndf/alpha_variance.png")).size() -
                read_text(path("one_/smooth_ggx/ndf/alpha_maps.csv")).size());
  // Three models in 4 shards: the 4th swept none and holds its manifest alone.
  EXPECT_TRUE(unexpected_files(path("s_4_4"), {"shard.json"}).empty());
}

// `sweep --list --shard K/N` prints the split without running it: every registered model has a
// measured cost (cli/sweep_costs.cpp) at both budgets, and the shards are balanced by it: every
// model in exactly one shard, the two costliest apart, the largest shard within the greedy bound
// and below the every-N-th split's largest.
TEST_F(SweepShardTest, ListShowsTheShardsBalancedByTheMeasuredCosts) {
  for (const std::string budget : {"quick", "full"}) {
    const auto all = plan("1/1", budget);
    ASSERT_EQ(all.size(), 9u) << budget;  // the registered models, in glintlab models order
    std::vector<double> costs;
    for (const auto& [m, c] : all) costs.push_back(c);
    // Each a measured row, not the mean a model without one gets.
    const double mean = std::accumulate(costs.begin(), costs.end(), 0.0) / double(costs.size());
    for (const auto& [m, c] : all) EXPECT_NE(c, mean) << m << " at " << budget;
    const double total = std::accumulate(costs.begin(), costs.end(), 0.0);
    std::vector<std::size_t> order(costs.size());
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
      return costs[a] > costs[b];
    });
    const int n = 4;
    double every_nth_largest = 0;
    for (int k = 0; k < n; ++k) {
      double sum = 0;
      for (std::size_t i = std::size_t(k); i < costs.size(); i += n) sum += costs[i];
      every_nth_largest = std::max(every_nth_largest, sum);
    }
    std::map<std::string, int> shard_of;
    double largest = 0;
    for (int k = 1; k <= n; ++k) {
      double sum = 0;
      for (const auto& [m, c] : plan(std::to_string(k) + "/" + std::to_string(n), budget)) {
        EXPECT_TRUE(shard_of.emplace(m, k).second) << m << " is in two shards";
        sum += c;
      }
      largest = std::max(largest, sum);
    }
    EXPECT_EQ(shard_of.size(), all.size()) << budget;
    EXPECT_NE(shard_of[all[order[0]].first], shard_of[all[order[1]].first]) << budget;
    EXPECT_LE(largest, total / n + (1 - 1.0 / n) * costs[order[0]] + 0.5) << budget;
    EXPECT_LT(largest, every_nth_largest) << budget;
  }
  EXPECT_EQ(unexpected_files(work(), {}), std::vector<std::string>{});
}

TEST_F(SweepShardTest, MissingRepeatedOrForeignShardsAreErrorsAndWriteNothing) {
  stand_in_charts();  // the merge's checks, not the maps, are tested here
  ASSERT_EQ(sweep("a1", "1/2").exit_code, 0);
  ASSERT_EQ(sweep("a2", "2/2").exit_code, 0);
  ASSERT_EQ(sweep("c2", "2/2", "smooth_ggx,deliot_belcour").exit_code, 0);
  // A shard whose stability.json holds another model than its manifest lists.
  fs::copy(path("a2"), path("x2"), fs::copy_options::recursive);
  write_text(path("x2/stability.json"), read_text(path("a1/stability.json")));
  const std::set<std::string> before = work_paths();
  expect_input_error(run({"merge", "a1", "--out", "m"}), {"shard 2/2 is missing"}, before);
  expect_input_error(run({"merge", "a1", "a2", "a2", "--out", "m"}),
                     {"shard 2/2 is given twice", "'a2'"}, before);
  expect_input_error(run({"merge", "a1", "c2", "--out", "m"}),
                     {"'c2' belongs to another run", "another selection of models"}, before);
  expect_input_error(run({"merge", "a1", "x2", "--out", "m"}),
                     {"x2/stability.json does not hold the models its shard.json lists"}, before);
  for (const char* bad : {"0/2", "3/2", "1/0", "x", "1/"})
    expect_input_error(run({"sweep", "--models", "smooth_ggx", "--shard", bad, "--out", "f"}),
                       {"--shard", bad, "K/N"}, before);
}

}  // namespace
}  // namespace glintlab::cli_test
