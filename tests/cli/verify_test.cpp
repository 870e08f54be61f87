// `glintlab verify`: the verdict table and its three result files, claim selection, and bad input
// (one line, exit 2, no output directory left behind).
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "cli/cli_test_util.h"

namespace glintlab::cli_test {
namespace {

using VerifyTest = CliTest;

TEST_F(VerifyTest, WritesTheThreeResultFilesWithTheRequiredFields) {
  const RunResult r = run({"verify", "--claims", "smooth.projected-area", "--out", "o", "--threads", "1"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("smooth.projected-area"), std::string::npos);
  EXPECT_EQ(unexpected_files(work(), {"o", "o/claims.json", "o/claims.csv", "o/claims.md"}),
            std::vector<std::string>{});
  const auto j = nlohmann::json::parse(read_text(path("o/claims.json")));
  ASSERT_EQ(j.size(), 1u);
  for (const char* key : {"id", "paper", "source", "verdict", "detail", "statistic", "p_value",
                          "control_p_value", "control_rejected", "control_verdict", "regime", "seconds",
                          "suite_adjusted_p_value"})
    EXPECT_TRUE(j[0].contains(key)) << key;
  EXPECT_EQ(j[0]["id"], "smooth.projected-area");
  EXPECT_EQ(j[0]["verdict"], "holds");
  EXPECT_TRUE(j[0]["p_value"].is_null());  // a deterministic check has an error bound, no p-value
  EXPECT_EQ(lines_of(read_text(path("o/claims.csv"))).size(), 2u);
}

TEST_F(VerifyTest, ListShowsRecordedVerdicts) {
  const RunResult r = run({"verify", "--list", "--claims", "smooth.*"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("smooth.vndf-normalized"), std::string::npos);
  EXPECT_NE(r.out.find("holds"), std::string::npos);
  EXPECT_EQ(unexpected_files(work(), {}), std::vector<std::string>{});
}

TEST_F(VerifyTest, CalibrateWritesItsJsonAndExitsZeroForAValidTest) {
  const RunResult r = run({"verify", "--calibrate", "eto.unbiased", "--runs", "30", "--out", "o"});
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("false-positive rate at level 0.05"), std::string::npos) << r.out;
  const auto j = nlohmann::json::parse(read_text(path("o/calibration-eto.unbiased.json")));
  EXPECT_EQ(j["runs"], 30);
  EXPECT_EQ(j["p_values"].size(), 30u);
  EXPECT_TRUE(j["valid"].get<bool>());
  EXPECT_EQ(unexpected_files(work(), {"o", "o/calibration-eto.unbiased.json"}), std::vector<std::string>{});
}

TEST_F(VerifyTest, BadInputLeavesNothingBehind) {
  expect_input_error(run({"verify", "--budget", "huge", "--out", "o"}), {"--budget", "valid: quick, full"}, {});
  expect_input_error(run({"verify", "--claims", "nosuch.*", "--out", "o"}), {"--claims", "nosuch.*"}, {});
  expect_input_error(run({"verify", "--threads", "-3", "--out", "o"}), {"--threads", "[0, 1024]"}, {});
  expect_input_error(run({"verify", "--calibrate", "nosuch.claim", "--out", "o"}),
                     {"--calibrate", "not a registered claim id"}, {});
  expect_input_error(run({"verify", "--calibrate", "smooth.projected-area", "--out", "o"}),
                     {"--calibrate", "deterministic"}, {});
  expect_input_error(run({"verify", "--calibrate", "smooth.projected-area", "--runs", "1", "--out", "o"}),
                     {"--runs", "[2, 1000000]"}, {});
  expect_input_error(run({"verify", "--level", "1.5", "--out", "o"}), {"--level", "(0, 1)"}, {});
}

}  // namespace
}  // namespace glintlab::cli_test
