// run_claim<C> (verify/claim_runner.h) on toy claims: the control rule picks the perturbed input
// for a holding claim and the corrected one for a failing claim, a control that does not oppose
// is reported NOT rejected, the regime is set only for holds-in-regime (a claim's regime(sizes) in
// place of kRegime), a control text without the runner's verdict where the claim says so, a
// control of several inputs that opposes only where every part is caught (control_sensitive), the
// registry entry carries the claim's metadata, and the result does not depend on the thread count.
#include "verify/claim_runner.h"

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <cmath>
#include <span>
#include <string>

#include "core/math/rng.h"

namespace glintlab::verify {
namespace {

enum class Toy { kHolds, kHoldsInRegime, kFails, kFailsWithoutCorrection };

// "The mean of the configurations' values is 1": each value 1 (+ 0.1 where the toy fails) with
// a ±0.0005 jitter from its seed. Perturbed input: the mean + 0.1; corrected: the mean − the toy's
// error.
template <Toy kToy>
struct ToyMean {
  static constexpr bool kFailing = kToy == Toy::kFails || kToy == Toy::kFailsWithoutCorrection;
  static constexpr double kError = kFailing ? 0.1 : 0.0;
  static constexpr std::string_view kId = "toy.mean";
  static constexpr std::string_view kPaper = "toy paper";
  static constexpr std::string_view kSource = "Eq. 1";
  static constexpr std::string_view kQuote = "the toy mean is zero";
  static constexpr std::string_view kStatistic = "|mean − 1|";
  static constexpr std::string_view kRegime = "toy regime";
  static constexpr Expected kExpected{.quick = kFailing ? Verdict::kFails : Verdict::kHolds,
                                      .full = Verdict::kInconclusive,
                                      .why_full_differs = "toy note"};
  static constexpr bool kHasCorrectedControl = kToy != Toy::kFailsWithoutCorrection;

