// What the four all.* claims share: one sweep of every registered model×sampler target per budget
// (verify/stability/), measured once per process and judged by each claim for its own kind of
// breakage; the per-target verdicts, their combination and the control's sweeps. Each claim's
// file says which defect it looks for, its control models and its power.
#pragma once

#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "verify/claim.h"
#include "verify/stability/failure_region.h"
#include "verify/stability/nan_control.h"

namespace glintlab::verify::across_claims {

inline constexpr std::string_view kPaper = "every registered model (core/model_registry.cpp)";
inline constexpr std::string_view kSource =
    "glintlab's rule all.stability (docs/verification.md): sweeps of α, θi, anisotropy, density, "
    "microroughness, footprint and light size";
inline constexpr std::string_view kCoreDomain =
    "the core domain: α ≥ 1e-3, anisotropy ≤ 100:1, front-facing θi ≤ 89°";

// The sweeps of every registered target at one budget, measured once per process and shared by
// the four claims (deterministic, so which claim runs first does not matter). Only all.variance
// needs the fixed-position variance, about half of a sweep's time: it gets a copy with it added.
const std::vector<stability::ModelSweep>& suite_sweeps(Budget b,
                                                       stability::FixedPositionVariance variance);

// Per target: its verdict for the kind and its first finding of that kind.
struct TargetVerdict {
  std::string id;
  Verdict verdict;
  std::string first;
};

struct Sizes {
  Budget budget;  // the sweep's grid and samples per cell (verify/stability/sweep_plan.h)
};
// The suite's sweep (one configuration: it is shared by the four claims and not split).
struct Evidence {
  const std::vector<stability::ModelSweep>* sweeps = nullptr;
};
struct Measured {
  std::vector<TargetVerdict> targets;  // the suite's, or the control models'
  std::size_t cells = 0;               // of the suite's sweep
  const std::vector<stability::ModelSweep>* suite = nullptr;
};

// Judges the suite's sweep (kGenuine) or a sweep of the control models through the same
// decision; the control models' sweeps are kept per process too (the tests' probes measure each
// control input twice).
Measured measure_kind(Budget b, const std::vector<stability::ModelSweep>& suite,
                      stability::DefectClass kind,
                      std::span<const ModelEntry* const> control_models);
// The claim's verdict from its targets': fails if one fails, holds-in-regime if one holds there.
Decision decide_kind(const Measured& m);
// "fails: …; holds outside the core domain only: …; holds: …"
std::string describe_targets(const std::vector<TargetVerdict>& targets);
// The genuine detail line: targets, cells, samples per cell and every target's verdict.
std::string describe_suite(Budget b, const Measured& m);
// The corrected input of a claim that fails (all but all.probability): a model known to behave.
std::vector<const ModelEntry*> corrected_models();
inline constexpr std::string_view kCorrectedWords =
    "smooth_ggx, whose values are finite and weights bounded (the corrected input)";
// The fewest calls (evals and samples) any target of the suite gets.
std::uint64_t fewest_calls(const std::vector<stability::ModelSweep>& suite);

// The protocol of a sweep claim, written once for the four (CRTP): a claim type derives from
// SweepClaim<Itself> and gives kId, kStatistic, kExpected, kKind, control_models(input),
// control_words(input) and power_text(budget, suite).
template <typename Self>
struct SweepClaim {
  static constexpr std::string_view kPaper = across_claims::kPaper;
  static constexpr std::string_view kSource = across_claims::kSource;
  static constexpr std::string_view kRegime = kCoreDomain;
  static constexpr bool kHasCorrectedControl = true;
  using Sizes = across_claims::Sizes;
  using Evidence = across_claims::Evidence;
  using Measured = across_claims::Measured;

  static Sizes sizes(Budget b) { return {b}; }
  // The sweep has no size below the quick budget's.
  static Sizes probe_sizes() { return {Budget::kQuick}; }
  static stability::FixedPositionVariance variance() {
    return Self::kKind == stability::DefectClass::kHugeVariance
               ? stability::FixedPositionVariance::kMeasure
               : stability::FixedPositionVariance::kSkip;
  }
  static int configurations(const Sizes&) { return 1; }
  static Evidence observe(const Sizes& z, int, std::uint64_t) {
    return {&suite_sweeps(z.budget, variance())};
  }
  static Measured measure(const Sizes& z, std::span<const Evidence> e, Input input) {
    const std::vector<const ModelEntry*> models =
        input == Input::kGenuine ? std::vector<const ModelEntry*>{} : Self::control_models(input);
    return measure_kind(z.budget, *e[0].sweeps, Self::kKind, models);
  }
  static Decision decide(const Sizes&, const Measured& m) { return decide_kind(m); }
  static std::string describe(const Sizes& z, const Measured& m, Input input) {
    return input == Input::kGenuine
               ? describe_suite(z.budget, m)
               : Self::control_words(input) + ": " + describe_targets(m.targets);
  }
  static std::string control_text(const Sizes&, const Measured& control, Input input,
                                  Verdict verdict) {
    return Self::control_words(input) + ": verdict " + std::string(to_string(verdict)) + "; " +
           describe_targets(control.targets);
  }
  static std::string power(const Sizes& z, const Measured& m, const Measured&) {
    return Self::power_text(z.budget, *m.suite);
  }
};

}  // namespace glintlab::verify::across_claims
