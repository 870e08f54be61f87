// `glintlab adequacy --models chermain`: the Chermain family's quick table (264 cells, nine levels,
// the ggaa_dh column, four maps, families.chermain in adequacy.json, the construction's level never
// refuted), and the same table in two shards measured on one thread and merged: the files of the
// unsharded two-thread run (the maps byte for byte, adequacy.csv and adequacy.json apart from the
// in-process timings), so the cells depend on neither the shard nor the thread count.
#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli/cli_test_util.h"
#include "core/io/csv.h"

namespace glintlab::cli_test {
namespace {

namespace fs = std::filesystem;
using AdequacyChermainTest = CliTest;

bool is_timing(const std::string& key) {
  return key == "ns_per_eval" || key.ends_with("_ns_total") || key.ends_with("_ns") ||
         key.starts_with("cheapest_measured");
}

nlohmann::json without_timing(const nlohmann::json& j) {
  if (j.is_object()) {
    nlohmann::json out = nlohmann::json::object();
    for (const auto& [k, v] : j.items())
      if (!is_timing(k)) out[k] = without_timing(v);
    return out;
  }
  if (j.is_array()) {
    nlohmann::json out = nlohmann::json::array();
    for (const auto& v : j) out.push_back(without_timing(v));
    return out;
  }
  return j;
}

std::vector<std::string> csv_without_timing(const fs::path& file) {
  const io::CsvTable t = io::read_csv(file);
  std::vector<std::string> rows;
  for (std::size_t r = 0; r < t.num_rows(); ++r) {
    std::string row;
    for (std::size_t c = 0; c < t.header().size(); ++c)
      if (!is_timing(t.header()[c])) row += t.header()[c] + "=" + std::string(t.text(r, c)) + ",";
    rows.push_back(row);
  }
  return rows;
}

TEST_F(AdequacyChermainTest, QuickTableAndOneThreadShardsMergedAreTheTwoThreadRun) {
  const auto adequacy = [&](const std::string& out, const std::string& threads,
                            const std::string& shard) {
    std::vector<std::string> args = {"adequacy", "--models", "chermain", "--budget", "quick",
                                     "--threads", threads,   "--out",    out};
    if (!shard.empty()) args.insert(args.end(), {"--shard", shard});
    return run(args);
  };
  const RunResult one = adequacy("one", "2", "");
  ASSERT_EQ(one.exit_code, 0) << one.err;
  EXPECT_NE(one.out.find("Chermain family: 264 cells"), std::string::npos) << one.out;
  const auto doc = nlohmann::json::parse(read_text(path("one/adequacy.json")));
  EXPECT_EQ(doc["cells"].size(), 264u);  // 11 footprints × 2 α × 2 θ_i × 3 θ_h × 2 dh
  EXPECT_EQ(doc["bound"]["decisions"], 264 * 8);
  const auto& family = doc["families"]["chermain"];
  EXPECT_EQ(family["most_complete"], "dict16_ggaa");
  EXPECT_EQ(family["levels"].size(), 9u);
  EXPECT_EQ(family["summary"]["construction_refuted"], 0);
  EXPECT_EQ(doc["maps"].size(), 4u);  // 2 dh × 2 incidences
  const io::CsvTable csv = io::read_csv(path("one/adequacy.csv"));
  EXPECT_EQ(csv.num_rows(), 264u);
  EXPECT_EQ(csv.header()[7], "ggaa_dh");
  std::size_t smooth = 0, short_dictionary = 0;
  for (const auto& c : doc["cells"]) {
    EXPECT_EQ(c["family"], "chermain");
    smooth += c["chosen"] == "smooth" ? 1 : 0;
    short_dictionary += c["chosen"] == "dict4" || c["chosen"] == "dict4_ggaa" ? 1 : 0;
  }
  EXPECT_GT(smooth, 0u);            // the largest footprints
  EXPECT_GT(short_dictionary, 0u);  // the smallest
  const std::map<std::string, std::string> files = file_tree("one");
  std::vector<std::string> merge = {"merge"};
  for (int k : {2, 1}) {
    const std::string dir = "c2_" + std::to_string(k);
    const RunResult r = adequacy(dir, "1", std::to_string(k) + "/2");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto m = nlohmann::json::parse(read_text(path(dir + "/shard.json")));
    EXPECT_EQ(m["selection"].size(), 264u);
    EXPECT_EQ(m["covered"][0], "chermain/" + std::to_string(k - 1));
    merge.push_back(dir);
  }
  merge.insert(merge.end(), {"--out", "merged"});
  const RunResult r = run(merge);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("264 cells from 2 shards"), std::string::npos) << r.out;
  const std::map<std::string, std::string> merged = file_tree("merged");
  ASSERT_EQ(merged.size(), files.size());
  std::size_t maps = 0;
  for (const auto& [file, bytes] : files) {
    ASSERT_TRUE(merged.count(file)) << file;
    maps += file.ends_with(".png") ? 1 : 0;
    if (file == "adequacy.csv")
      EXPECT_EQ(csv_without_timing(path("merged/" + file)), csv_without_timing(path("one/" + file)));
    else if (file == "adequacy.json")
      EXPECT_EQ(without_timing(nlohmann::json::parse(merged.at(file))),
                without_timing(nlohmann::json::parse(bytes)));
    else
      EXPECT_TRUE(merged.at(file) == bytes) << file << " differs";
  }
  EXPECT_EQ(maps, 4u);
}

}  // namespace
}  // namespace glintlab::cli_test
