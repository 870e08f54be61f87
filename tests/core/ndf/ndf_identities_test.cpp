// Identities every Smith microfacet NDF must satisfy (Heitz 2014, "Understanding the masking-
// shadowing function"): normalisation (Eq. 4), projected area (Eq. 5, 14), Λ(−ω) = 1 + Λ(ω), G1/G2
// symmetry and reciprocity, VNDF normalisation (Heitz 2018 Eq. 1). Each check is a function of the
// NDF type and is also run on a deliberately broken NDF, which it must reject.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "core/math/rng.h"
#include "core/ndf/beckmann.h"
#include "core/ndf/fresnel.h"
#include "core/ndf/ggx.h"
#include "core/ndf/microfacet.h"
#include "verify/stats/ndf_cubature.h"

namespace glintlab {
namespace {

using V = Vec3<double>;

V direction(double theta_deg, double phi) {
  const double t = theta_deg * std::numbers::pi / 180;
  return {std::sin(t) * std::cos(phi), std::sin(t) * std::sin(phi), std::cos(t)};
}

struct Alpha {
  double x, y;
};
const std::vector<Alpha> kAlphas = {{1e-3, 1e-3}, {1e-2, 1e-2}, {0.1, 0.1}, {0.5, 0.5},
                                    {1, 1},       {2, 2},       {0.1, 0.5}, {1e-3, 1},
                                    {1.5, 0.3}};
const std::vector<double> kThetas = {0, 30, 60, 85, 89.9};

// Mutants: a normalisation error of 2 %, a Λ that forgets the back-facing convention, and a
// masking term that is not symmetric in its arguments.
template <class Ndf>
struct ScaledD : Ndf {
  double scale;
  double D(V m) const { return scale * Ndf::D(m); }
  double projected_area(V w) const { return scale * Ndf::projected_area(w); }
};
template <class Ndf>
struct SymmetricLambda : Ndf {
  double lambda(V w) const { return Ndf::lambda(V{w.x, w.y, std::abs(w.z)}); }
};

// --- The checks, as functions of the NDF -----------------------------------------------------

// |∫ D(m) m_z dm − 1| (Heitz 2014 Eq. 4).
template <class Ndf>
double normalization_error(const Ndf& ndf, double ax, double ay) {
  auto r = verify::integrate_ndf_lobe([&](const V& m) { return ndf.D(m) * m.z; }, ax, ay, true);
  return std::abs(r.value - 1);
}

// max over ω of |∫ (ω·m) D(m) dm − ω_z| and |∫ max(0, ω·m) D(m) dm − A(ω)|, with
// A(ω) = ω_z + |ω_z| Λ(ω) the Smith projected area (Heitz 2014 Eq. 14 and Eq. 5).
template <class Ndf>
double projected_area_error(const Ndf& ndf, double ax, double ay) {
  double worst = 0;
  for (double th : {0.0, 40.0, 80.0, 89.9, 100.0, 150.0}) {
    const V w = direction(th, 0.7);
    auto s = verify::integrate_ndf_lobe([&](const V& m) { return dot(w, m) * ndf.D(m); }, ax, ay, true);
    auto p = verify::integrate_ndf_lobe(
        [&](const V& m) { return std::max(0.0, dot(w, m)) * ndf.D(m); }, ax, ay, true, 1e-10, &w);
    const double a = w.z + std::abs(w.z) * ndf.lambda(w);
    worst = std::max({worst, std::abs(s.value - w.z), std::abs(p.value - a),
                      std::abs(p.value - ndf.projected_area(w))});
  }
  return worst;
}

// max over ωi of |∫ D_ωi(m) dm − 1| (Heitz 2018 Eq. 1), front- and back-facing ωi. A back-facing
// ωi can see a projected area that underflows double (Beckmann, αx = 1e-3, ωi 30° below the
// horizon along x: A ≈ exp(−3e5)); there the VNDF is 0/0 and is skipped, since no float type can
// represent it.
template <class Ndf>
double vndf_normalization_error(const Ndf& ndf, double ax, double ay) {
  double worst = 0;
  for (double th : {0.0, 30.0, 60.0, 85.0, 89.9, 120.0})
    for (double phi : {0.0, 2.0}) {
      const V wi = direction(th, phi);
      if (ndf.projected_area(wi) < 1e-250) continue;
      auto r = verify::integrate_ndf_lobe([&](const V& m) { return vndf(ndf, wi, m); }, ax, ay,
                                           true, 1e-10, &wi);
      worst = std::max(worst, std::abs(r.value - 1));
    }
  return worst;
}

// max over ω of |Λ(−ω) − 1 − Λ(ω)|, relative to 1 + Λ(ω).
template <class Ndf>
double lambda_reversal_error(const Ndf& ndf) {
  double worst = 0;
  for (double th : {0.0, 10.0, 45.0, 80.0, 89.0, 89.99})
    for (double phi : {0.0, 0.8, 2.5}) {
      const V w = direction(th, phi);
      const double l = ndf.lambda(w);
      worst = std::max(worst, std::abs(ndf.lambda(-w) - 1 - l) / (1 + l));
    }
  return worst;
}

// max relative asymmetry of G2 (both forms) and of the BRDF under ωi ↔ ωo, plus a violation of
// 0 ≤ G2_separable ≤ G2_height_correlated ≤ min(G1) ≤ 1 (Heitz 2014 Sec. 6).
template <class Ndf>
double masking_symmetry_error(const Ndf& ndf) {
  double worst = 0;
  for (std::uint64_t i = 0; i < 2000; ++i) {
    auto u = [&](int d) { return counter_uniform<double>(hash_string("masking-symmetry"), i, d); };
    const V wi = direction(89.99 * u(0), 6.283 * u(1)), wo = direction(89.99 * u(2), 6.283 * u(3));
    const V h = half_vector(wi, wo);
    const double gc = smith_g2_height_correlated(ndf, wi, wo, h);
    const double gc_r = smith_g2_height_correlated(ndf, wo, wi, h);
    const double gs = smith_g2_separable(ndf, wi, wo, h);
    const double gs_r = smith_g2_separable(ndf, wo, wi, h);
    const double f = microfacet_brdf(ndf, wi, wo, 1.0), f_r = microfacet_brdf(ndf, wo, wi, 1.0);
    const double g1 = std::min(smith_g1(ndf, wi, h), smith_g1(ndf, wo, h));
    auto rel = [](double a, double b) { return std::abs(a - b) / std::max({std::abs(a), std::abs(b), 1e-300}); };
    worst = std::max({worst, rel(gc, gc_r), rel(gs, gs_r), rel(f, f_r)});
    if (gs < 0 || gs > gc * (1 + 1e-14) || gc > g1 * (1 + 1e-14) || g1 > 1) worst = std::max(worst, 1.0);
  }
  return worst;
}

// --- The tests ----------------------------------------------------------------------------------

template <class Ndf>
class NdfIdentities : public ::testing::Test {};
using NdfTypes = ::testing::Types<GGX<double>, Beckmann<double>>;
TYPED_TEST_SUITE(NdfIdentities, NdfTypes);

TYPED_TEST(NdfIdentities, NormalizedOverProjectedArea) {
  for (const Alpha& a : kAlphas)
    EXPECT_LT(normalization_error(TypeParam{a.x, a.y}, a.x, a.y), 1e-7) << a.x << "," << a.y;
}

TYPED_TEST(NdfIdentities, ProjectedAreaIsOmegaZAndSmithArea) {
  for (const Alpha& a : kAlphas)
    EXPECT_LT(projected_area_error(TypeParam{a.x, a.y}, a.x, a.y), 1e-7) << a.x << "," << a.y;
}

TYPED_TEST(NdfIdentities, VisibleNormalsNormalized) {
  for (const Alpha& a : kAlphas)
    EXPECT_LT(vndf_normalization_error(TypeParam{a.x, a.y}, a.x, a.y), 1e-7) << a.x << "," << a.y;
}

TYPED_TEST(NdfIdentities, LambdaOfReversedDirection) {
  for (const Alpha& a : kAlphas) EXPECT_LT(lambda_reversal_error(TypeParam{a.x, a.y}), 1e-12);
}

TYPED_TEST(NdfIdentities, MaskingSymmetricAndOrdered) {
  for (const Alpha& a : kAlphas) EXPECT_LT(masking_symmetry_error(TypeParam{a.x, a.y}), 1e-12);
}

// Values stay finite and non-negative at the extremes: α = 1e-4, anisotropy 1:1000, θ = 89.99°,
// ω = ±z exactly, and the horizon.
TYPED_TEST(NdfIdentities, FiniteAtExtremes) {
  const std::vector<Alpha> alphas = {{1e-4, 1e-4}, {1e-4, 0.1}, {1e-3, 1}, {4, 4}, {1, 1e-3}};
  const std::vector<V> dirs = {{0, 0, 1}, {0, 0, -1}, direction(89.99, 0.3), direction(90, 1.0),
                               direction(90.01, 2.0), direction(1e-6, 0.0), direction(45, 0.0)};
  for (const Alpha& a : alphas) {
    const TypeParam ndf{a.x, a.y};
    for (const V& wi : dirs) {
      EXPECT_TRUE(std::isfinite(ndf.lambda(wi)) || wi.z == 0) << a.x << " " << wi.z;
      EXPECT_TRUE(std::isfinite(ndf.projected_area(wi)));
      for (const V& wo : dirs) {
        const V h = half_vector(wi, wo);
        for (double v : {ndf.D(h), smith_g1(ndf, wi, h), smith_g2_height_correlated(ndf, wi, wo, h),
                         smith_g2_separable(ndf, wi, wo, h), vndf(ndf, wi, h),
                         microfacet_brdf(ndf, wi, wo, 1.0)}) {
          EXPECT_TRUE(std::isfinite(v) && v >= 0) << a.x << "," << a.y << " wi.z=" << wi.z << " wo.z=" << wo.z;
        }
      }
    }
  }
}

// The same checks reject broken formulas: they can fail.
TYPED_TEST(NdfIdentities, ChecksRejectBrokenNdfs) {
  const double ax = 0.3, ay = 0.3;
  ScaledD<TypeParam> scaled{{ax, ay}, 1.02};
  EXPECT_GT(normalization_error(scaled, ax, ay), 1e-3);
  EXPECT_GT(vndf_normalization_error(ScaledD<TypeParam>{{ax, ay}, 1.02}, ax, ay) +
                projected_area_error(scaled, ax, ay), 1e-3);
  // A Λ that ignores the side of the surface breaks both the reversal identity and the projected
  // area of back-facing directions.
  SymmetricLambda<TypeParam> sym{{ax, ay}};
  EXPECT_GT(lambda_reversal_error(sym), 0.1);
  EXPECT_GT(projected_area_error(sym, ax, ay), 1e-3);
}

// A G2 that weighs its arguments differently is caught by the symmetry check.
TEST(NdfIdentitiesControl, AsymmetricMaskingRejected) {
  struct Lopsided : GGX<double> {
    double lambda(V w) const { return (w.x > 0 ? 1.5 : 1.0) * GGX<double>::lambda(w); }
  };
  EXPECT_GT(masking_symmetry_error(Lopsided{{0.5, 0.5}}), 1e-3);
}

// Fresnel: Schlick at normal incidence is F0 and 1 at grazing; the conductor formula matches the
// dielectric Fresnel equations when κ = 0 and is 1 at grazing.
TEST(Fresnel, LimitsAndDielectricCase) {
  EXPECT_DOUBLE_EQ(fresnel_schlick(0.04, 1.0), 0.04);
  EXPECT_DOUBLE_EQ(fresnel_schlick(0.04, 0.0), 1.0);
  for (double c : {1.0, 0.8, 0.5, 0.2, 0.05}) {
    const double eta = 1.5, s2 = 1 - c * c, ct = std::sqrt(1 - s2 / (eta * eta));
    const double rs = (c - eta * ct) / (c + eta * ct), rp = (eta * c - ct) / (eta * c + ct);
    EXPECT_NEAR(fresnel_conductor(eta, 0.0, c), 0.5 * (rs * rs + rp * rp), 1e-12) << c;
  }
  EXPECT_NEAR(fresnel_conductor(0.2, 3.0, 0.0), 1.0, 1e-12);
  // Gold at 550 nm (η ≈ 0.43, κ ≈ 2.45): normal incidence ((η−1)² + κ²)/((η+1)² + κ²).
  const double e = 0.43, k = 2.45;
  EXPECT_NEAR(fresnel_conductor(e, k, 1.0), ((e - 1) * (e - 1) + k * k) / ((e + 1) * (e + 1) + k * k), 1e-12);
}

}  // namespace
}  // namespace glintlab
