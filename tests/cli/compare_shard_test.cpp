// `glintlab compare --shard K/N` and `glintlab merge`: the models of a comparison split into N
// shards (N = 1, 2 and 3, the 3rd empty) and merged give the page of one unsharded run: the same
// bytes apart from the timing fields (experiments/compare/compare.h kTimingFields, and the chart
// drawn from them); a missing, repeated or foreign shard, or one whose files are not the models
// its manifest lists, is one error line naming it, and nothing is written. The page is drawn by
// reports/compare_page.py for the unsharded run and N = 2, by the stand-in (CliTest::
// stand_in_charts: the page is the bytes of the compare.json it is drawn from) for the rest.
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

class CompareShardTest : public CliTest {
 protected:
  void SetUp() override {
    CliTest::SetUp();
    // No conformance rows: each model shows its recorded verdicts instead of running its suite.
    fs::create_directory(path("verify"));
    write_text(path("verify/claims.json"), "[]\n");
  }

  RunResult compare(const std::string& out, const std::string& shard = "",
                    const std::string& models = "smooth_ggx,smooth_beckmann",
                    const std::string& threads = "2") const {
    std::vector<std::string> args = {"compare", "--models", models,  "--claims-from",
                                     "verify",  "--budget", "quick", "--threads",
                                     threads,   "--out",    out};
    if (!shard.empty()) args.insert(args.end(), {"--shard", shard});
    return run(args);
  }
};

// The timing fields blanked: ns per evaluation and seconds in compare.json, their columns in the
// CSVs (compare.csv: scalar_ns_per_eval, best_ns_per_eval; equal_time.csv: seconds) and the
// "scalar → best (isa)" cell of index.html.
std::string without_timing(const std::string& file, const std::string& text) {
  if (file == "compare.json")
    return std::regex_replace(
        text, std::regex("\"(scalar_ns_per_eval|best_ns_per_eval|seconds)\": [-0-9.e+]+"),
        "\"$1\": T");
  if (file == "compare.csv")
    return std::regex_replace(
        text, std::regex("^([^,]*,\"[^\"]*\"),[^,]*,([^,]*),[^,]*,", std::regex::multiline),
        "$1,T,$2,T,");
  if (file == "equal_time.csv")
    return std::regex_replace(text, std::regex("^([^,]*,[^,]*),[^,]*,", std::regex::multiline),
                              "$1,T,");
  return std::regex_replace(text, std::regex("[0-9.]+ → [0-9.]+ \\("), "T → T (");
}

