// The quantity every model is compared on: the albedo a(ωi) = ∫ value(ωi, ωo) dωo over the upper
// hemisphere (value is cosine-weighted, core/model.h) of each shared scene, i.e. the white-furnace
// radiance a renderer estimates with the model's own sampler. Per model:
//   - its reference: the conformance suite's integral (verify/conformance/common.h
//     integrate_hemisphere, the truth of sampler-covers-value): cubature about the mirror
//     direction for models without a footprint, Monte Carlo over a fixed mixture about the mirror
//     direction with its standard error for footprint models (whose value holds thousands of glint
//     peaks cubature resolves only after minutes); flagged when its error says it did not converge;
//   - the equal-time curve: the relative RMS error of the sampler's estimate against that
//     reference at N = 1, 4, 16, … samples, against the wall time the N samples took, beside the
//     reference's own relative error (the floor below which the curve says nothing).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/model_registry.h"
#include "experiments/compare/compare_budget.h"

namespace glintlab::experiments::compare {

struct AlbedoReference {
  double theta_deg = 0;
  std::string method;  // "cubature" or "monte-carlo"
  double value = 0;
  double error = 0;  // cubature: its error estimate; monte-carlo: one standard error
  // false: the error is above the budget's bound for the method (the value is not to be used)
  bool converged = true;
};

AlbedoReference reference_albedo(const ModelEntry& m, double theta_deg, const CompareBudget& b,
                                 std::uint64_t seed);

struct EqualTimePoint {
  std::uint64_t samples = 0;
  double seconds = 0;  // wall time of one N-sample estimate (mean over scenes and repetitions)
  // RMS over scenes of the relative RMS error over repetitions, |estimate − reference| / reference.
  double relative_rmse = 0;
};

struct EqualTimeCurve {
  std::vector<EqualTimePoint> points;
  // At the largest N: the mean relative deviation over scenes and repetitions and its standard
  // error, the references' errors included (the estimator's bias against the reference, where it
  // is resolved).
  double relative_bias = 0, relative_bias_se = 0;
  // RMS over scenes of the references' relative errors (one σ for Monte Carlo): an estimate's
  // error against the reference cannot be resolved below it.
  double reference_relative_error = 0;
  std::string isa;     // the ISA the samples were drawn on
  std::string reason;  // non-empty: no curve, and why (a reference not converged, or zero)
};

// The curve over the scenes whose references are given (in b.thetas_deg order).
EqualTimeCurve equal_time_curve(const ModelEntry& m, const std::vector<AlbedoReference>& refs,
                                const CompareBudget& b, std::uint64_t seed);

}  // namespace glintlab::experiments::compare
