// all.stability — glintlab's own rule (docs/verification.md), not a paper's claim.
//
// The rule: "where each method breaks (NaN, Inf, negative values, energy gain, p > 1, huge
// variance)"; per model: "no NaN/Inf/negative, gain or variance blow-up in the core domain". This
// claim: NaN, Inf or negative values.
//
// Measured: every registered model×sampler target swept over α (1e-4 … 4), incidence (to 89.999°
// and back-facing), anisotropy (to 1:1000), density, microroughness, footprint and light size
// (verify/stability/), at float and double; a NaN, Inf or negative value, pdf or sample weight in
// any cell is a finding. Decided per target: holds where none appears, holds-in-regime where one
// appears only outside the core domain (or only at float), fails where one appears inside.
// Control (perturbed): smooth_ggx with a NaN value in 0.05 % of eval calls
// (verify/stability/nan_control.h); (corrected, where the claim fails) smooth_ggx as it is.
// Regime: the core domain (α ≥ 1e-3, anisotropy ≤ 100:1, front-facing θi ≤ 89°).
#include <fmt/format.h>

#include <cmath>

#include "verify/claim_runner.h"
#include "verify/claims/across/common.h"

namespace glintlab::verify::across_claims {

struct Stability : SweepClaim<Stability> {
  static constexpr std::string_view kId = "all.stability";
  // The paper's own sentence or equation the claim is judged against (glintlab's own rule).
  static constexpr std::string_view kQuote =
      "Not a paper's claim: glintlab's rule (docs/verification.md): \"where each method "
      "breaks (NaN, Inf, negative values, energy gain, p > 1, huge variance)\" "
      "(all.stability); per model: \"no NaN/Inf/negative, gain or variance blow-up in "
      "the core domain\"; this check: NaN, Inf or negative values";
  static constexpr bool kGlintlabRule = true;
  static constexpr std::string_view kStatistic =
      "model×sampler targets with NaN, Inf or negative values in the core domain";
  static constexpr Expected kExpected{.quick = Verdict::kHolds};
  static constexpr stability::DefectClass kKind = stability::DefectClass::kBreaks;

  static std::vector<const ModelEntry*> control_models(Input input) {
    if (input == Input::kCorrected) return corrected_models();
    return {&stability::sparse_nan_control_model()};
  }
  static std::string control_words(Input input) {
    if (input == Input::kCorrected) return std::string(kCorrectedWords);
    return fmt::format("smooth_ggx with a NaN value in {:g} % of eval calls",
                       100 * stability::kSparseNanRate);
  }
  // A rare defect's smallest share of calls found with 90 % power over the fewest calls a target
  // gets.
  static std::string power_text(Budget, const std::vector<stability::ModelSweep>& suite) {
    const std::uint64_t fewest = fewest_calls(suite);
    return fmt::format(
        "a defect in a share {:.2g} of calls (ln 10 / N, N = {} calls of the least-swept "
        "target) is found with 90 % power; the control's 0.05 % is found",
        std::log(10.0) / double(fewest), fewest);
  }
};

}  // namespace glintlab::verify::across_claims

GLINTLAB_CLAIM(glintlab::verify::across_claims::Stability);
