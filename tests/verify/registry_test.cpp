// The claim registry: every check has a CLAIMS.md-style id, reaches the verdict it reaches today
// at the quick budget, and rejects its negative control. A verdict that changes is a regression or
// a discovery; either way this test makes a person look.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <ostream>
#include <set>
#include <string>
#include <vector>

#include "verify/check.h"
#include "verify/claim_runner.h"

namespace glintlab::verify {
namespace {

TEST(Registry, IdsUniqueAndExpected) {
  std::set<std::string> seen;
  for (const Check& c : registered_checks()) {
    EXPECT_TRUE(seen.insert(c.id).second) << "duplicate id " << c.id;
    EXPECT_NE(c.id.find('.'), std::string::npos) << c.id;
    EXPECT_FALSE(c.paper.empty()) << c.id;
    EXPECT_FALSE(c.source.empty()) << c.id;
  }
}

// The rule that decides whether a control rejects a check: the opposite verdict, in the right
// direction; it cannot be met by a control that merely agrees or is inconclusive.
TEST(Registry, ControlMustGetTheOppositeVerdict) {
  EXPECT_TRUE(control_opposes(Verdict::kHolds, Verdict::kFails));
  EXPECT_TRUE(control_opposes(Verdict::kHoldsInRegime, Verdict::kFails));
  EXPECT_TRUE(control_opposes(Verdict::kFails, Verdict::kHoldsWithin));
  EXPECT_FALSE(control_opposes(Verdict::kHolds, Verdict::kHoldsInRegime));
  EXPECT_FALSE(control_opposes(Verdict::kHolds, Verdict::kInconclusive));
  EXPECT_FALSE(control_opposes(Verdict::kFails, Verdict::kFails));
  EXPECT_TRUE(control_opposes(Verdict::kInconclusive, Verdict::kFails));  // decided
  EXPECT_FALSE(control_opposes(Verdict::kInconclusive, Verdict::kInconclusive));
  CheckResult r;
  r.verdict = Verdict::kHoldsWithin;
  run_control(r, true, [](Input) { return Verdict::kHoldsWithin; });
  EXPECT_FALSE(r.control_rejected);
  run_control(r, true, [](Input) { return Verdict::kFails; });
  EXPECT_TRUE(r.control_rejected);
  EXPECT_EQ(r.control_verdict, Verdict::kFails);
}

// The one control rule, as the conformance suite gets it at run time: a holding check gets the
// perturbed input, a failing or undecided one the corrected input where it has one.
TEST(Registry, ControlInputFollowsTheOneRule) {
  const auto picked = [](Verdict genuine, bool has_corrected) {
    CheckResult r;
    r.verdict = genuine;
    Input seen = Input::kGenuine;
    run_control(r, has_corrected, [&](Input in) { return seen = in, Verdict::kInconclusive; });
    return seen;
  };
  EXPECT_EQ(picked(Verdict::kHolds, true), Input::kPerturbed);
  EXPECT_EQ(picked(Verdict::kHoldsInRegime, true), Input::kPerturbed);
  EXPECT_EQ(picked(Verdict::kFails, true), Input::kCorrected);
  EXPECT_EQ(picked(Verdict::kInconclusive, true), Input::kCorrected);
  EXPECT_EQ(picked(Verdict::kFails, false), Input::kPerturbed);
}

TEST(Registry, SeedsDependOnIdAndConfiguration) {
  EXPECT_NE(check_seed("a.b", 0), check_seed("a.b", 1));
  EXPECT_NE(check_seed("a.b", 0), check_seed("a.c", 0));
  EXPECT_EQ(check_seed("a.b", 7), check_seed("a.b", 7));
}

// The check `id` at the quick budget: its recorded verdict, and a control that opposes it.
void expect_verdict_and_control(const std::string& id) {
  for (const Check& c : registered_checks()) {
    if (c.id != id) continue;
    const CheckResult r = c.run(Budget::kQuick);
    EXPECT_EQ(std::string(to_string(r.verdict)), to_string(c.expected)) << r.detail;
    EXPECT_TRUE(r.control_rejected) << r.control;
    // The control's verdict, from the same decision, opposes the genuine one.
    if (r.control_verdict) {
      EXPECT_TRUE(control_opposes(r.verdict, *r.control_verdict))
          << "verdict " << to_string(r.verdict) << ", control " << to_string(*r.control_verdict);
    }
    // A regime is named exactly when the verdict is holds-in-regime.
    EXPECT_EQ(r.verdict == Verdict::kHoldsInRegime, !r.regime.empty()) << r.regime;
    EXPECT_GT(r.configurations, 0);
    return;
  }
  FAIL() << "not registered: " << id;
}

class QuickBudget : public ::testing::TestWithParam<std::string> {};

TEST_P(QuickBudget, VerdictAndControl) { expect_verdict_and_control(GetParam()); }

// Claims decided on one measurement that a process makes once and shares between them: run in
// one test, so the measurement is made once, not once per claim (each claim's own process).
struct ClaimGroup {
  const char* name;
  std::vector<std::string> ids;
};
void PrintTo(const ClaimGroup& g, std::ostream* os) { *os << g.name; }
const std::vector<ClaimGroup>& shared_measurements() {
  static const std::vector<ClaimGroup> groups = {
      // The stability sweep of every registered model (verify/claims/across/common.cpp
      // suite_sweeps): about 15 s each apart.
      {"stability_sweep", {"all.energy-gain", "all.probability", "all.variance"}},
      // The replicates of the GGAA renders (verify/claims/chermain/common.h, replicate).
      {"chermain_ggaa_replicates", {"chermain.ggaa-error", "chermain.ggaa-shimmer"}},
      // The normal-mapped tubes' replicates, three 256-spp references each (replicate).
      {"chermain_bumpy_replicates", {"chermain.ggaa-derivatives", "chermain.ggaa-sk"}},
  };
  return groups;
}

bool in_shared_measurement(const std::string& id) {
  for (const ClaimGroup& g : shared_measurements())
    if (std::ranges::find(g.ids, id) != g.ids.end()) return true;
  return false;
}

// Every paper claim. The models' conformance checks are not run here: the `suite` test
// (suite.conformance_quick_reproduces_recorded_rows) runs every model's at the quick budget and
// compares each row, verdict and control included, with its recorded row; their generator,
// controls and broken models are tested by tests/verify/conformance. The claims that share
// a measurement run together in Checks/SharedMeasurement.*. all.stability is run
// with these assertions and more by PluginTest.SweepFigureAndGenericClaimCoverThePluginModel
// (tests/cli/plugin_test.cpp), which the sanitized run includes.
std::vector<std::string> all_ids() {
  std::vector<std::string> ids;
  for (const Check& c : registered_checks())
    if (c.family.empty() && c.id != "all.stability" && !in_shared_measurement(c.id))
      ids.push_back(c.id);
  return ids;
}

INSTANTIATE_TEST_SUITE_P(Checks, QuickBudget, ::testing::ValuesIn(all_ids()),
                         [](const auto& param_info) {
                           std::string n = param_info.param;
                           for (char& ch : n)
                             if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
                           return n;
                         });

class SharedMeasurement : public ::testing::TestWithParam<ClaimGroup> {};

TEST_P(SharedMeasurement, QuickVerdictsAndControls) {
  for (const std::string& id : GetParam().ids) {
    SCOPED_TRACE(id);
    expect_verdict_and_control(id);
  }
}

INSTANTIATE_TEST_SUITE_P(Checks, SharedMeasurement, ::testing::ValuesIn(shared_measurements()),
                         [](const auto& param_info) { return std::string(param_info.param.name); });

}  // namespace
}  // namespace glintlab::verify
