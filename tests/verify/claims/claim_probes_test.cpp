// Every claim that is a type (verify/claim.h), run by the one runner at its probe size: its
// recorded probe verdict, a control that opposes it, the perturbed input failing and the corrected
// one (where the claim has one) holding. One typed test over the papers' lists: a claim added to a
// list is tested here with no edit.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "verify/check.h"
#include "verify/claim.h"
#include "verify/claims/across/list.h"
#include "verify/claims/adequacy/list.h"
#include "verify/claims/chermain/list.h"
#include "verify/claims/eto/list.h"
#include "verify/claims/kemppinen/list.h"
#include "verify/claims/kneiphof/list.h"
#include "verify/claims/podee/list.h"
#include "verify/claims/smooth/list.h"

namespace glintlab::verify {

// The claim types are declared, not defined, here (their files instantiate probe_claim); a
// complete wrapper names each for GoogleTest, and ctest names the test after it:
// ClaimProbes.VerdictAndControlsAtProbeSize<glintlab::verify::Probe<…::podee_claims::Rmse>>.
template <typename C>
struct Probe {
  using Claim = C;
};

namespace {

template <typename... Lists>
struct ProbesOf;
template <typename... Cs>
struct ProbesOf<ClaimList<Cs...>> {
  using type = ::testing::Types<Probe<Cs>...>;
};
// Several papers' lists, joined.
template <typename... As, typename... Bs, typename... Rest>
struct ProbesOf<ClaimList<As...>, ClaimList<Bs...>, Rest...>
    : ProbesOf<ClaimList<As..., Bs...>, Rest...> {};

template <typename T>
class ClaimProbes : public ::testing::Test {};
// Not the across-method all.* claims: their probe size is the quick budget (the stability sweep of
// every model has no smaller size, and verify/stability is stamped), where each probe, in its own
// process, would sweep the whole suite again (35–69 s each); Checks/SharedMeasurement runs the
// four through the same runner at quick, genuine and control, on one sweep.
using AllProbes =
    ProbesOf<smooth_claims::Claims, eto_claims::Claims, kemppinen_claims::Claims,
             kneiphof_claims::Claims, chermain_claims::Claims, podee_claims::Claims,
             adequacy_claims::Claims>::type;
TYPED_TEST_SUITE(ClaimProbes, AllProbes);

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
TEST(ClaimLists, SmoothRegisteredFirstInOrder) {
  std::vector<std::string> ids;
  for (const Check& c : registered_checks())
    if (c.id.rfind("smooth.", 0) == 0) {
      ids.push_back(c.id);
      EXPECT_FALSE(c.paper_quote.empty()) << c.id;
      EXPECT_EQ(c.expected, Verdict::kHolds) << c.id;
      EXPECT_EQ(is_statistical(c), c.id == "smooth.sampler-matches-pdf") << c.id;
    }
  EXPECT_EQ(
      ids, (std::vector<std::string>{"smooth.projected-area", "smooth.vndf-normalized",
                                     "smooth.sampler-matches-pdf", "smooth.eval-pdf-consistency"}));
  EXPECT_EQ(registered_checks().front().id, "smooth.projected-area");
}

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

TEST(ClaimLists, KemppinenRegisteredInOrderAfterEto) {
  std::vector<std::string> ids;
  std::vector<Verdict> expected;
  std::string before;  // the id registered just before the first kemppinen claim
  for (const Check& c : registered_checks()) {
    if (c.id.rfind("kemppinen.", 0) == 0) {
      ids.push_back(c.id), expected.push_back(c.expected);
      EXPECT_EQ(c.paper, "Kemppinen et al. 2025");
      EXPECT_FALSE(c.paper_quote.empty()) << c.id;
      // The statistical claims keep their calibration (and so count in the suite's level).
      EXPECT_EQ(bool(c.calibration), c.id == "kemppinen.jacobian" || c.id == "kemppinen.roulette" ||
                                         c.id == "kemppinen.furnace" ||
                                         c.id == "kemppinen.sampling-unbiased")
          << c.id;
      EXPECT_FALSE(c.expected_full.has_value()) << c.id;
    } else if (ids.empty()) {
      before = c.id;
    }
  }
  EXPECT_EQ(before, "eto.backfacing-stable-pdf");
  EXPECT_EQ(ids, (std::vector<std::string>{
                     "kemppinen.jacobian", "kemppinen.convergence", "kemppinen.compensation",
                     "kemppinen.compensation-k16", "kemppinen.roulette", "kemppinen.furnace",
                     "kemppinen.constant-time", "kemppinen.sampling-unbiased"}));
  EXPECT_EQ(expected, (std::vector<Verdict>{Verdict::kFails, Verdict::kHoldsInRegime,
                                            Verdict::kHolds, Verdict::kHoldsInRegime,
                                            Verdict::kHoldsWithin, Verdict::kHolds, Verdict::kHolds,
                                            Verdict::kHolds}));
}

TEST(ClaimLists, KneiphofRegisteredInOrder) {
  std::vector<std::string> ids;
  std::vector<Verdict> expected;
  for (const Check& c : registered_checks())
    if (c.id.rfind("kneiphof.", 0) == 0) {
      ids.push_back(c.id), expected.push_back(c.expected);
      EXPECT_EQ(c.paper, "Kneiphof & Klein 2024");
      EXPECT_FALSE(c.paper_quote.empty()) << c.id;
      // The statistical claims keep their calibration (and so count in the suite's level).
      EXPECT_EQ(bool(c.calibration),
                c.id == "kneiphof.discrete-ndf-mean" || c.id == "kneiphof.subdivision")
          << c.id;
    }
  EXPECT_EQ(ids,
            (std::vector<std::string>{"kneiphof.total-area", "kneiphof.discrete-ndf-mean",
                                      "kneiphof.subdivision", "kneiphof.convergence",
                                      "kneiphof.cap-probability", "kneiphof.ltc-probability"}));
  EXPECT_EQ(expected, (std::vector<Verdict>{Verdict::kHoldsWithin, Verdict::kHolds, Verdict::kHolds,
                                            Verdict::kHoldsWithin, Verdict::kHoldsInRegime,
                                            Verdict::kInconclusive}));
}

TEST(ClaimLists, ChermainRegisteredInOrder) {
  std::vector<std::string> ids;
  std::vector<Verdict> expected;
  for (const Check& c : registered_checks())
    if (c.id.rfind("chermain.", 0) == 0) {
      ids.push_back(c.id), expected.push_back(c.expected);
      EXPECT_EQ(c.paper, "Chermain et al. 2021");
      EXPECT_FALSE(c.paper_quote.empty()) << c.id;
      EXPECT_FALSE(c.calibration) << c.id;
      EXPECT_FALSE(c.expected_full.has_value()) << c.id;
    }
  EXPECT_EQ(ids, (std::vector<std::string>{
                     "chermain.kernel-normalized", "chermain.dictionary-converges",
                     "chermain.correlation", "chermain.ggaa-error", "chermain.ggaa-derivatives",
                     "chermain.ggaa-sk", "chermain.ggaa-shimmer", "chermain.lean-correlation"}));
  EXPECT_EQ(expected,
            (std::vector<Verdict>{Verdict::kHolds, Verdict::kHolds, Verdict::kHolds,
                                  Verdict::kHolds, Verdict::kInconclusive, Verdict::kInconclusive,
                                  Verdict::kHolds, Verdict::kHolds}));
}

TEST(ClaimLists, EtoRegisteredInOrder) {
  std::vector<std::string> ids;
  std::vector<Verdict> expected;
  for (const Check& c : registered_checks())
    if (c.id.rfind("eto.", 0) == 0) {
      ids.push_back(c.id), expected.push_back(c.expected);
      EXPECT_EQ(c.paper, c.id == "eto.pdf-matches" || c.id == "eto.bound-is-infimum" ||
                                 c.id == "eto.backfacing-stable-pdf"
                             ? "Eto & Tokuyoshi 2023"
                             : "Eto & Tokuyoshi 2023 (vs Dupuy & Benyoub 2023)")
          << c.id;
      EXPECT_FALSE(c.paper_quote.empty()) << c.id;
      // The statistical claims keep their calibration (and so count in the suite's level).
      EXPECT_EQ(bool(c.calibration), c.id == "eto.pdf-matches" || c.id == "eto.unbiased" ||
                                         c.id == "eto.fewer-rejections")
          << c.id;
      // Only eto.pdf-matches is recorded otherwise at the full budget, with the reason.
      EXPECT_EQ(c.expected_full.has_value(), c.id == "eto.pdf-matches") << c.id;
      EXPECT_EQ(c.budget_note.empty(), c.id != "eto.pdf-matches") << c.id;
    }
  EXPECT_EQ(ids,
            (std::vector<std::string>{"eto.pdf-matches", "eto.unbiased", "eto.bound-is-infimum",
                                      "eto.fewer-rejections", "eto.variance-rough",
                                      "eto.variance-smooth", "eto.backfacing-stable-pdf"}));
  EXPECT_EQ(expected, (std::vector<Verdict>{Verdict::kHolds, Verdict::kHolds, Verdict::kHolds,
                                            Verdict::kHolds, Verdict::kHoldsInRegime,
                                            Verdict::kHoldsInRegime, Verdict::kHolds}));
}

TEST(ClaimLists, AcrossRegisteredInOrder) {
  std::vector<std::string> ids;
  std::vector<Verdict> expected;
  for (const Check& c : registered_checks())
    if (c.id.rfind("all.", 0) == 0) {
      ids.push_back(c.id), expected.push_back(c.expected);
      EXPECT_EQ(c.paper, "every registered model (core/model_registry.cpp)");
      EXPECT_FALSE(c.paper_quote.empty()) << c.id;
      EXPECT_FALSE(c.calibration) << c.id;  // rules decided without a p-value
      // Only all.energy-gain is recorded otherwise at the full budget, with the reason.
      EXPECT_EQ(c.expected_full.has_value(), c.id == "all.energy-gain") << c.id;
      EXPECT_EQ(c.budget_note.empty(), c.id != "all.energy-gain") << c.id;
    }
  EXPECT_EQ(ids, (std::vector<std::string>{"all.stability", "all.energy-gain", "all.probability",
                                           "all.variance"}));
  EXPECT_EQ(expected, (std::vector<Verdict>{Verdict::kHolds, Verdict::kHolds, Verdict::kHolds,
                                            Verdict::kFails}));
}

// The adequacy claims, in order; the prediction keeps its calibration, and both are glintlab's
// rules with their sentences.
TEST(ClaimLists, AdequacyRegisteredInOrder) {
  std::vector<std::string> ids;
  std::vector<Verdict> expected;
  for (const Check& c : registered_checks())
    if (c.id.rfind("adequacy.", 0) == 0) {
      ids.push_back(c.id), expected.push_back(c.expected);
      EXPECT_EQ(c.paper, "glintlab (adequacy of the binomial family)");
      EXPECT_FALSE(c.paper_quote.empty()) << c.id;
      EXPECT_TRUE(c.glintlab_rule) << c.id;
      EXPECT_EQ(bool(c.calibration), c.id == "adequacy.prediction-matches-measurement") << c.id;
    }
  EXPECT_EQ(ids, (std::vector<std::string>{"adequacy.prediction-matches-measurement",
                                           "adequacy.choice-is-safe"}));
  EXPECT_EQ(expected, (std::vector<Verdict>{Verdict::kHoldsInRegime, Verdict::kHoldsInRegime}));
}

}  // namespace
}  // namespace glintlab::verify
