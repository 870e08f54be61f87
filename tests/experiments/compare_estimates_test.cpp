// experiments/compare: the sampler's error against the reference sees a biased sampler (its
// weights × 1.2) and not the genuine one; a reference that is not resolved (a NaN in the value) is
// flagged, and no curve is drawn against it; the reference is the conformance suite's integral.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/model_registry.h"
#include "experiments/compare/albedo_estimates.h"
#include "verify/conformance/common.h"

namespace glintlab::experiments::compare {
namespace {

namespace cf = verify::conformance;

std::vector<AlbedoReference> references(const ModelEntry& m, const CompareBudget& b) {
  std::vector<AlbedoReference> refs;
  for (double t : b.thetas_deg) refs.push_back(reference_albedo(m, t, b, 7));
  return refs;
}

TEST(CompareEstimates, BiasedSamplerIsSeenAndTheGenuineOneIsNot) {
  const CompareBudget b = compare_budget(verify::Budget::kQuick);
  const ModelEntry& genuine = find_model("smooth_ggx");
  const auto refs = references(genuine, b);
  for (const AlbedoReference& r : refs) EXPECT_TRUE(r.converged) << r.theta_deg;
  const EqualTimeCurve ok = equal_time_curve(genuine, refs, b, 11);
  ASSERT_TRUE(ok.reason.empty()) << ok.reason;
  ASSERT_EQ(ok.points.size(), sample_ladder(b).size());
  EXPECT_LT(std::abs(ok.relative_bias), 4 * ok.relative_bias_se);
  // The error falls with the sample count (1 → 1024 samples: about 32 × less noise).
  EXPECT_LT(ok.points.back().relative_rmse, 0.2 * ok.points.front().relative_rmse);

  // pdf and value unchanged. The copy changes the entry's thunks, so it must not reach the built-in
  // SIMD batches (the batch API then loops over the thunks).
  ModelEntry biased = cf::with_weight_scaled(genuine, 1.2);
  biased.static_model = nullptr;
  const EqualTimeCurve bad = equal_time_curve(biased, references(biased, b), b, 11);
  ASSERT_TRUE(bad.reason.empty()) << bad.reason;
  EXPECT_GT(bad.relative_bias, 4 * bad.relative_bias_se);
  EXPECT_NEAR(bad.relative_bias, 0.2, 0.05);
}

TEST(CompareEstimates, UnresolvedReferencesAreFlaggedAndGetNoCurve) {
  const CompareBudget b = compare_budget(verify::Budget::kQuick);
  const ModelEntry nan = cf::with_sparse_nan(find_model("smooth_ggx"), 0.01);
  const auto nan_refs = references(nan, b);
  EXPECT_FALSE(nan_refs.front().converged);
  const EqualTimeCurve nan_curve = equal_time_curve(nan, nan_refs, b, 11);
  EXPECT_TRUE(nan_curve.points.empty());
  EXPECT_NE(nan_curve.reason.find("did not converge"), std::string::npos) << nan_curve.reason;
}

// The reference is the conformance suite's integral (the truth of sampler-covers-value), so it
// resolves sparse glint values on the scenes' footprint (the suite's wide one): Kneiphof & Klein's
// glints at θi = 30° get a converged, non-zero reference and an equal-time curve, and the integral
// is the suite's to the bit.
TEST(CompareEstimates, ReferenceIsTheSuitesIntegralAndResolvesSparseGlints) {
  const CompareBudget b = compare_budget(verify::Budget::kQuick);
  const ModelEntry& m = find_model("kneiphof_klein");
  const AlbedoReference r = reference_albedo(m, 30, b, 7);
  EXPECT_EQ(r.method, "monte-carlo");
  EXPECT_TRUE(r.converged) << r.value << " ± " << r.error;
  EXPECT_GT(r.value, 0);

  const std::vector<double> values = resolve_params(m, {});
  const ModelQuery<double> q = cf::make_query(m, 30, kSceneFootprint);
  const verify::conformance::HemisphereIntegral h = cf::integrate_hemisphere(
      m, [&](const Vec3<double>& w) { return cf::value_at(m, values, q, w); }, q.wi,
      cf::roughness_hint(m, values), b.budget, 7);
  EXPECT_EQ(r.value, h.value);
  EXPECT_EQ(r.error, h.error);

  const EqualTimeCurve c = equal_time_curve(m, {r}, b, 11);
  EXPECT_TRUE(c.reason.empty()) << c.reason;
  EXPECT_DOUBLE_EQ(c.reference_relative_error, r.error / r.value);
}

}  // namespace
}  // namespace glintlab::experiments::compare