TEST_F(CompareShardTest, MergedShardsAreThePageOfOneRun) {
  ASSERT_EQ(compare("one").exit_code, 0);
  // N = 2 with the real page, compared with the unsharded run's; N = 1 and 3 with the stand-in,
  // whose page is the merged compare.json compared with the unsharded run's.
  for (int n : {2, 1, 3}) {
    if (n == 1) stand_in_charts();
    std::vector<std::string> merge = {"merge"};
    for (int k = n; k >= 1; --k) {  // any order; shard 1 with one thread
      const std::string dir = "s" + std::to_string(n) + "_" + std::to_string(k);
      const RunResult r = compare(dir, std::to_string(k) + "/" + std::to_string(n),
                                  "smooth_ggx,smooth_beckmann", k == 1 ? "1" : "2");
      ASSERT_EQ(r.exit_code, 0) << r.err;
      const auto m = nlohmann::json::parse(read_text(path(dir + "/shard.json")));
      EXPECT_EQ(m["command"], "compare");
      EXPECT_EQ(m["selection"], nlohmann::json({"smooth_ggx", "smooth_beckmann"}));
      // The plan that --list --shard prints, running nothing, is what the shard ran.
      const RunResult listed = run({"compare", "--list", "--models", "smooth_ggx,smooth_beckmann",
                                    "--claims-from", "verify", "--budget", "quick", "--shard",
                                    std::to_string(k) + "/" + std::to_string(n)});
      ASSERT_EQ(listed.exit_code, 0) << listed.err;
      std::vector<std::string> names;
      std::istringstream lines(listed.out);
      for (std::string line; std::getline(lines, line);)
        if (!line.starts_with("shard ")) names.push_back(line.substr(0, line.find(' ')));
      EXPECT_EQ(nlohmann::json(names), m["covered"]) << dir;
      merge.push_back(dir);
    }
    const std::string out = "merged" + std::to_string(n);
    merge.insert(merge.end(), {"--out", out});
    const RunResult r = run(merge);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("compare: 2 models"), std::string::npos) << r.out;
    for (const char* f : {"compare.json", "compare.csv", "equal_time.csv"})
      EXPECT_EQ(without_timing(f, read_text(path(out + "/" + f))),
                without_timing(f, read_text(path(std::string("one/") + f))))
          << n << " shards: " << f;
    if (n == 2) {
      EXPECT_EQ(without_timing("index.html", read_text(path(out + "/index.html"))),
                without_timing("index.html", read_text(path("one/index.html"))))
          << n << " shards: index.html";
    } else {
      for (const char* page : {"index.html", "equal_time.png"})
        EXPECT_EQ(read_text(path(out + "/" + page)), read_text(path(out + "/compare.json")))
            << n << " shards: " << page << " is not drawn from the merged compare.json";
    }
    EXPECT_TRUE(unexpected_files(path(out), {"compare.json", "compare.csv", "equal_time.csv",
                                             "equal_time.png", "index.html"})
                    .empty());
  }
  // Two models in 3 shards: the 3rd ran none and holds its manifest alone.
  EXPECT_TRUE(unexpected_files(path("s3_3"), {"shard.json"}).empty());
  // The blanking leaves the rest: one run's file against another's with a model more differs.
  ASSERT_EQ(compare("ggx", "", "smooth_ggx").exit_code, 0);
  EXPECT_NE(without_timing("compare.csv", read_text(path("ggx/compare.csv"))),
            without_timing("compare.csv", read_text(path("one/compare.csv"))));
}

// `compare --list --shard K/N` prints the split without running it. Where the run measures the
// conformance checks itself, the shards are balanced by the checks' recorded seconds: every model
// in exactly one shard, the two costliest apart, the largest shard within the greedy bound and
// below the every-N-th split's largest. With --claims-from the run still sweeps every model, and
// the shards are balanced by the sweeps' measured costs (the two Kemppinen models apart); with
// --sweeps-from too every model weighs 1 and shard K holds every N-th model from the K-th.
TEST_F(CompareShardTest, ListShowsTheShardsBalancedByTheRecordedCosts) {
  enum Reads { kNothing, kClaims, kClaimsAndSweeps };
  const auto plan = [&](const std::string& shard, Reads reads) {
    std::vector<std::string> args = {"compare", "--list", "--budget", "quick", "--shard", shard};
    if (reads != kNothing) args.insert(args.end(), {"--claims-from", "verify"});
    if (reads == kClaimsAndSweeps) args.insert(args.end(), {"--sweeps-from", "sweeps"});
    const RunResult r = run(args);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    std::vector<std::pair<std::string, double>> rows;
    std::istringstream in(r.out);
    for (std::string line; std::getline(in, line);) {
      if (line.starts_with("shard ")) continue;
      std::istringstream words(line);
      std::string model;
      double weight = 0;
      words >> model >> weight;
      rows.emplace_back(model, weight);
    }
    return rows;
  };
  // The shards of 3 balanced by the plan's weights: each model in one shard, the two Kemppinen
  // models apart, the largest within the greedy bound, and for the conformance checks' weights
  // below every N-th's largest (which puts two costly models together there; for the quick
  // sweeps' nearly equal weights every N-th happens to be as good).
  const auto expect_balanced = [&](Reads reads) {
    const auto all = plan("1/1", reads);
    ASSERT_EQ(all.size(), 9u);  // the registered models, in glintlab models order
    std::vector<double> weights;
    for (const auto& [m, w] : all) weights.push_back(w);
    const double total = std::accumulate(weights.begin(), weights.end(), 0.0);
    const double costliest = *std::max_element(weights.begin(), weights.end());
    const int n = 3;
    double every_nth_largest = 0;
    for (int k = 0; k < n; ++k) {
      double sum = 0;
      for (std::size_t i = std::size_t(k); i < weights.size(); i += n) sum += weights[i];
      every_nth_largest = std::max(every_nth_largest, sum);
    }
    std::map<std::string, int> shard_of;
    double largest = 0;
    for (int k = 1; k <= n; ++k) {
      double sum = 0;
      for (const auto& [m, w] : plan(std::to_string(k) + "/3", reads)) {
        EXPECT_TRUE(shard_of.emplace(m, k).second) << m << " is in two shards";
        sum += w;
      }
      largest = std::max(largest, sum);
    }
    EXPECT_EQ(shard_of.size(), all.size());
    EXPECT_NE(shard_of["kemppinen_ggx"], shard_of["kemppinen_beckmann"]);
    EXPECT_LE(largest, total / n + (1 - 1.0 / n) * costliest + 0.5);
    if (reads == kNothing) {
      EXPECT_LT(largest, every_nth_largest);
    }
  };
  expect_balanced(kNothing);
  expect_balanced(kClaims);
  // A model that sweeps weighs more than 1: the sweep's cost is counted.
  for (const auto& [m, w] : plan("1/1", kClaims)) EXPECT_GT(w, 1.5) << m;
  // Verdicts and sweeps read: one per model, every N-th from the K-th.
  const auto all = plan("1/1", kClaimsAndSweeps);
  const auto read = plan("2/3", kClaimsAndSweeps);
  ASSERT_EQ(read.size(), 3u);
  for (std::size_t j = 0; j < read.size(); ++j) {
    EXPECT_EQ(read[j].first, all[1 + 3 * j].first);
    EXPECT_EQ(read[j].second, 1.0);
  }
  EXPECT_EQ(unexpected_files(work(), {"verify", "verify/claims.json"}), std::vector<std::string>{});
}

