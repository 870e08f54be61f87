// chermain.ggaa-derivatives — Chermain et al. 2021, Fig. 9, Sec. 6.2.
//
// The paper, Sec. 6.2: "In Figure 9, we compare Equations 20 and 21: using finite differences of
// projected half vectors yields lower errors than half slopes." Fig. 9 (RMSE, half slopes vs
// projected half vectors: 7.527 vs 7.425 % at s_K = 0.5, 8.185 vs 7.794 % at s_K = 1):
// "Differences to the reference are also more prominent with half slopes derivatives".
//
// Measured: on the K replicates of the normal-mapped tubes that chermain.ggaa-sk reads (common.h),
// per s_K ∈ {0.5, 1} the per-replicate differences of display RMSE % half slope (Eq. 20) −
// projected half vector (Eq. 21), decided by paired t intervals (99 %, Šidák over the two parts):
// holds when both lie above 0, fails when one lies below −tolerance (the larger of 0.1 RMSE
// points and the reference's own error of the difference), else a tie. Beside it: Eq. 20's kernel
// is wider than Eq. 21's at the same s_K, so Eq. 21 at the s_K matching Eq. 20's median width is
// compared too. Where that comparison does not fail and chermain.ggaa-sk does not hold either, a
// measured "fails" is the kernel width, the cause ggaa-sk judges, not a separate finding: the
// claim then reports inconclusive and keeps "fails" as its measured verdict.
// Control: an independent reference × 1.03 (near truth) in place of half slope (perturbed, when
// the genuine verdict holds) or of projected half vector (corrected, otherwise).
// Regime: none (the paper's, Fig. 9, as chermain.ggaa-sk).
#include <fmt/format.h>

#include <span>
#include <string>
#include <vector>

#include "verify/claim_runner.h"
#include "verify/claims/chermain/common.h"

namespace glintlab::verify::chermain_claims {
namespace {

// What the derivatives' ordering is measured with: Eq. 21 at the matching kernel width against
// Eq. 20 at s_K 0.5, and chermain.ggaa-sk's own verdict on the same replicates.
struct DerivativesMeasured {
  OrderingMeasured ordering;
  PairedComparison matched = {};
  Verdict matched_verdict = Verdict::kInconclusive, sk = Verdict::kInconclusive;
};

}  // namespace

struct GgaaDerivatives : BumpyOrderingClaim<GgaaDerivatives> {
  static constexpr std::string_view kId = "chermain.ggaa-derivatives";
  static constexpr std::string_view kPaper = chermain_claims::kPaper;
  static constexpr std::string_view kSource = "Fig. 9, Sec. 6.2";
  // The paper's own sentence or equation the claim is judged against.
  static constexpr std::string_view kQuote =
      "Sec. 6.2: \"In Figure 9, we compare Equations 20 and 21: using finite "
      "differences of projected half vectors yields lower errors than half slopes.\" "
      "Fig. 9 (RMSE, half slopes vs projected half vectors: 7.527 vs 7.425 % at s_K = "
      "0.5, 8.185 vs 7.794 % at s_K = 1): \"Differences to the reference are also more "
      "prominent with half slopes derivatives\"";
  // What the check tests beyond the quote (so a verdict on it is never the paper failing).
  static constexpr std::string_view kStrongerReading =
      "Fig. 9 is a normal-mapped lion head against a 1,024-spp reference; the "
      "check renders Fig. 8's tubes with a procedural bump map (4-pixel "
      "bumps, rms slope 0.1) against a reference whose every sample has its "
      "own footprint (256 spp quick, 1,024 full), and requires Eq. 21 lower "
      "at both s_K beyond the replicate noise; a reversal counts only beyond "
      "0.1 RMSE points (the paper's smallest difference) or the reference's "
      "own error. It shares its measurement with chermain.ggaa-sk, and also "
      "compares the two at equal kernel width, which the paper does not.";
  // The competing causes reviewed for a "fails" (verify/finding_rule.h): how each was ruled
  // out, or why it is still open.
  static std::vector<Alternative> alternatives() {
    return {{"the kernel width (the cause chermain.ggaa-sk judges)",
             "not excluded, and not a separate finding: on the normal-mapped tubes Eq. 20's GGAA "
             "kernel is 2.0× as wide as Eq. 21's at the same s_K (median over pixels: 2.00 quick, "
             "2.03 full), and Eq. 21 at the s_K that matches that width (1.0) is lower than Eq. "
             "20 at 0.5 by 1.7 (quick) and 1.9 (full) RMSE points, the paper's order; the "
             "reversal at equal s_K is the wider kernel winning, which chermain.ggaa-sk measures "
             "and reports once",
             false},
            {"tolerance",
             "excluded: Eq. 20 is lower by 0.35–0.46 RMSE points with every interval below −0.1 "
             "(the paper's smallest ordering) and beyond the reference's own error of the "
             "difference (at most 0.03)",
             true},
            {"scene or reference mismatch",
             "not excluded: the same as for chermain.ggaa-sk (the reference the paper used is not "
             "stated, and either reading of it rewards a wider kernel)",
             false}};
  }
  static constexpr std::string_view kStatistic =
      "display RMSE % of half slope (Eq. 20) − projected half vector (Eq. 21), s_K 0.5 and 1, "
      "normal-mapped tubes: mean paired difference over replicates";
  static constexpr Expected kExpected{.quick = Verdict::kInconclusive};

