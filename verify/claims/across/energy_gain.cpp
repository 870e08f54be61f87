// all.energy-gain — glintlab's own rule (docs/verification.md), not a paper's claim.
//
// The rule: "where each method breaks (NaN, Inf, negative values, energy gain, p > 1, huge
// variance)"; per model: "no NaN/Inf/negative, gain or variance blow-up in the core domain". This
// claim: energy gain, a white-furnace albedo significantly above 1.
//
// Measured: the suite's sweep (verify/claims/across/common.h, shared with the other all.* claims):
// per cell the white-furnace albedo and its standard error; an albedo more than kGainSigmas
// standard errors above 1 is a finding. Decided per target as all.stability is.
// Control (perturbed): smooth_ggx with value and weight × 1.03 (verify/stability/nan_control.h);
// (corrected, where the claim fails) smooth_ggx as it is.
// Regime: the core domain (α ≥ 1e-3, anisotropy ≤ 100:1, front-facing θi ≤ 89°).
#include <fmt/format.h>

#include <algorithm>

#include "verify/claim_runner.h"
#include "verify/claims/across/common.h"

namespace glintlab::verify::across_claims {

struct EnergyGain : SweepClaim<EnergyGain> {
  static constexpr std::string_view kId = "all.energy-gain";
  // The paper's own sentence or equation the claim is judged against (glintlab's own rule).
  static constexpr std::string_view kQuote =
      "Not a paper's claim: glintlab's rule (docs/verification.md): \"where each method "
      "breaks (NaN, Inf, negative values, energy gain, p > 1, huge variance)\" "
      "(all.stability); per model: \"no NaN/Inf/negative, gain or variance blow-up in "
      "the core domain\"; this check: energy gain (a white-furnace albedo significantly "
      "above 1)";
  static constexpr bool kGlintlabRule = true;
  static constexpr std::string_view kStatistic =
      "model×sampler targets with a significant energy gain in the core domain";
  static constexpr Expected kExpected{
      .quick = Verdict::kHolds,
      .full = Verdict::kHoldsInRegime,
      .why_full_differs =
          "the full budget finds podee's white-furnace albedo above 1 at θi 89.95–89.999° for "
          "footprints s 0.1–0.32 (outside the core domain, hence holds-in-regime); there the "
          "albedo estimate is heavy-tailed, and 256 samples per cell (quick) leave a standard "
          "error too large to flag the gain, where 1024 (full) do, on a grid that also has "
          "s = 0.32"};
  static constexpr stability::DefectClass kKind = stability::DefectClass::kEnergyGain;

  static std::vector<const ModelEntry*> control_models(Input input) {
    if (input == Input::kCorrected) return corrected_models();
    return {&stability::gain_control_model()};
  }
  static std::string control_words(Input input) {
    if (input == Input::kCorrected) return std::string(kCorrectedWords);
    return fmt::format("smooth_ggx with value and weight × {:g}", stability::kGainControlScale);
  }
  // The gain seen with 90 % power from the per-cell standard errors of the albedo (cells with
  // noise): its median and 90th percentile.
  static std::string power_text(Budget, const std::vector<stability::ModelSweep>& suite) {
    std::vector<double> se;
    for (const stability::ModelSweep& s : suite)
      for (const stability::SweepMap& m : s.maps)
        for (const stability::CellStats& c : m.cells)
          if (c.albedo_error > 1e-12) se.push_back(c.albedo_error);
    std::sort(se.begin(), se.end());
    const double se_median = se.empty() ? 0 : se[se.size() / 2];
    const double se_p90 = se.empty() ? 0 : se[se.size() * 9 / 10];
    const double sigmas = stability::kGainSigmas;
    return fmt::format(
        "an albedo above 1 by {:g} standard errors is flagged: with the median per-cell SE "
        "{:.2g} (90th percentile {:.2g}) a gain of {:.2g} ({:.2g}) is seen with 90 % power",
        sigmas, se_median, se_p90, (sigmas + 1.2816) * se_median, (sigmas + 1.2816) * se_p90);
  }
};

}  // namespace glintlab::verify::across_claims

GLINTLAB_CLAIM(glintlab::verify::across_claims::EnergyGain);
