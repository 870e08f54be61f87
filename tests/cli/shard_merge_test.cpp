// `glintlab verify --shard K/N` and `glintlab merge`: a run split into N shards (N = 1, 2, 3 and 7,
// some shards empty) and merged gives the bytes of one unsharded run apart from the timing fields,
// the suite's Holm–Šidák adjustment included (a shard's own adjustment covers only its rows); a
// missing, repeated or foreign shard is one error line naming it, and nothing is written.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
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
  // Six quick claims, three of them with p-values (so that the adjustment spans shards).
  static constexpr const char* kClaims =
      "kemppinen.furnace,kemppinen.roulette,kneiphof.subdivision,eto.backfacing-stable-pdf,"
      "kneiphof.cap-probability,podee.brightest-vector";

  RunResult verify(const std::string& out, const std::string& shard = "") const {
    std::vector<std::string> args = {"verify", "--claims", kClaims,  "--budget",
                                     "quick",  "--threads", "2",     "--out", out};
    if (!shard.empty()) args.insert(args.end(), {"--shard", shard});
    return run(args);
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
    for (int k = n; k >= 1; --k) {  // any order
      const std::string dir = "s" + std::to_string(n) + "_" + std::to_string(k);
      const RunResult r = verify(dir, std::to_string(k) + "/" + std::to_string(n));
      ASSERT_EQ(r.exit_code, 0) << r.err;
      ASSERT_TRUE(fs::exists(path(dir + "/shard.json"))) << dir;
      merge.push_back(dir);
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
  // With 7 shards of 6 claims the 7th is empty. A shard's own adjustment covers its rows only:
  // the merge's is computed over every shard's p-values, as one run's.
  EXPECT_EQ(read_text(path("s7_7/claims.json")), "[]\n");
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
}

}  // namespace
}  // namespace glintlab::cli_test
