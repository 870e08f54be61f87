// The finding rule: a "fails" stands only when every competing cause is excluded; every claim
// carries the paper's sentence it is judged against; every claim recorded as failing has its
// competing causes reviewed and excluded.
#include "verify/finding_rule.h"

#include <gtest/gtest.h>

#include <map>
#include <set>
#include <string>

#include "verify/claim_runner.h"

namespace glintlab::verify {
namespace {

CheckResult failing_result() {
  CheckResult r;
  r.verdict = Verdict::kFails;
  r.detail = "the measurement";
  run_control(r, /*has_corrected=*/true, [](Input) { return Verdict::kHolds; });  // corrected: holds
  return r;
}

Check claim_with(std::vector<Alternative> alternatives) {
  Check c;
  c.id = "paper.claim";
  c.alternatives = std::move(alternatives);
  return c;
}

TEST(FindingRule, FailsStandsOnlyWithEveryCauseExcluded) {
  CheckResult r = failing_result();
  apply_finding_rule(claim_with({{"implementation bug", "cross-checked", true},
                                 {"tolerance", "fails at any tolerance", true}}),
                     r);
  EXPECT_EQ(r.verdict, Verdict::kFails);
  EXPECT_FALSE(r.measured_verdict);
  EXPECT_EQ(r.detail, "the measurement");
}

// A deliberately incomplete review: one cause open makes the failure inconclusive, names the
// cause, keeps the measurement and its measured verdict, and the control still opposes.
TEST(FindingRule, AnOpenCauseMakesItInconclusive) {
  CheckResult r = failing_result();
  apply_finding_rule(claim_with({{"implementation bug", "cross-checked", true},
                                 {"scene or reference mismatch", "another scene", false}}),
                     r);
  EXPECT_EQ(r.verdict, Verdict::kInconclusive);
  ASSERT_TRUE(r.measured_verdict);
  EXPECT_EQ(*r.measured_verdict, Verdict::kFails);
  EXPECT_NE(r.detail.find("scene or reference mismatch (another scene)"), std::string::npos)
      << r.detail;
  EXPECT_EQ(r.detail.find("implementation bug"), std::string::npos) << r.detail;
  EXPECT_NE(r.detail.find("the measurement"), std::string::npos);
  EXPECT_TRUE(r.control_rejected);
}

TEST(FindingRule, UnreviewedFailureIsInconclusive) {
  CheckResult r = failing_result();
  apply_finding_rule(claim_with({}), r);
  EXPECT_EQ(r.verdict, Verdict::kInconclusive);
  EXPECT_NE(r.detail.find("no competing cause reviewed"), std::string::npos) << r.detail;
}

TEST(FindingRule, LeavesHoldingClaimsAndConformanceAlone) {
  CheckResult holds;
  holds.verdict = Verdict::kHolds;
  apply_finding_rule(claim_with({}), holds);
  EXPECT_EQ(holds.verdict, Verdict::kHolds);
  CheckResult conformance = failing_result();
  Check model_check = claim_with({});
  model_check.family = "model.broken";
  apply_finding_rule(model_check, conformance);
  EXPECT_EQ(conformance.verdict, Verdict::kFails);
}

// A claim type without kQuote does not compile (the Claim concept); its quote reaches the check.
TEST(FindingRule, EveryClaimQuotesItsPaper) {
  for (const Check& c : registered_checks()) {
    if (!c.family.empty()) continue;
    EXPECT_FALSE(c.paper_quote.empty()) << c.id << " has no paper_quote";
    const bool rule = c.id.rfind("all.", 0) == 0 || c.id.rfind("adequacy.", 0) == 0;
    EXPECT_EQ(c.glintlab_rule, rule) << c.id;
  }
}

// A recorded "fails" (at either budget) is a finding: its causes are reviewed and all excluded.
// A review says how each cause was excluded or why it is open.
TEST(FindingRule, RecordedFailuresHaveEveryCauseExcluded) {
  for (const Check& c : registered_checks()) {
    if (!c.family.empty()) continue;
    for (Budget b : {Budget::kQuick, Budget::kFull}) {
      if (c.expected_for(b) != Verdict::kFails) continue;
      EXPECT_FALSE(c.alternatives.empty()) << c.id;
      EXPECT_FALSE(c.correction.empty()) << c.id << ": a finding names the smallest correction";
      for (const Alternative& a : c.alternatives)
        EXPECT_TRUE(a.excluded) << c.id << ": " << a.cause;
    }
  }
  for (const Check& c : registered_checks())
    for (const Alternative& a : c.alternatives) {
      EXPECT_FALSE(a.cause.empty()) << c.id;
      EXPECT_FALSE(a.how.empty()) << c.id << ": " << a.cause;
    }
}

}  // namespace
}  // namespace glintlab::verify