  struct Sizes {
    int n;
  };
  static Sizes sizes(Budget b) { return {b == Budget::kQuick ? 8 : 64}; }
  static Sizes probe_sizes() { return {4}; }
  using Evidence = double;
  static int configurations(const Sizes& z) { return z.n; }
  static double observe(const Sizes&, int, std::uint64_t seed) {
    return 1 + kError + 1e-3 * (counter_uniform<double>(seed, 0, 0) - 0.5);
  }
  using Measured = double;
  static double measure(const Sizes&, std::span<const double> e, Input input) {
    double m = 0;
    for (double v : e) m += v / double(e.size());
    return input == Input::kPerturbed ? m + 0.1 : input == Input::kCorrected ? m - kError : m;
  }
  static Decision decide(const Sizes& z, const double& m) {
    const bool ok = std::abs(m - 1) <= 0.01;
    return {.verdict = !ok                           ? Verdict::kFails
                       : kToy == Toy::kHoldsInRegime ? Verdict::kHoldsInRegime
                                                     : Verdict::kHolds,
            .value = std::abs(m - 1),
            .bound = 0.01,
            .configurations = z.n};
  }
  static std::string describe(const Sizes&, const double& m, Input input) {
    return fmt::format("{} mean {:.6f}", input == Input::kGenuine ? "genuine" : "control", m);
  }
  static std::string power(const Sizes&, const double&, const double& control) {
    return fmt::format("control off by {:.3f}", std::abs(control - 1));
  }
};

TEST(ClaimRunner, HoldingClaimGetsThePerturbedControl) {
  const CheckResult r = run_claim<ToyMean<Toy::kHolds>>({8});
  EXPECT_EQ(r.verdict, Verdict::kHolds);
  EXPECT_EQ(r.control_verdict, Verdict::kFails);
  EXPECT_TRUE(r.control_rejected);
  EXPECT_EQ(r.control.rfind("control mean 1.1", 0), 0u) << r.control;
  EXPECT_NE(r.control.find("→ fails (rejected)"), std::string::npos) << r.control;
  EXPECT_EQ(r.statistic, "|mean − 1|");
  EXPECT_EQ(r.bound, 0.01);
  EXPECT_EQ(r.configurations, 8);
  EXPECT_TRUE(r.regime.empty());
  EXPECT_EQ(r.power.rfind("control off by 0.1", 0), 0u) << r.power;
}

TEST(ClaimRunner, FailingClaimGetsTheCorrectedControl) {
  const CheckResult r = run_claim<ToyMean<Toy::kFails>>({8});
  EXPECT_EQ(r.verdict, Verdict::kFails);
  EXPECT_EQ(r.control_verdict, Verdict::kHolds);
  EXPECT_TRUE(r.control_rejected) << r.control;
}

// Without a corrected input the perturbed one is all there is, and it cannot oppose "fails".
TEST(ClaimRunner, ControlThatAgreesIsNotRejected) {
  const CheckResult r = run_claim<ToyMean<Toy::kFailsWithoutCorrection>>({8});
  EXPECT_EQ(r.verdict, Verdict::kFails);
  EXPECT_EQ(r.control_verdict, Verdict::kFails);
  EXPECT_FALSE(r.control_rejected);
  EXPECT_NE(r.control.find("(NOT rejected)"), std::string::npos) << r.control;
}

TEST(ClaimRunner, RegimeOnlyForHoldsInRegime) {
  EXPECT_EQ(run_claim<ToyMean<Toy::kHoldsInRegime>>({8}).regime, "toy regime");
  EXPECT_TRUE(run_claim<ToyMean<Toy::kFails>>({8}).regime.empty());
}

// A regime that names the sizes (regime(sizes), in place of kRegime) and a control whose text
// states its own verdict rule (control_text: no "→ verdict (rejected)" appended).
struct ToySizedRegime : ToyMean<Toy::kHoldsInRegime> {
  static std::string control_text(const Sizes& z, const double& control, Input input, Verdict) {
    return describe(z, control, input);
  }
  static std::string regime(const Sizes& z) { return fmt::format("toy regime at n = {}", z.n); }
};

TEST(ClaimRunner, RegimeOfTheSizesAndControlTextAsDescribed) {
  const CheckResult r = run_claim<ToySizedRegime>({8});
  EXPECT_EQ(r.verdict, Verdict::kHoldsInRegime);
  EXPECT_EQ(r.regime, "toy regime at n = 8");
  EXPECT_EQ(r.control_verdict, Verdict::kFails);
  EXPECT_TRUE(r.control_rejected);
  EXPECT_EQ(r.control.rfind("control mean 1.1", 0), 0u) << r.control;
  EXPECT_EQ(r.control.find("→"), std::string::npos) << r.control;
  EXPECT_TRUE(run_claim<ToySizedRegime>({8}).regime != run_claim<ToySizedRegime>({4}).regime);
}

TEST(ClaimRunner, RegistryEntryCarriesTheMetadata) {
  const Check c = claim_check<ToyMean<Toy::kHolds>>();
  EXPECT_EQ(c.id, "toy.mean");
  EXPECT_EQ(c.paper, "toy paper");
  EXPECT_EQ(c.source, "Eq. 1");
  EXPECT_EQ(c.expected, Verdict::kHolds);
  EXPECT_EQ(c.expected_for(Budget::kFull), Verdict::kInconclusive);
  EXPECT_EQ(c.budget_note, "toy note");
  EXPECT_FALSE(c.calibration);
  EXPECT_EQ(c.run(Budget::kFull).configurations, 64);
  const ClaimProbe p = probe_claim<ToyMean<Toy::kFails>>();
  EXPECT_EQ(p.result.configurations, 4);
  EXPECT_EQ(p.perturbed, Verdict::kFails);
  EXPECT_EQ(p.corrected, Verdict::kHolds);
}

// A statistical claim: its calibrate becomes the registry entry's calibration.
struct CalibratedToy : ToyMean<Toy::kHolds> {
  static double calibrate(std::uint64_t seed) { return counter_uniform<double>(seed, 1, 0); }
};

TEST(ClaimRunner, CalibrateBecomesTheCalibration) {
  const Check c = claim_check<CalibratedToy>();
  ASSERT_TRUE(c.calibration);
  EXPECT_EQ(c.calibration(7), counter_uniform<double>(7, 1, 0));
  EXPECT_TRUE(is_statistical(c));
}

// A claim whose own rule reports "inconclusive" for a measured "fails" (not a separate finding,
// Decision::measured_verdict): the control is picked and judged against the measured "fails", and
// the result keeps it.
template <Toy kToy>
struct NotASeparateFinding : ToyMean<kToy> {
  static Decision decide(const typename ToyMean<kToy>::Sizes& z, const double& m) {
    Decision d = ToyMean<kToy>::decide(z, m);
    // The genuine measurement's "fails" (mean 1.1; the perturbed input's is 1.2).
    if (d.verdict == Verdict::kFails && m < 1.15)
      d.measured_verdict = d.verdict, d.verdict = Verdict::kInconclusive;
    return d;
  }
};

TEST(ClaimRunner, MeasuredVerdictPicksAndJudgesTheControl) {
  const CheckResult r = run_claim<NotASeparateFinding<Toy::kFails>>({8});
  EXPECT_EQ(r.verdict, Verdict::kInconclusive);
  EXPECT_EQ(r.measured_verdict, Verdict::kFails);
  EXPECT_EQ(r.control_verdict, Verdict::kHolds);  // the corrected input, as for "fails"
  EXPECT_TRUE(r.control_rejected) << r.control;
  // A perturbed control that fails too does not oppose the measured "fails" (it would oppose the
  // reported "inconclusive").
  const CheckResult q = run_claim<NotASeparateFinding<Toy::kFailsWithoutCorrection>>({8});
  EXPECT_EQ(q.verdict, Verdict::kInconclusive);
  EXPECT_EQ(q.control_verdict, Verdict::kFails);
  EXPECT_FALSE(q.control_rejected) << q.control;
  // Without the rule: no measured verdict kept.
  EXPECT_FALSE(run_claim<ToyMean<Toy::kFails>>({8}).measured_verdict.has_value());
}

// A control of several inputs (control_sensitive): the corrected input holds, but where the
// check is not also seen to catch a near-truth error the control does not oppose; its verdict is
// kept either way.
template <bool kSensitive>
struct PartlySensitive : ToyMean<Toy::kFails> {
  static bool control_sensitive(const Sizes&, const double&) { return kSensitive; }
};

TEST(ClaimRunner, ControlSensitiveGatesTheRejection) {
  const CheckResult caught = run_claim<PartlySensitive<true>>({8});
  EXPECT_EQ(caught.control_verdict, Verdict::kHolds);
  EXPECT_TRUE(caught.control_rejected) << caught.control;
  const CheckResult missed = run_claim<PartlySensitive<false>>({8});
  EXPECT_EQ(missed.control_verdict, Verdict::kHolds);
  EXPECT_FALSE(missed.control_rejected) << missed.control;
  EXPECT_NE(missed.control.find("(NOT rejected)"), std::string::npos) << missed.control;
}

TEST(ClaimRunner, SameResultOnOneAndTwoThreads) {
  CheckResult one, two;
  tbb::task_arena(1).execute([&] { one = run_claim<ToyMean<Toy::kHolds>>({64}); });
  tbb::task_arena(2).execute([&] { two = run_claim<ToyMean<Toy::kHolds>>({64}); });
  EXPECT_EQ(one.value, two.value);
  EXPECT_EQ(one.detail, two.detail);
  EXPECT_EQ(one.control, two.control);
}

}  // namespace
}  // namespace glintlab::verify
