// chermain.ggaa-sk — Chermain et al. 2021, Fig. 9, Sec. 6.2.
//
// The paper, Sec. 6.2: "Small kernels (s_K = 0.5) yield results closer to the reference, but
// induce more specular shimmering in the animated sequences (see supplemental video)." Fig. 9:
// "RMSEs obtained with s_K = 1 are higher than RMSEs obtained with s_K = 0.5" (7.794 vs 7.425 %
// with projected half vectors, 8.185 vs 7.527 % with half slopes).
//
// Measured: on K replicates of the normal-mapped tubes (common.h; the shading normal varies within
// pixels, as on Fig. 9's lion head; each replicate its own glint layout, sub-pixel camera offset
// and two independent references whose every sample has its own footprint, the paper's 1,024-spp
// supersampled reference), the display RMSE % of Eq. 21 and of Eq. 20 at s_K 0.5 and 1; per
// derivative variant the per-replicate differences s_K 1 − s_K 0.5, decided by paired t intervals
// (99 %, Šidák over the two parts): holds when both lie above 0, fails when one lies below
// −tolerance (the larger of 0.1 RMSE points, Fig. 9's smallest ordering, and the reference's own
// error of the difference), else a tie. The replicates are shared with chermain.ggaa-derivatives.
// Control: an independent reference × 1.03 (near truth) in place of s_K 1 (perturbed, when the
// genuine verdict holds) or of s_K 0.5 (corrected, otherwise).
// Regime: none (the paper's, Fig. 9: a normal map without LEAN, 1 spp, GGAA at s_K 0.5 and 1; here
// bumps 4 pixels wide, rms slope 0.1, on the tubes of Fig. 8).
#include "verify/claim_runner.h"
#include "verify/claims/chermain/common.h"

namespace glintlab::verify::chermain_claims {

struct GgaaSk : BumpyOrderingClaim<GgaaSk> {
  static constexpr std::string_view kId = "chermain.ggaa-sk";
  static constexpr std::string_view kPaper = chermain_claims::kPaper;
  static constexpr std::string_view kSource = "Fig. 9, Sec. 6.2";
  // The paper's own sentence or equation the claim is judged against.
  static constexpr std::string_view kQuote =
      "Sec. 6.2: \"Small kernels (s_K = 0.5) yield results closer to the reference, but "
      "induce more specular shimmering in the animated sequences (see supplemental "
      "video).\" Fig. 9: \"RMSEs obtained with s_K = 1 are higher than RMSEs obtained "
      "with s_K = 0.5\" (7.794 vs 7.425 % with projected half vectors, 8.185 vs 7.527 % "
      "with half slopes)";
  // What the check tests beyond the quote (so a verdict on it is never the paper failing).
  static constexpr std::string_view kStrongerReading =
      "Fig. 9 is a normal-mapped lion head against a 1,024-spp reference; the "
      "check renders Fig. 8's tubes with a procedural bump map (4-pixel "
      "bumps, rms slope 0.1) against a reference whose every sample has its "
      "own footprint (256 spp quick, 1,024 full), with both derivative "
      "variants (Fig. 9 shows both); a reversal counts only beyond 0.1 RMSE "
      "points or the reference's own error. It shares its measurement with "
      "chermain.ggaa-derivatives.";
  // The competing causes reviewed for a "fails" (verify/finding_rule.h): how each was ruled
  // out, or why it is still open.
  static std::vector<Alternative> alternatives() {
    return {{"tolerance",
             "excluded: s_K = 1 is lower by 2.1–2.3 RMSE points at both budgets and with both "
             "derivatives, every interval below −1.4, against a tolerance of 0.1 points (Fig. 9's "
             "smallest ordering) and a reference's own error of the difference of at most 0.08",
             true},
            {"scene or reference mismatch (what the reference is)",
             "not excluded: against the per-sample-footprint reference (each sample at its own uv "
             "with a 1/32-pixel footprint, at least one microfacet) the glints come from another "
             "realization than the methods' (the pixel's LOD), and RMSE then rewards blur: the "
             "smooth limit, with no glints at all, scores 17.0 % (quick) and 21.4 % (full) against "
             "20.4–22.9 % and 26.4–29.1 % for every GGAA variant; against the other reading of a "
             "1,024-spp reference (jittered frames: each sample's footprint the pixel's size, the "
             "same realization) s_K = 1 also wins (full: 9.0 and 9.6 % against 13.3 and 14.3 %), "
             "but that pixel average spans more than the pixel, which a wider kernel approximates. "
             "The paper does not say which it used",
             false},
            {"regime",
             "not excluded: one scene (Fig. 8's tubes, α 0.35, 1.6e5 microfacets per unit uv, "
             "4-pixel bumps of rms slope 0.1); Fig. 9's lion head, its normal map, glint density "
             "and resolution are not given",
             false}};
  }
  static constexpr std::string_view kStatistic =
      "display RMSE % of s_K 1 − s_K 0.5 (Eq. 21, then Eq. 20), normal-mapped tubes: mean paired "
      "difference over replicates";
  // Measured "fails" at both budgets; the finding rule reports it inconclusive (a competing cause
  // is not excluded: alternatives() above). At the probe size (32×22, 4 replicates)
  // the reference's own error (5 % RMSE) leaves the orderings a tie.
  static constexpr Expected kExpected{.quick = Verdict::kInconclusive};

  static const Ordering& ordering() { return kSkOrdering; }
};

}  // namespace glintlab::verify::chermain_claims

GLINTLAB_CLAIM(glintlab::verify::chermain_claims::GgaaSk);
