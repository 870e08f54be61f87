// Every claim that is a type (verify/claim.h), run by the one runner at its probe size: its
// recorded probe verdict, a control that opposes it, the perturbed input failing and the corrected
// one (where the claim has one) holding. One typed test over the papers' lists: a claim added to a
// list is tested here with no edit.
#include <gtest/gtest.h>

#include <cctype>
#include <string>
#include <vector>

#include "verify/check.h"
#include "verify/claim.h"
#include "verify/claims/podee/list.h"

namespace glintlab::verify {
namespace {

// The claim types are declared, not defined, here (their files instantiate probe_claim); a
// complete wrapper names each for GoogleTest.
template <typename C>
struct Tag {
  using Claim = C;
};
template <typename List>
struct TagsOf;
template <typename... Cs>
struct TagsOf<ClaimList<Cs...>> {
  using type = ::testing::Types<Tag<Cs>...>;
};

// Test names from the claims' ids (podee.far-failure → podee_far_failure).
struct ClaimName {
  template <typename T>
  static std::string GetName(int) {
    std::string n = claim_check<typename T::Claim>().id;
    for (char& ch : n)
      if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
    return n;
  }
};

template <typename T>
class ClaimProbes : public ::testing::Test {};
TYPED_TEST_SUITE(ClaimProbes, TagsOf<podee_claims::Claims>::type, ClaimName);

TYPED_TEST(ClaimProbes, VerdictAndControlsAtProbeSize) {
  const ClaimProbe p = probe_claim<typename TypeParam::Claim>();
  const CheckResult& r = p.result;
  SCOPED_TRACE(p.id + ": " + r.detail);
  EXPECT_EQ(std::string(to_string(r.verdict)), to_string(p.expected.probe));
  EXPECT_TRUE(r.control_rejected) << r.control;
  ASSERT_TRUE(r.control_verdict.has_value());
  EXPECT_TRUE(control_opposes(r.verdict, *r.control_verdict)) << r.control;
  // Each control input on its own: the perturbed one fails, the corrected one holds.
  EXPECT_EQ(std::string(to_string(p.perturbed)), "fails");
  if (p.corrected) {
    EXPECT_TRUE(is_holding(*p.corrected)) << to_string(*p.corrected);
  }
  EXPECT_EQ(r.verdict == Verdict::kHoldsInRegime, !r.regime.empty()) << r.regime;
  EXPECT_GT(r.configurations, 0);
  EXPECT_FALSE(r.statistic.empty());
  EXPECT_FALSE(r.power.empty());
}

// The lists are registered in order, with the papers' readings attached, and their recorded
// verdicts.
TEST(ClaimLists, PodeeRegisteredInOrder) {
  std::vector<std::string> ids;
  for (const Check& c : registered_checks())
    if (c.id.rfind("podee.", 0) == 0) {
      ids.push_back(c.id);
      EXPECT_EQ(c.paper, "Podee, Max, Iwasaki & Dobashi");
      EXPECT_FALSE(c.paper_quote.empty()) << c.id;
      EXPECT_EQ(c.id == "podee.rmse" ? Verdict::kInconclusive : Verdict::kHolds, c.expected)
          << c.id;
    }
  EXPECT_EQ(ids, (std::vector<std::string>{"podee.brightest-vector", "podee.rmse",
                                           "podee.far-failure", "podee.stability"}));
}

}  // namespace
}  // namespace glintlab::verify
