// What `glintlab compare` measures at each budget: the shared scenes (incidence angles; the
// footprint and light of the conformance settings) and an explicit cap on every cost, so a slow
// model (a glint model whose eval takes microseconds) cannot stretch the run: no cubature for
// footprint models, a fixed number of reference samples, a fixed ladder of sample counts.
#pragma once

#include <cstdint>
#include <vector>

#include "verify/check.h"
#include "verify/conformance/common.h"

namespace glintlab::experiments::compare {

// The scenes' footprint: the conformance suite's wide footprint (verify/conformance/common.h),
// where sampler-covers-value integrates footprint models. At the suite's narrower kFootprint
// (0.1) Kneiphof & Klein's value is 0 everywhere at θi = 30° (no glint reflects into the light),
// so its albedo, and a relative error against it, would be undefined there.
inline constexpr double kSceneFootprint = verify::conformance::kWideFootprint;

struct CompareBudget {
  verify::Budget budget = verify::Budget::kQuick;
  // θi of the shared scenes, degrees; every model sees the same ones (verify/conformance's
  // make_query: footprint side kSceneFootprint at uv (0.5, 0.5), a 1° cone for area-light models,
  // a delta light otherwise).
  std::vector<double> thetas_deg;
  // The reference is the conformance suite's integral at this budget (its cubature, or for
  // footprint models its Monte Carlo over the mirror mixture, sample count set there): the
  // relative error estimate of a cubature above which the reference is flagged as not converged;
  // and the relative standard error above which a Monte Carlo reference is flagged.
  double cubature_converged_rel = 0, monte_carlo_converged_rel = 0;
  // The equal-time ladder: estimates of N = 1, 4, 16, … up to max_samples, each repeated.
  std::uint64_t max_samples = 0;
  int repetitions = 0;
  // Timing: rows per eval_batch call and the least time measured per ISA (best of 3 rounds).
  std::size_t timing_rows = 0;
  double timing_seconds = 0;
};

inline CompareBudget compare_budget(verify::Budget b) {
  if (b == verify::Budget::kQuick) return {b, {30, 70}, 1e-3, 0.1, 1024, 8, 256, 0.01};
  return {b, {0, 30, 60, 80}, 1e-5, 0.03, 16384, 32, 1024, 0.1};
}

// The sample counts of the ladder: 1, 4, 16, …, max_samples.
inline std::vector<std::uint64_t> sample_ladder(const CompareBudget& b) {
  std::vector<std::uint64_t> n;
  for (std::uint64_t k = 1; k <= b.max_samples; k *= 4) n.push_back(k);
  return n;
}

}  // namespace glintlab::experiments::compare
