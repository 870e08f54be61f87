// Tests: every sampler's reported pdf equals its standalone pdf at the produced wo.
// Over α in [1e-3, 2] (anisotropic to 1:1000), θ up to 89.99° and, where allowed, wi_z < 0.
#include <gtest/gtest.h>

#include "tests/core/samplers/sampler_checks.h"

namespace glintlab {
namespace {

using namespace sampler_checks;

// Budget: every sampler evaluates its reported pdf by calling its standalone pdf function on the
// produced wo, so the measured mismatch is 0 (bitwise) in both types; the budgets are the brief's
// 1e-12 (double) and 4 ulps (float), guarding any later, cheaper in-sampler evaluation.
constexpr double kDoubleBudget = 1e-12;
constexpr double kFloatBudget = 4 * 5.96e-8;

template <class T>
double mismatch(Kind k, std::string* worst, double pdf_scale = 1) {
  return max_pdf_mismatch<T>(
      [&](const Config& c, Vec2<T> u) {
        MicrofacetSample<T> s = draw<T>(k, T(c.ax), T(c.ay), cast<T>(c.wi), u);
        s.pdf = s.pdf * T(pdf_scale);
        return s;
      },
      [&](const Config& c, Vec3<T> wo) {
        return density<T>(k, T(c.ax), T(c.ay), cast<T>(c.wi), wo);
      },
      grid(handles_backfacing(k)), u_grid<T>(6), worst);
}

TEST(SamplerPdfConsistency, DoublePdfOfSampleIsStandalonePdf) {
  for (Kind k : kAllKinds) {
    std::string worst;
    const double e = mismatch<double>(k, &worst);
    EXPECT_LE(e, kDoubleBudget) << name(k) << " worst at " << worst;
  }
}

TEST(SamplerPdfConsistency, FloatPdfOfSampleIsStandalonePdf) {
  for (Kind k : kAllKinds) {
    std::string worst;
    const double e = mismatch<float>(k, &worst);
    EXPECT_LE(e, kFloatBudget) << name(k) << " worst at " << worst;
  }
}

// The same check rejects a sampler whose reported pdf is off by 2%.
TEST(SamplerPdfConsistency, MutantScaledPdfIsRejected) {
  for (Kind k : {Kind::kWalterGgx, Kind::kHeitz, Kind::kBoundedListing1}) {
    const double e = mismatch<double>(k, nullptr, 1.02);
    EXPECT_GT(e, kDoubleBudget) << name(k);
    EXPECT_NEAR(e, 0.02, 1e-9) << name(k);
  }
}

}  // namespace
}  // namespace glintlab