  static const Ordering& ordering() {
    static const Ordering o{
        {{"projected half s_K 0.5", &BumpyGgaaReplicate::proj05, &BumpyGgaaReplicate::proj05_alt,
          "half slope s_K 0.5", &BumpyGgaaReplicate::half05, &BumpyGgaaReplicate::half05_alt},
         {"projected half s_K 1", &BumpyGgaaReplicate::proj1, &BumpyGgaaReplicate::proj1_alt,
          "half slope s_K 1", &BumpyGgaaReplicate::half1, &BumpyGgaaReplicate::half1_alt}}};
    return o;
  }

  using Measured = DerivativesMeasured;
  static Measured measure(const Sizes&, std::span<const Evidence> all, Input input) {
    Measured m{.ordering = measure_ordering(ordering(), all, input)};
    std::vector<double> matched;
    for (const BumpyGgaaReplicate& x : all) matched.push_back(x.half05 - x.proj_matched);
    m.matched = compare_paired(matched, kGgaaConfidence);
    m.matched_verdict = decide_paired({matched}, m.ordering.tolerance);
    m.sk = decide_paired(kSkOrdering.diffs(all), kSkOrdering.tolerance(all));
    return m;
  }

  // A genuine "fails" that is ggaa-sk's cause is reported inconclusive.
  static bool same_cause_as_sk(const Measured& m, Verdict measured) {
    return m.ordering.input == Input::kGenuine && measured == Verdict::kFails &&
           m.matched_verdict != Verdict::kFails && !is_holding(m.sk);
  }
  static Decision decide(const Sizes&, const Measured& m) {
    Decision d = decide_ordering(ordering(), m.ordering);
    if (same_cause_as_sk(m, d.verdict))
      d.measured_verdict = d.verdict, d.verdict = Verdict::kInconclusive;
    return d;
  }

  static std::string describe(const Sizes& z, const Measured& m, Input input) {
    const std::string ordered = describe_ordering(ordering(), z, m.ordering);
    if (input != Input::kGenuine) return ordered;
    const std::span<const BumpyGgaaReplicate> reps = m.ordering.reps;
    const std::string detail = fmt::format(
        "{}. Kernel width: Eq. 20's is {:.2f}× Eq. 21's at s_K 0.5 (median over pixels, mean over "
        "replicates); Eq. 21 at the matching s_K {:.3f} {:.3f} % RMSE against half slope s_K 0.5 "
        "{:.3f} %: difference {:+.3f}, {:.0f} % CI [{:+.3f}, {:+.3f}] → {} at equal width",
        ordered, mean_field(reps, &BumpyGgaaReplicate::width_ratio),
        mean_field(reps, &BumpyGgaaReplicate::matched_s_k),
        mean_field(reps, &BumpyGgaaReplicate::proj_matched),
        mean_field(reps, &BumpyGgaaReplicate::half05), m.matched.mean, 100 * kGgaaConfidence,
        m.matched.lo, m.matched.hi, to_string(m.matched_verdict));
    if (!same_cause_as_sk(m, decide_ordering(ordering(), m.ordering).verdict)) return detail;
    return fmt::format(
        "inconclusive, not a separate finding: the check measured \"fails\", but at equal kernel "
        "width Eq. 20 and Eq. 21 do not differ beyond the tolerance, so the reversal is the "
        "kernel width, the cause chermain.ggaa-sk judges ({} there). Measured: {}",
        to_string(m.sk), detail);
  }

  static std::string power(const Sizes& z, const Measured& m, const Measured&) {
    return paired_power(m.ordering.diffs, Ordering::unit, z.replicates);
  }
};

}  // namespace glintlab::verify::chermain_claims

GLINTLAB_CLAIM(glintlab::verify::chermain_claims::GgaaDerivatives);
