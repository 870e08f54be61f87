// `glintlab adequacy --shard K/N` and `glintlab merge`: the table's cells split into N shards
// (N = 1, 2 and 7, given to merge in any order) and merged give the files of one unsharded run:
// the maps byte for byte, adequacy.csv and adequacy.json apart from the in-process timings (each
// level's ns per evaluation and the cheapest level measured from them); a missing, repeated or
// foreign shard, or one whose cells are not those its manifest lists, is one error line naming
// it, and nothing is written.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

#include "cli/chart_png.h"
#include "cli/cli_test_util.h"
#include "core/io/csv.h"

namespace glintlab::cli_test {
namespace {

namespace fs = std::filesystem;

class AdequacyShardTest : public CliTest {
 protected:
  // At 1000 positions per cell, not the budget's 8000: what is compared is how the cells are split
  // and joined, the same at any number of positions.
  RunResult adequacy(const std::string& out, const std::string& shard = "",
                     const std::string& threshold = "0.02",
                     const std::string& models = "deliot_belcour",
                     const std::string& positions = "1000") const {
    std::vector<std::string> args = {"adequacy",  "--models",    models,    "--budget",
                                     "quick",     "--threads",   "2",       "--threshold",
                                     threshold,   "--positions", positions, "--out",
                                     out};
    if (!shard.empty()) args.insert(args.end(), {"--shard", shard});
    return run(args);
  }
};

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

// adequacy.csv without its timing columns, one string per row.
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

// A merge's files against the unsharded run's: the same names, adequacy.csv and adequacy.json
// apart from the timings, every other file byte for byte; returns how many maps (PNGs) there are.
std::size_t expect_files_of_one_run(const std::map<std::string, std::string>& merged,
                                    const std::map<std::string, std::string>& one,
                                    const fs::path& merged_dir, const fs::path& one_dir) {
  EXPECT_EQ(merged.size(), one.size());
  std::size_t maps = 0;
  for (const auto& [file, bytes] : one) {
    if (!merged.count(file)) {
      ADD_FAILURE() << file << " is not in the merge";
      continue;
    }
    maps += file.ends_with(".png") ? 1 : 0;
    if (file == "adequacy.csv")
      EXPECT_EQ(csv_without_timing(merged_dir / file), csv_without_timing(one_dir / file));
    else if (file == "adequacy.json")
      EXPECT_EQ(without_timing(nlohmann::json::parse(merged.at(file))),
                without_timing(nlohmann::json::parse(bytes)));
    else
      EXPECT_TRUE(merged.at(file) == bytes) << file << " differs";
  }
  return maps;
}

// The paths of the merge: one shard (N = 1), an even split (N = 2: 162 cells each), an uneven
// one (N = 7: 46 or 47 cells each); an even split into 3 took none that N = 2 does not.
// The merges' maps drawn by matplotlib for N = 2 (the first pass, like the unsharded run), by the
// stand-in (CliTest::stand_in_charts) for N = 1 and 7: each of their maps is then the bytes of
// its chart spec and data, compared with the unsharded run's spec and data, which matplotlib drew
// as that run's map (the same spec and data are the same PNG in any run:
// FigureChartsTest.SeveralFoldersInOneRunAreTheBytesOfSeparateRunsOrNone). The shards draw none.
TEST_F(AdequacyShardTest, MergedShardsAreTheFilesOfOneRun) {
  ASSERT_EQ(adequacy("one").exit_code, 0);
  const std::map<std::string, std::string> one = file_tree("one");
  // A map as the stand-in draws it from the unsharded run's spec and data.
  const auto stand_in_map = [&](const std::string& png) {
    const std::string spec = one.at(png.substr(0, png.size() - 4) + ".chart.json");
    return spec + one.at(nlohmann::json::parse(spec).at("csv").get<std::string>());
  };
  for (int n : {2, 1, 7}) {
    if (n == 1) stand_in_charts();  // for this and the later passes
    std::vector<std::string> merge = {"merge"};
    for (int k = n; k >= 1; --k) {  // any order
      const std::string dir = "s" + std::to_string(n) + "_" + std::to_string(k);
      const RunResult r = adequacy(dir, std::to_string(k) + "/" + std::to_string(n));
      ASSERT_EQ(r.exit_code, 0) << r.err;
      EXPECT_NE(r.out.find("of the table's 324 cells"), std::string::npos) << r.out;
      const auto m = nlohmann::json::parse(read_text(path(dir + "/shard.json")));
      EXPECT_EQ(m["command"], "adequacy");
      EXPECT_EQ(m["selection"].size(), 324u);
      // Each family's cells dealt round-robin: cell k-1, k-1+n, ...
      EXPECT_EQ(m["covered"][0], "binomial/" + std::to_string(k - 1));
      merge.push_back(dir);
    }
    const std::string out = "merged" + std::to_string(n);
    merge.insert(merge.end(), {"--out", out});
    const RunResult r = run(merge);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("324 cells from " + std::to_string(n) + " shards"), std::string::npos)
        << r.out;
    const std::map<std::string, std::string> merged = file_tree(out);
    ASSERT_EQ(merged.size(), one.size()) << n;
    for (const auto& [file, bytes] : one) {
      ASSERT_TRUE(merged.count(file)) << n << ": " << file;
      if (file == "adequacy.csv")
        EXPECT_EQ(csv_without_timing(path(out + "/" + file)),
                  csv_without_timing(path("one/" + file)))
            << n;
      else if (file == "adequacy.json")
        EXPECT_EQ(without_timing(nlohmann::json::parse(merged.at(file))),
                  without_timing(nlohmann::json::parse(bytes)))
            << n;
      else if (n != 2 && file.ends_with(".png"))
        EXPECT_TRUE(merged.at(file) == stand_in_map(file)) << n << " shards: " << file << " differs";
      else
        EXPECT_TRUE(merged.at(file) == bytes) << n << " shards: " << file << " differs";
    }
  }
  // The unsharded run's and the first merge's maps were matplotlib's: each with its chart record.
  EXPECT_TRUE(chart_manifest(path("one/adequacy_deliot_belcour_light0_theta0.png")).is_object());
  EXPECT_TRUE(chart_manifest(path("merged2/adequacy_deliot_belcour_light0_theta0.png")).is_object());
}

// The area family (kneiphof_klein_area under square lights) through the command line: 2 shards
// merged are the files of one run (its maps byte for byte).
TEST_F(AdequacyShardTest, AreaFamilyMergedIsTheFilesOfOneRun) {
  const std::string models = "kneiphof_klein_area";
  ASSERT_EQ(adequacy("one", "", "0.02", models).exit_code, 0);
  const std::map<std::string, std::string> one = file_tree("one");
  std::vector<std::string> merge = {"merge"};
  for (int k : {2, 1}) {
    const std::string dir = "a2_" + std::to_string(k);
    const RunResult r = adequacy(dir, std::to_string(k) + "/2", "0.02", models);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto m = nlohmann::json::parse(read_text(path(dir + "/shard.json")));
    EXPECT_EQ(m["selection"].size(), 324u);
    EXPECT_EQ(m["covered"][0], "area/" + std::to_string(k - 1));
    merge.push_back(dir);
  }
  merge.insert(merge.end(), {"--out", "merged"});
  const RunResult r = run(merge);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("324 cells from 2 shards"), std::string::npos) << r.out;
  EXPECT_EQ(expect_files_of_one_run(file_tree("merged"), one, path("merged"), path("one")),
            6u);  // 3 lights × 2 incidences
}

