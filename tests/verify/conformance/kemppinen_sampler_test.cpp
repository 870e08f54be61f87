// The Kemppinen models' sampler (the mixture of Algorithm 2 and D cosθ of
// core/glints/kemppinen_full_sampling.h) against Algorithm 2 alone, the paper's sampler, which
// does not draw the compensation C of Eq. 10: at the compensation settings of the conformance
// suite (verify/conformance/common.h), sampler-covers-value rejects Algorithm 2 alone and holds for
// the mixture.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "core/model_registry.h"
#include "core/models/kemppinen_beckmann.h"
#include "core/models/kemppinen_ggx.h"
#include "verify/conformance/common.h"
#include "verify/conformance/conformance.h"

namespace glintlab::verify::conformance {
namespace {

// The registered entry with its sampler and pdf replaced by Algorithm 2 alone (the model's sampler
// before it drew the compensation); eval's value is unchanged. Without its rows functions, which
// would bypass the replaced thunks.
template <class Model>
ModelEntry with_explicit_only_sampler(const ModelEntry& m) {
  ModelEntry e = clear_rows(m);
  e.sample = [](const std::vector<double>& values, const ModelQuery<double>& q, Vec2<double> u) {
    return detail::kemppinen_model_explicit_sample(Model::template params<double>(values), q, u);
  };
  e.pdf = [](const std::vector<double>& values, const ModelQuery<double>& q) {
    return detail::kemppinen_model_explicit_pdf(Model::template params<double>(values), q);
  };
  e.sample_float = nullptr;
  e.pdf_float = nullptr;
  e.eval_float = nullptr;
  e.static_model = nullptr;
  return e;
}

// At the compensation settings only: the property's other settings do not tell the two samplers
// apart (the recorded model.<name>.sampler-covers-value rows hold at every setting).
template <class Model>
void expect_explicit_only_fails_and_mixture_holds() {
  const ModelEntry& m = find_model(Model::kName);
  const std::vector<Setting> compensation = compensation_settings(m);
  ASSERT_EQ(compensation.size(), 3u);
  const double level = model_level(m);
  const Assessment mixture = covers_value_at(m, compensation, Budget::kQuick,
                                             "test.kemppinen_mixture", level, nullptr);
  EXPECT_EQ(mixture.verdict, Verdict::kHolds) << mixture.detail;
  // The same integrals of value (only the sampler differs).
  const ModelEntry old = with_explicit_only_sampler<Model>(m);
  const Assessment explicit_only = covers_value_at(old, compensation, Budget::kQuick,
                                                   "test.kemppinen_mixture", level,
                                                   &mixture.references);
  EXPECT_EQ(explicit_only.verdict, Verdict::kFails) << explicit_only.detail;
  // It misses value: the mean weight falls short of ∫ value (k = 1 at footprint 0.4, θi = 80°:
  // about −11 % measured), at a compensation setting (the last).
  EXPECT_LT(explicit_only.value, -0.05) << explicit_only.detail;
  ASSERT_EQ(explicit_only.raw_p_values.size(), compensation.size());
  EXPECT_LT(explicit_only.raw_p_values.back(), 1e-6) << explicit_only.detail;
}

TEST(KemppinenSampler, ExplicitOnlyFailsCoversValueAndMixtureHoldsGgx) {
  expect_explicit_only_fails_and_mixture_holds<KemppinenGGX>();
}

TEST(KemppinenSampler, ExplicitOnlyFailsCoversValueAndMixtureHoldsBeckmann) {
  expect_explicit_only_fails_and_mixture_holds<KemppinenBeckmann>();
}

}  // namespace
}  // namespace glintlab::verify::conformance
