// Tests: sample weights f·cos/pdf are finite and non-negative, and rejection is reported.
// Everywhere, including the corners (α = 1e-4, θ = 89.99°, wi = ±z exactly, anisotropy 1:1000, u at
// 0 and 1 − ε), in both float types.
#include <gtest/gtest.h>

#include "tests/core/samplers/sampler_checks.h"

namespace glintlab {
namespace {

using namespace sampler_checks;

// The weight grid: the shared grid plus α = 1e-4 (isotropic and 1:1e4) and both exact poles;
// every sampler gets back-facing incidences too (the VNDF samplers must reject, not produce NaN).
std::vector<Config> weight_configs() {
  std::vector<Config> out = grid(true);
  for (double t : {0.0, 45.0, 89.99, 135.0, 180.0})
    for (auto [ax, ay] : {std::pair{1e-4, 1e-4}, std::pair{1e-4, 1.0}, std::pair{1.0, 1e-4}})
      out.push_back({ax, ay, t == 0 ? V3{0, 0, 1} : t == 180 ? V3{0, 0, -1} : dir(deg(t), 0.3)});
  return out;
}

template <class T>
int bad_weights(Kind k, std::string* first, bool unguarded = false) {
  return count_bad_weights<T>(
      [&](const Config& c, Vec2<T> u) { return draw<T>(k, T(c.ax), T(c.ay), cast<T>(c.wi), u); },
      [&](const Config& c, const MicrofacetSample<T>& s) {
        if (!unguarded) return weight<T>(k, T(c.ax), T(c.ay), cast<T>(c.wi), s);
        // Mutant: the weight without its rejected / pdf == 0 guard.
        const GGX<T> g{T(c.ax), T(c.ay)};
        return microfacet_brdf(g, cast<T>(c.wi), s.wo, T(1)) * s.wo.z / s.pdf;
      },
      weight_configs(), u_grid<T>(6), first);
}

TEST(SamplerWeights, FiniteAndNonNegativeDouble) {
  for (Kind k : kAllKinds) {
    std::string first;
    EXPECT_EQ(bad_weights<double>(k, &first), 0) << name(k) << " first at " << first;
  }
}

TEST(SamplerWeights, FiniteAndNonNegativeFloat) {
  for (Kind k : kAllKinds) {
    std::string first;
    EXPECT_EQ(bad_weights<float>(k, &first), 0) << name(k) << " first at " << first;
  }
}

// The same check catches a weight computed without the guard (0/0 where wi sees no microfacet).
TEST(SamplerWeights, MutantUnguardedWeightIsRejected) {
  for (Kind k : {Kind::kCaps, Kind::kBoundedListing1, Kind::kHeitz})
    EXPECT_GT(bad_weights<double>(k, nullptr, true), 0) << name(k);
}

// rejected is exactly "wo below the surface, m facing away from wi, or pdf not positive" (plus
// wi_z <= 0 for the samplers defined only above the surface), and an accepted sample's weight is 0
// only where the BRDF itself is 0 (rounding at θ = 90°, where wi_z = 6e-17).
TEST(SamplerWeights, RejectionIsReportedConsistently) {
  for (Kind k : kAllKinds) {
    int wrong = 0, silent_zero = 0;
    std::string first;
    for (const Config& c : weight_configs())
      for (const V2& u : u_grid<double>(6)) {
        const MicrofacetSample<double> s = draw<double>(k, c.ax, c.ay, c.wi, u);
        const bool domain = handles_backfacing(k) || c.wi.z > 0;
        const bool expect = s.wo.z <= 0 || dot(c.wi, s.m) <= 0 || !(s.pdf > 0) || !domain;
        if (bool(s.rejected) != expect) ++wrong;
        const double f = is_beckmann(k)
                             ? microfacet_brdf(Beckmann<double>{c.ax, c.ay}, c.wi, s.wo, 1.0)
                             : microfacet_brdf(GGX<double>{c.ax, c.ay}, c.wi, s.wo, 1.0);
        if (!s.rejected && f > 0 && !(weight<double>(k, c.ax, c.ay, c.wi, s) > 0)) {
          if (silent_zero++ == 0) first = describe(c);
        }
      }
    EXPECT_EQ(wrong, 0) << name(k);
    EXPECT_EQ(silent_zero, 0) << name(k) << " first at " << first;
  }
}

}  // namespace
}  // namespace glintlab