// The Chermain family through the command line: its quick table (264 cells, nine levels, the
// ggaa_dh column, four maps, families.chermain, the construction's level never refuted), and the
// same table in two shards measured on one thread and merged: the files of the unsharded two-thread
// run (its maps byte for byte), so its cells depend on neither the shard nor the thread count.
TEST_F(AdequacyShardTest, ChermainFamilyOnOneThreadMergedIsTheTwoThreadRun) {
  // At 1000 positions per cell (the budget's 8000 take five times as long; the choosers are tested
  // against the table in tests/verify/adequacy/chermain_chooser_test.cpp).
  const auto chermain = [&](const std::string& out, const std::string& threads,
                            const std::string& shard) {
    std::vector<std::string> args = {"adequacy",  "--models", "chermain", "--budget",
                                     "quick",     "--threads", threads,   "--positions",
                                     "1000",      "--out",     out};
    if (!shard.empty()) args.insert(args.end(), {"--shard", shard});
    return run(args);
  };
  const RunResult one = chermain("one", "2", "");
  ASSERT_EQ(one.exit_code, 0) << one.err;
  EXPECT_NE(one.out.find("Chermain family: 264 cells"), std::string::npos) << one.out;
  const auto doc = nlohmann::json::parse(read_text(path("one/adequacy.json")));
  EXPECT_EQ(doc["cells"].size(), 264u);  // 11 footprints × 2 α × 2 θ_i × 3 θ_h × 2 dh
  EXPECT_EQ(doc["bound"]["decisions"], 264 * 8);
  EXPECT_EQ(doc["families"]["chermain"]["samples_per_cell"], 1000);
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
    const RunResult r = chermain(dir, "1", std::to_string(k) + "/2");
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
  EXPECT_EQ(expect_files_of_one_run(file_tree("merged"), files, path("merged"), path("one")), 4u);
}


