// `glintlab compare`: the page's files, the example plug-in (examples/zirr_kaplanyan) beside the
// papers' models, verdict origins, thread-count independence of every field but the timings, and
// a malformed --claims-from file (one line, exit 2, nothing written).
#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli/cli_test_util.h"

namespace glintlab::cli_test {
namespace {

namespace fs = std::filesystem;
using CompareTest = CliTest;

// compare.json without its wall-clock fields (experiments/compare/compare.h kTimingFields).
nlohmann::json without_timings(nlohmann::json j) {
  if (j.is_object()) {
    for (const char* f : {"scalar_ns_per_eval", "best_ns_per_eval", "seconds"}) j.erase(f);
    for (auto& [k, v] : j.items()) v = without_timings(v);
  } else if (j.is_array()) {
    for (auto& v : j) v = without_timings(v);
  }
  return j;
}

const nlohmann::json& model_named(const nlohmann::json& doc, const std::string& name) {
  for (const auto& m : doc["models"])
    if (m["name"] == name) return m;
  ADD_FAILURE() << "no model " << name << " in compare.json";
  static const nlohmann::json none;
  return none;
}

TEST_F(CompareTest, PluginModelBesideThePapersModelsAndThreadIndependent) {
  fs::create_directory(path("verify"));
  write_text(path("verify/claims.json"), "[]\n");
  const auto compare = [&](const std::string& out, const std::string& threads) {
    return run({"--plugin", kTestPluginZirrKaplanyan, "compare", "--models",
                "smooth_ggx,deliot_belcour,zirr*", "--claims-from", "verify", "--threads", threads,
                "--out", out});
  };
  const RunResult one = compare("c1", "1");
  ASSERT_EQ(one.exit_code, 0) << one.err;
  EXPECT_NE(one.out.find("compare: 3 models; wrote c1/index.html"), std::string::npos) << one.out;
  for (const char* f :
       {"compare.json", "compare.csv", "equal_time.csv", "equal_time.png", "index.html"})
    EXPECT_TRUE(fs::is_regular_file(path("c1") / f)) << f;
  // Nothing but the page (no staging folder).
  EXPECT_TRUE(unexpected_files(path("c1"), {"compare.json", "compare.csv", "equal_time.csv",
                                            "equal_time.png", "index.html"})
                  .empty());
  const auto doc = nlohmann::json::parse(read_text(path("c1/compare.json")));
  ASSERT_EQ(doc["models"].size(), 3u);
  EXPECT_EQ(doc["models"][2]["name"], "zirr_kaplanyan");
  EXPECT_NE(read_text(path("c1/index.html")).find("zirr_kaplanyan"), std::string::npos);
  EXPECT_NE(read_text(path("c1/compare.csv")).find("\nzirr_kaplanyan,"), std::string::npos);
  // claims.json holds no rows: a built-in model shows its recorded verdicts, labelled so; the
  // plug-in has none to show, except the property it declares it does not claim.
  for (const auto& v : model_named(doc, "deliot_belcour")["conformance"])
    EXPECT_EQ(v["origin"], "recorded") << v.dump();
  for (const auto& v : model_named(doc, "zirr_kaplanyan")["conformance"]) {
    EXPECT_NE(v["origin"], "recorded") << v.dump();
    EXPECT_NE(v["origin"], "measured") << v.dump();
  }
  // Swept here, so measured; every model gets timings and a curve or a reason for none.
  for (const auto& m : doc["models"]) {
    EXPECT_EQ(m["stability"][0]["origin"], "measured") << m["name"];
    EXPECT_GT(m["timing"]["scalar_ns_per_eval"].get<double>(), 0) << m["name"];
    EXPECT_TRUE(!m["equal_time"]["points"].empty() || m["equal_time"]["not_shown"].is_string())
        << m["name"];
  }
  EXPECT_EQ(model_named(doc, "smooth_ggx")["reference"][0]["method"], "cubature");
  EXPECT_EQ(model_named(doc, "deliot_belcour")["reference"][0]["method"], "monte-carlo");

  // The second run's compare.json is compared, not its page: the stand-in draws it
  // (CliTest::stand_in_charts; the page is drawn from compare.json alone).
  stand_in_charts();
  const RunResult two = compare("c2", "2");
  ASSERT_EQ(two.exit_code, 0) << two.err;
  const auto doc2 = nlohmann::json::parse(read_text(path("c2/compare.json")));
  EXPECT_EQ(without_timings(doc), without_timings(doc2));
}

TEST_F(CompareTest, ReadsVerdictsAndFailureRegionsFromEarlierRuns) {
  fs::create_directories(path("verify"));
  write_text(path("verify/claims.json"),
             R"([{"id": "model.smooth_ggx.energy", "verdict": "fails", "detail": "d",
                  "control_rejected": true}])");
  fs::create_directories(path("sweeps"));
  write_text(path("sweeps/stability.json"),
             R"({"models": [{"model": "smooth_ggx", "sampler": "vndf", "verdict": "holds",
                             "failure_region": "none found"}]})");
  const RunResult r = run({"compare", "--models", "smooth_ggx", "--claims-from", "verify",
                           "--sweeps-from", "sweeps", "--out", "c"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto m = nlohmann::json::parse(read_text(path("c/compare.json")))["models"][0];
  bool seen = false;
  for (const auto& v : m["conformance"]) {
    if (v["property"] != "energy") continue;
    seen = true;
    EXPECT_EQ(v["verdict"], "fails");  // what the file says, not the recorded "holds"
    EXPECT_EQ(v["origin"], "read");
  }
  EXPECT_TRUE(seen);
  ASSERT_EQ(m["stability"].size(), 1u);
  EXPECT_EQ(m["stability"][0]["failure_region"], "none found");
  EXPECT_EQ(m["stability"][0]["origin"], "read");
}

// Without --claims-from, compare runs the model's conformance checks itself, several at once
// (the costliest first), constant-time alone afterwards: every verdict, control and detail is the
// row `glintlab verify` writes for the same check, with one thread or two (constant-time's detail
// is a timing). deliot_belcour: the cheapest suite (about 1 s at quick) that takes every path of
// compare's scheduling: all ten properties (sampler-covers-value and energy in one job, stability
// with the failure regions, constant-time in the timed phase), verdicts that hold and one that
// fails.
TEST_F(CompareTest, MeasuredConformanceIsVerifysRowsWithOneOrTwoThreads) {
  stand_in_charts();  // compare.json is tested, not the page drawn from it
  const RunResult v =
      run({"verify", "--claims", "model.deliot_belcour.*", "--budget", "quick", "--out", "v"});
  ASSERT_TRUE(v.exit_code == 0 || v.exit_code == 1) << v.err;
  std::map<std::string, nlohmann::json> rows;
  for (const auto& row : nlohmann::json::parse(read_text(path("v/claims.json"))))
    rows[row["id"].get<std::string>()] = row;
  ASSERT_EQ(rows.size(), 10u);  // every property, measured
  nlohmann::json first;
  for (const char* threads : {"1", "2"}) {
    const std::string out = std::string("c") + threads;
    const RunResult r =
        run({"compare", "--models", "deliot_belcour", "--threads", threads, "--out", out});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto doc = nlohmann::json::parse(read_text(path(out + "/compare.json")));
    const auto& conformance = model_named(doc, "deliot_belcour")["conformance"];
    ASSERT_EQ(conformance.size(), rows.size());
    for (const auto& c : conformance) {
      const std::string id = "model.deliot_belcour." + c["property"].get<std::string>();
      ASSERT_TRUE(rows.count(id)) << id;
      const auto& row = rows.at(id);
      EXPECT_EQ(c["origin"], "measured") << id;
      EXPECT_EQ(c["verdict"], row["verdict"]) << id;
      EXPECT_EQ(c["control_rejected"], row["control_rejected"]) << id;
      if (c["property"] != "constant-time") {
        EXPECT_EQ(c["detail"], row["detail"]) << id;
      }
    }
    EXPECT_EQ(model_named(doc, "deliot_belcour")["stability"][0]["origin"], "measured");
    if (first.is_null()) {
      first = doc;
      continue;
    }
    // Every field but the timings (and constant-time's detail, a timing) for either thread count.
    auto a = without_timings(first), b = without_timings(doc);
    for (auto* d : {&a, &b})
      for (auto& c : (*d)["models"][0]["conformance"])
        if (c["property"] == "constant-time") c.erase("detail");
    EXPECT_EQ(a, b);
  }
}

// --verbose says where the time went (every measurement of the parallel phase, each timed step of
// each model, the phases' wall and CPU seconds) and changes nothing else; without it, none of that.
TEST_F(CompareTest, VerboseSaysWhereTheTimeWentAndChangesNothingElse) {
  stand_in_charts();  // the page's step is timed whoever draws it; its files are not tested
  fs::create_directories(path("verify"));
  write_text(path("verify/claims.json"), "[]\n");
  fs::create_directories(path("sweeps"));
  write_text(path("sweeps/stability.json"), R"({"models": []})");
  const auto compare = [&](const std::string& out, bool verbose) {
    std::vector<std::string> args{"compare", "--models", "smooth_ggx", "--claims-from", "verify",
                                  "--sweeps-from", "sweeps", "--out", out};
    if (verbose) args.push_back("--verbose");
    return run(args);
  };
  const RunResult quiet = compare("q", false), verbose = compare("v", true);
  ASSERT_EQ(quiet.exit_code, 0) << quiet.err;
  ASSERT_EQ(verbose.exit_code, 0) << verbose.err;
  for (const char* line :
       {"compare: where the time went", "smooth_ggx           reference 30°",
        "smooth_ggx           reference 70°", "smooth_ggx           timed: ns/eval",
        "smooth_ggx           timed: equal-time curve", "parallel phase: ",
        "timed phase, smooth_ggx: ", "timed phase: ", "; page: "}) {
    EXPECT_NE(verbose.err.find(line), std::string::npos) << line << "\n" << verbose.err;
    EXPECT_EQ(quiet.err.find(line), std::string::npos) << line << "\n" << quiet.err;
  }
  EXPECT_EQ(without_timings(nlohmann::json::parse(read_text(path("q/compare.json")))),
            without_timings(nlohmann::json::parse(read_text(path("v/compare.json")))));
}

TEST_F(CompareTest, MalformedClaimsFileIsAnErrorAndWritesNothing) {
  fs::create_directories(path("verify"));
  write_text(path("verify/claims.json"), "[{\"id\": ");
  expect_input_error(run({"compare", "--models", "smooth_ggx", "--claims-from", "verify",
                          "--sweeps-from", "verify", "--out", "c"}),
                     {"--sweeps-from", "stability.json"}, {"verify", "verify/claims.json"});
  fs::create_directories(path("sweeps"));
  write_text(path("sweeps/stability.json"), "{\"models\": []}");
  expect_input_error(run({"compare", "--models", "smooth_ggx", "--claims-from", "verify",
                          "--sweeps-from", "sweeps", "--out", "c"}),
                     {"--claims-from", "malformed"},
                     {"verify", "verify/claims.json", "sweeps", "sweeps/stability.json"});
}

}  // namespace
}  // namespace glintlab::cli_test
