// `glintlab adequacy`: the quick table, maps and index for one model, identical output (timing
// columns aside) for any --threads, and the bad-input errors (one line, exit 2, nothing written).
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "cli/cli_test_util.h"
#include "core/io/csv.h"

namespace glintlab::cli_test {
namespace {

namespace fs = std::filesystem;
using AdequacyTest = CliTest;

TEST_F(AdequacyTest, QuickRunWritesTableAndMaps) {
  const RunResult r = run({"adequacy", "--budget", "quick", "--models", "kneiphof_klein",
                           "--out", "a", "--threads", "2"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("324 cells"), std::string::npos) << r.out;  // 9 × 2 × 3 × 3 × 2
  const auto doc = nlohmann::json::parse(read_text(path("a/adequacy.json")));
  EXPECT_EQ(doc["threshold"], 0.02);
  EXPECT_EQ(doc["cells"].size(), 324u);
  EXPECT_EQ(doc["maps"].size(), 6u);
  for (const auto& m : doc["maps"]) {
    EXPECT_TRUE(fs::exists(path("a") / m["png"].get<std::string>()));
    EXPECT_TRUE(fs::exists(path("a") / m["exr"].get<std::string>()));
  }
  EXPECT_EQ(io::read_csv(path("a/adequacy.csv")).num_rows(), 324u);
  // Every level appears somewhere in 1 .. 1e8 facets except possibly small_count.
  std::size_t smooth = doc["summary"]["chosen"]["smooth"], exact = doc["summary"]["chosen"]["exact"];
  EXPECT_GT(smooth, 0u);
  EXPECT_GT(exact, 0u);
  EXPECT_EQ(doc["summary"]["chooser_refuted"], 0);
  EXPECT_EQ(unexpected_files(path("a"), {}).size(), 2u + 12u);
}

TEST_F(AdequacyTest, OutputDoesNotDependOnThreads) {
  for (const char* t : {"1", "2"})
    ASSERT_EQ(run({"adequacy", "--models", "deliot_belcour", "--out", std::string("t") + t,
                   "--threads", t})
                  .exit_code,
              0);
  // Every line up to the four *_ns columns, cheapest_measured and time_saved_ns (timing, last) is identical.
  const auto without_timing = [](const std::string& line) {
    std::size_t cut = line.size();
    for (int k = 0; k < 6; ++k) cut = line.rfind(',', cut - 1);
    return line.substr(0, cut);
  };
  const auto a = lines_of(read_text(path("t1/adequacy.csv")));
  const auto b = lines_of(read_text(path("t2/adequacy.csv")));
  ASSERT_EQ(a.size(), b.size());
  ASSERT_GT(a.size(), 100u);
  for (std::size_t i = 0; i < a.size(); ++i) EXPECT_EQ(without_timing(a[i]), without_timing(b[i])) << i;
}

TEST_F(AdequacyTest, BadInputIsOneLineAndWritesNothing) {
  expect_input_error(run({"adequacy", "--threshold", "0", "--out", "o"}),
                     {"--threshold", "(0, 1]"}, {});
  expect_input_error(run({"adequacy", "--threshold", "1.5", "--out", "o"}),
                     {"--threshold", "(0, 1]"}, {});
  expect_input_error(run({"adequacy", "--threshold", "abc", "--out", "o"}), {"--threshold"}, {});
  expect_input_error(run({"adequacy", "--models", "chermain", "--out", "o"}),
                     {"--models", "deliot_belcour, kneiphof_klein"}, {});
  expect_input_error(run({"adequacy", "--budget", "huge", "--out", "o"}), {"--budget"}, {});
  expect_input_error(run({"adequacy", "--threads", "-1", "--out", "o"}), {"--threads"}, {});
  expect_input_error(run({"adequacy", "--calibrate", "--runs", "0", "--out", "o"}),
                     {"--runs", "[1, 1000000]"}, {});
  expect_input_error(run({"adequacy", "--runs", "10", "--out", "o"}), {"--runs", "--calibrate"},
                     {});
  expect_input_error(run({"adequacy", "--calibrate", "--tables", "-1", "--out", "o"}),
                     {"--tables", "[0, 100000]"}, {});
  expect_input_error(run({"adequacy", "--tables", "2", "--out", "o"}), {"--tables", "--calibrate"},
                     {});
}

TEST_F(AdequacyTest, CalibrateWritesRatesForEveryCaseDeltaAndLevel) {
  const RunResult r = run({"adequacy", "--calibrate", "--runs", "3", "--tables", "1", "--models",
                           "deliot_belcour", "--out", "c", "--threads", "2"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("972 decisions"), std::string::npos) << r.out;  // 324 cells × 3 levels
  const auto doc = nlohmann::json::parse(read_text(path("c/adequacy-calibration.json")));
  EXPECT_EQ(doc["table_decisions"], 972);
  EXPECT_EQ(doc["positions_per_cell"], 8000);
  // 7 cases × 7 δ × (4 nominal levels + the table's share).
  EXPECT_EQ(doc["rows"].size(), 7u * 7u * 5u);
  EXPECT_EQ(io::read_csv(path("c/adequacy-calibration.csv")).num_rows(), 7u * 7u * 5u);
  EXPECT_EQ(doc["pooled"].size(), 7u * 5u);  // the five pooled cases summed per δ and level
  EXPECT_EQ(doc["pooled"][0]["decisions"], 5 * 3);
  EXPECT_EQ(doc["pooled"][0]["verdict"], "power");  // δ = −0.5: truly adequate
  ASSERT_EQ(doc["family_wise"].size(), 4u);  // δ = 0, 0.05, 0.1, 0.25
  EXPECT_EQ(doc["family_wise"][0]["tables"], 1);
  EXPECT_EQ(doc["family_wise"][0]["table_decisions"], 972);
  EXPECT_EQ(unexpected_files(path("c"), {}).size(), 2u);
}

}  // namespace
}  // namespace glintlab::cli_test
