// The conformance suite every registered model gets (built-in or plug-in): one check per model and
// property, id "model.<name>.<property>", generated from the registry (core/model_registry.h)
// through the type-erased ModelEntry only. Each property is a measure → decide step that runs the
// same way on the model and on its control (a copy of the entry made deliberately wrong, about
// 3 % off, or, where the model fails, corrected), so the control gets its own verdict.
//
// False positives: a model's statistical properties are one family of their own, family-wise rate
// kFamilyWiseRate split by Šidák over them (model_level); inside a property its configurations are
// corrected by Holm–Šidák at that level. Adding models or plug-ins therefore changes neither the
// papers' claims' level (check_level counts only Check::family == "") nor another model's.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/model_registry.h"
#include "verify/check.h"
#include "verify/control_rule.h"

namespace glintlab::verify::conformance {

// The properties, in check order (core/model.h, where a model's kNotClaimed is checked against
// them).
inline constexpr const auto& kProperties = kConformanceProperties;

// Whether a property is generated for a model at all: converges-to-smooth and constant-time only
// for footprint models (kNeedsFootprint); every other property for every model.
bool applies(std::string_view property, const ModelEntry& model);
// Whether the property tests a hypothesis (p-values; a share of the model's family rate).
bool is_statistical_property(std::string_view property);
// The model's reason for not claiming the property (ModelEntry::not_claimed), or, where the entry
// cannot have it (float-vs-double without a float instantiation, simd-equivalence without SIMD
// batches, converges-to-smooth without a declared smooth limit), the generated reason; nothing
// where the property is claimed.
std::optional<std::string> not_claimed_reason(std::string_view property, const ModelEntry& model);
// The per-property level of a model's family: Šidák share of kFamilyWiseRate over the model's
// claimed statistical properties.
double model_level(const ModelEntry& model);

// An integral over the upper hemisphere by cubature or, for footprint models, Monte Carlo
// (verify/conformance/common.h), with its error estimate (one σ for Monte Carlo).
struct HemisphereIntegral {
  double value = 0, error = 0;
  bool monte_carlo = false;
};

// The result of one property's measure and decide steps on one entry (the model or a control).
struct Assessment {
  Verdict verdict = Verdict::kInconclusive;
  std::string detail, statistic;
  double value = 0;
  std::optional<double> bound, p_value;
  std::vector<double> raw_p_values;
  int configurations = 0;
  std::string power;
  // sampler-covers-value's integrals of value, one per configuration: its controls change only the
  // sampler, so they reuse them (the control then differs from the model in nothing else).
  std::vector<HemisphereIntegral> references;
  // What the property needed as a number but measured NaN or Inf (e.g. ∫ value dωo of an eval
  // that returns NaN); non-empty: the statistic could not be computed, and run_property reports
  // the check's verdict as error with this.
  std::string non_finite;
};

// Measure and decide `property` for `model` at budget b, seeds from check id `id`, configurations
// corrected at `level`. `model` may be any entry (a registered one, a control, a test's toy).
// `reuse`: another assessment's references, for an entry whose value is that one's.
// `batch_value_scale`: simd-equivalence's batch outputs (the path under test) have their value
// multiplied by it before they are compared with the scalar eval; 1 (the model's own check) leaves
// them as the batch wrote them. The other properties ignore it.
Assessment assess(std::string_view property, const ModelEntry& model, Budget b,
                  const std::string& id, double level,
                  const std::vector<HemisphereIntegral>* reuse = nullptr,
                  double batch_value_scale = 1);

// The control of a property: a copy of `model` deliberately wrong (input kPerturbed) or corrected
// from what `genuine` measured (kCorrected), and its name; which one is the runner's rule
// (control_input in verify/control_rule.h). Its verdict comes from assess.
// batch_value_scale: what assess multiplies the SIMD batch's value by (simd-equivalence's
// near-truth control perturbs the batch, the path under test; its scalar reference is unchanged).
struct Control {
  ModelEntry model;
  std::string name;
  double batch_value_scale = 1;
};
Control make_control(std::string_view property, const ModelEntry& model, const Assessment& genuine,
                     Input input);

// The whole check of one property of one model: assess, the control's assessment, described;
// a not-claimed property gives Verdict::kNotClaimed with the reason and measures nothing; a
// statistic or p-value measured NaN or infinite gives Verdict::kError naming the model and what
// was not finite (the check's run, from conformance_checks, also reports an exception so).
CheckResult run_property(std::string_view property, const ModelEntry& model, Budget b);

// The recorded verdicts of the built-in models (quick, and full where it differs): the generator
// sets Check::expected from them; a model without a record (a plug-in) is expected to hold
// (holds, or not-claimed where declared).
struct Recorded {
  Verdict quick;
  std::optional<Verdict> full = {};
};
std::optional<Recorded> recorded_verdict(std::string_view model, std::string_view property);

// The checks of one model, and of every registered model (registration order, kProperties order).
std::vector<Check> conformance_checks(const ModelEntry& model);
std::vector<Check> conformance_checks();

}  // namespace glintlab::verify::conformance

namespace glintlab::verify {
using conformance::conformance_checks;
}