TEST_F(CompareShardTest, MissingRepeatedOrForeignShardsAreErrorsAndWriteNothing) {
  stand_in_charts();  // the merge's checks are tested, not the page
  ASSERT_EQ(compare("a1", "1/2").exit_code, 0);
  ASSERT_EQ(compare("a2", "2/2").exit_code, 0);
  ASSERT_EQ(compare("b2", "2/2", "smooth_ggx,smooth_beckmann", "1").exit_code, 0);
  ASSERT_EQ(compare("c2", "2/2", "smooth_ggx,smooth_beckmann,podee").exit_code, 0);
  // b2's compare.json with a2's settings changed (as another --budget's would be).
  const std::string b2 = read_text(path("b2/compare.json"));
  write_text(path("b2/compare.json"),
             std::regex_replace(b2, std::regex("\"repetitions\": [0-9]+"), "\"repetitions\": 99"));
  const std::set<std::string> before = work_paths();
  expect_input_error(run({"merge", "a1", "--out", "m"}), {"shard 2/2 is missing"}, before);
  expect_input_error(run({"merge", "a1", "a2", "a2", "--out", "m"}),
                     {"shard 2/2 is given twice", "'a2'"}, before);
  expect_input_error(run({"merge", "a1", "c2", "--out", "m"}),
                     {"'c2' belongs to another run", "another selection of models"}, before);
  expect_input_error(run({"merge", "a1", "b2", "--out", "m"}),
                     {"'b2' belongs to another run than 'a1'", "other settings"}, before);
  // A shard whose files hold another model than its manifest lists.
  write_text(path("b2/compare.json"), b2);
  write_text(path("b2/compare.csv"), read_text(path("a1/compare.csv")));
  expect_input_error(run({"merge", "a1", "b2", "--out", "m"}),
                     {"b2/compare.csv holds a row of 'smooth_ggx'"}, before);
  for (const char* bad : {"0/2", "3/2", "1/0", "x", "1/"})
    expect_input_error(run({"compare", "--models", "smooth_ggx", "--shard", bad, "--out", "f"}),
                       {"--shard", bad, "K/N"}, before);
}

}  // namespace
}  // namespace glintlab::cli_test
