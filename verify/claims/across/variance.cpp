// all.variance — glintlab's own rule (shared/CLAIMS.md), not a paper's claim.
//
// The rule: "where each method breaks (NaN, Inf, negative values, energy gain, p > 1, huge
// variance)"; per model: "no NaN/Inf/negative, gain or variance blow-up in the core domain". This
// claim: huge variance, read as a sample weight whose relative variance at a fixed surface
// position exceeds kVarianceBlowup = 81.92 (verify/stability/cell_stats.h: a pixel noisier than
// 10 % at 8192 samples).
//
// Measured: the suite's sweep (verify/claims/across/common.h, shared with the other all.* claims)
// with the fixed-position variance added: Var(w)/max(E(w), 1/256)² at 4 fixed surface positions
// per cell, a position above the bound confirmed from 4× fresh samples. Decided per target as
// all.stability is. Recorded as failing: the samplers that draw a smooth lobe for a glinty BRDF
// (the stand-ins of podee, kneiphof_klein, kneiphof_klein_area and chermain, whose papers give no
// sampler) exceed the bound inside the core domain (verify/claims/failure_reviews.cpp).
// Control (corrected, as the claim fails): smooth_ggx as it is, which must hold; (perturbed)
// smooth_ggx with weights × 300 in 0.2 % of samples, mean kept (verify/stability/nan_control.h).
// Regime: the core domain (α ≥ 1e-3, anisotropy ≤ 100:1, front-facing θi ≤ 89°).
#include <fmt/format.h>

#include "verify/claim_runner.h"
#include "verify/claims/across/common.h"

namespace glintlab::verify::across_claims {

// kStatistic spells the bound out ({:g} of it: 81.92): it moves with it.
static_assert(stability::kVarianceBlowup > 81.91995 && stability::kVarianceBlowup < 81.92005);

struct Variance : SweepClaim<Variance> {
  static constexpr std::string_view kId = "all.variance";
  static constexpr std::string_view kStatistic =
      "model×sampler targets with a variance blow-up at a fixed surface position (Var(w)/E(w)² "
      "above 81.92) in the core domain";
  static constexpr Expected kExpected{.quick = Verdict::kFails};
  static constexpr stability::DefectClass kKind = stability::DefectClass::kHugeVariance;

  static std::vector<const ModelEntry*> control_models(Input input) {
    if (input == Input::kCorrected) return corrected_models();
    return {&stability::spike_control_model()};
  }
  static std::string control_words(Input input) {
    if (input == Input::kCorrected) return std::string(kCorrectedWords);
    return fmt::format("smooth_ggx with weights × {:g} in {:g} % of samples (mean kept)",
                       stability::kSpikeWeight, 100 * stability::kSpikeRate);
  }
  // The variance ratio's ceiling (an estimate from n samples reaches n) and how many positions
  // are judged against their own mean rather than the dark floor.
  static std::string power_text(Budget b, const std::vector<stability::ModelSweep>& suite) {
    using namespace stability;
    std::uint64_t positions = 0, bright = 0;
    for (const ModelSweep& s : suite)
      for (const SweepMap& m : s.maps)
        for (const CellStats& c : m.cells) {
          positions += kVariancePositions;
          bright += c.positions_reflecting;
        }
    const std::uint64_t n = cell_budget(b).samples;
    return fmt::format(
        "Var(w)/max(E(w), 1/{:g})² is measured at {} fixed surface positions per cell from {} "
        "samples each (an estimate from n samples reaches n, so a blow-up above {:g} is "
        "visible), and a position above the bound again from {} fresh samples; {} of {} "
        "positions were brighter than 1/{:g} (the others' noise is judged against 1/{:g}); the "
        "control's 0.2 % weight spikes are found",
        1 / kDarkAlbedo, kVariancePositions, n, kVarianceBlowup, kVarianceConfirmFactor * n, bright,
        positions, 1 / kDarkAlbedo, 1 / kDarkAlbedo);
  }
};

}  // namespace glintlab::verify::across_claims

GLINTLAB_CLAIM(glintlab::verify::across_claims::Variance);
