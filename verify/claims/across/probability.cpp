// all.probability — glintlab's own rule (docs/verification.md), not a paper's claim.
//
// The rule: "where each method breaks (NaN, Inf, negative values, energy gain, p > 1, huge
// variance)"; per model: "no NaN/Inf/negative, gain or variance blow-up in the core domain". This
// claim: p > 1.
//
// Measured: the suite's sweep (verify/claims/across/common.h, shared with the other all.* claims):
// every probability intermediate (p, p_*) a model reports is compared with 1; any value above 1
// is a finding. Decided per target as all.stability is.
// Control (perturbed): every model with probability intermediates, its probabilities × 1.05;
// (corrected, where the claim fails) the same models with their probabilities clamped to [0, 1]
// (verify/stability/nan_control.h).
// Regime: the core domain (α ≥ 1e-3, anisotropy ≤ 100:1, front-facing θi ≤ 89°).
#include <fmt/format.h>

#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <utility>

#include "verify/claim_runner.h"
#include "verify/claims/across/common.h"

namespace glintlab::verify::across_claims {

struct Probability : SweepClaim<Probability> {
  static constexpr std::string_view kId = "all.probability";
  // The paper's own sentence or equation the claim is judged against (glintlab's own rule).
  static constexpr std::string_view kQuote =
      "Not a paper's claim: glintlab's rule (docs/verification.md): \"where each method "
      "breaks (NaN, Inf, negative values, energy gain, p > 1, huge variance)\" "
      "(all.stability); per model: \"no NaN/Inf/negative, gain or variance blow-up in "
      "the core domain\"; this check: p > 1";
  static constexpr bool kGlintlabRule = true;
  static constexpr std::string_view kStatistic =
      "model×sampler targets with a probability above 1 in the core domain";
  static constexpr Expected kExpected{.quick = Verdict::kHolds};
  static constexpr stability::DefectClass kKind = stability::DefectClass::kProbabilityAboveOne;

  // Every model with probability intermediates: p × 1.05 (perturbed) or p clamped to [0, 1]
  // (corrected), made once per process.
  static std::vector<const ModelEntry*> control_models(Input input) {
    static std::map<std::pair<std::string, double>, std::unique_ptr<ModelEntry>> made;
    static std::mutex mutex;
    const std::lock_guard lock(mutex);
    std::vector<const ModelEntry*> out;
    const double scale = input == Input::kPerturbed ? stability::kProbabilityControlScale : 0.0;
    for (const ModelEntry& m : registered_models()) {
      bool has_p = false;
      for (auto name : m.intermediates) has_p |= stability::is_probability_name(name);
      if (!has_p) continue;
      auto& slot = made[{std::string(m.name), scale}];
      if (!slot)
        slot = std::make_unique<ModelEntry>(stability::probability_control_model(m.name, scale));
      out.push_back(slot.get());
    }
    return out;
  }
  static std::string control_words(Input input) {
    return input == Input::kPerturbed
               ? fmt::format("every model's probabilities × {:g}",
                             stability::kProbabilityControlScale)
               : std::string("every model's probabilities clamped to [0, 1]");
  }
  static std::string power_text(Budget, const std::vector<stability::ModelSweep>&) {
    return "every probability intermediate evaluated is compared with 1: any value above 1 is "
           "found (deterministic)";
  }
};

}  // namespace glintlab::verify::across_claims

GLINTLAB_CLAIM(glintlab::verify::across_claims::Probability);