TEST_F(AdequacyShardTest, MissingRepeatedOrForeignShardsAreErrorsAndWriteNothing) {
  ASSERT_EQ(adequacy("a1", "1/2").exit_code, 0);
  ASSERT_EQ(adequacy("a2", "2/2").exit_code, 0);
  ASSERT_EQ(adequacy("t2", "2/2", "0.05").exit_code, 0);
  ASSERT_EQ(adequacy("p2", "2/2", "0.02", "deliot_belcour", "1001").exit_code, 0);
  // A shard whose cells are the other shard's.
  fs::copy(path("a2"), path("x2"), fs::copy_options::recursive);
  write_text(path("x2/adequacy-cells.json"), read_text(path("a1/adequacy-cells.json")));
  // A shard whose cells were measured with another TAU than its manifest names.
  fs::copy(path("a2"), path("y2"), fs::copy_options::recursive);
  write_text(path("y2/adequacy-cells.json"), read_text(path("t2/adequacy-cells.json")));
  const std::set<std::string> before = work_paths();
  expect_input_error(run({"merge", "a1", "--out", "m"}), {"shard 2/2 is missing"}, before);
  expect_input_error(run({"merge", "a1", "a2", "a2", "--out", "m"}),
                     {"shard 2/2 is given twice", "'a2'"}, before);
  expect_input_error(run({"merge", "a1", "t2", "--out", "m"}),
                     {"'t2' belongs to another run", "another selection of cells"}, before);
  expect_input_error(run({"merge", "a1", "p2", "--out", "m"}),
                     {"'p2' belongs to another run", "another selection of cells"}, before);
  expect_input_error(run({"merge", "a1", "x2", "--out", "m"}),
                     {"adequacy-cells.json does not hold the cells its shard.json lists"}, before);
  expect_input_error(run({"merge", "a1", "y2", "--out", "m"}),
                     {"adequacy-cells.json was measured with other settings"}, before);
  for (const char* bad : {"0/2", "3/2", "1/0", "x", "1/"})
    expect_input_error(run({"adequacy", "--models", "deliot_belcour", "--shard", bad, "--out", "f"}),
                       {"--shard", bad, "K/N"}, before);
  expect_input_error(run({"adequacy", "--calibrate", "--shard", "1/2", "--out", "f"}),
                     {"--shard", "--calibrate"}, before);
}

}  // namespace
}  // namespace glintlab::cli_test
