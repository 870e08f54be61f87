// Tests of core/glints/deliot_belcour.h and kneiphof.h: the radiance factor averages to 1 (E[b] =
// N p), Eq. 22 = Eq. 16 where p is not clamped, Eq. 20 at normal incidence, the clamp is reported,
// the multinomial split and the Monte Carlo area-light terms, and bad parameters are rejected.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "core/glints/deliot_belcour.h"
#include "core/glints/kneiphof.h"
#include "core/lights/polygon_light_check.h"
#include "core/model_registry.h"

namespace glintlab {
namespace {

ModelQuery<double> query(Vec3<double> wi, Vec3<double> wo, double u, double side) {
  ModelQuery<double> q{};
  q.footprint.uv = {u, 0.25};
  q.footprint.duv_dx = {side, 0};
  q.footprint.duv_dy = {0, side};
  q.wi = wi;
  q.wo = wo;
  q.light = {1.0, 1.0};
  return q;
}

Vec3<double> dir(double theta, double phi) {
  return {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
}

TEST(DeliotBelcour, FactorAveragesToOneAndClampIsReported) {
  const auto p = DeliotBelcour::params<double>(std::vector<double>{0.3, 0.3, 6, 0.5, 0, 3});
  const Vec3<double> wi = dir(0.4, 0), wo = dir(0.5, 3.0);
  double sum = 0;
  const int m = 4000;
  for (int i = 0; i < m; ++i) {
    const auto e = DeliotBelcour::eval(p, query(wi, wo, 0.001 * i, 1e-2));  // N_P = 100
    EXPECT_EQ(e.intermediates[0], 100);
    EXPECT_NEAR(e.value, e.intermediates[6] * e.intermediates[5], 1e-15);
    sum += e.intermediates[5];
  }
  EXPECT_NEAR(sum / m, 1, 0.05);
  // R = 3 at the peak: R D(h)/D(n) = 3 > 1, clamped and flagged.
  const auto pc = DeliotBelcour::params<double>(std::vector<double>{0.3, 0.3, 6, 3, 0, 3});
  const auto e = DeliotBelcour::eval(pc, query(dir(0.3, 0), dir(0.3, std::numbers::pi), 0.1, 1e-2));
  EXPECT_NEAR(e.intermediates[1], 3, 1e-9);
  EXPECT_EQ(e.intermediates[2], 1);
  EXPECT_EQ(e.intermediates[3], 1);
  EXPECT_EQ(e.intermediates[4], 100);  // p = 1: every facet reflects
}

TEST(KneiphofKlein, Eq20AtNormalIncidenceAndEq22) {
  const double a = 0.25, g = 5.0;
  const auto p = KneiphofKlein::params<double>(std::vector<double>{a, a, 6, g, 0, 1});
  const double dh = total_area_ggx_eq29(a);
  const double omc = one_minus_cos(g * std::numbers::pi / 180);
  // h = n, ⟨h, ω_l⟩ = 1, D(n) = 1/(π α²): p = 2π(1 − cos γ)/(4 π α² D_H).
  const auto e = KneiphofKlein::eval(p, query({0, 0, 1}, {0, 0, 1}, 0.2, 1e-2));
  EXPECT_NEAR(e.intermediates[1], 2 * std::numbers::pi * omc / (4 * std::numbers::pi * a * a * dh),
              1e-12);
  EXPECT_NEAR(e.intermediates[8], g * std::numbers::pi / 180, 1e-12);
  // Off the peak (p < 1): Eq. 22 equals the Eq. 16 value.
  for (int i = 0; i < 50; ++i) {
    const auto f = KneiphofKlein::eval(p, query(dir(0.6, 0), dir(0.9, 2.5), 0.01 * i, 1e-2));
    ASSERT_LT(f.intermediates[1], 1);
    EXPECT_NEAR(f.value, f.intermediates[9], 1e-12 * (1 + f.value));
  }
}

TEST(KneiphofKlein, ClampRegionIsSmoothSurfacesAndLargeCaps) {
  const auto smooth_big =
      KneiphofKlein::params<double>(std::vector<double>{0.01, 0.01, 6, 5, 0, 1});
  const auto e = KneiphofKlein::eval(smooth_big, query({0, 0, 1}, {0, 0, 1}, 0.2, 1e-2));
  EXPECT_GT(e.intermediates[1], 1);
  EXPECT_EQ(e.intermediates[3], 1);
  EXPECT_NEAR(e.intermediates[5], 1, 1e-15);  // b = N: the continuous BRDF
  const auto rough_sun =
      KneiphofKlein::params<double>(std::vector<double>{0.81, 0.81, 6, 0.26, 0, 1});
  EXPECT_LT(KneiphofKlein::eval(rough_sun, query({0, 0, 1}, {0, 0, 1}, 0.2, 1e-2)).intermediates[1],
            1e-3);
}

TEST(KneiphofKlein, BadParametersAreOneLineErrors) {
  const ModelEntry& m = find_model("kneiphof_klein");
  for (const char* bad : {"0", "90", "-1", "120"}) {
    try {
      resolve_params(m, {{"gamma_deg", bad}});
      FAIL() << bad;
    } catch (const ModelParamError& e) {
      const std::string w = e.what();
      EXPECT_NE(w.find("gamma_deg"), std::string::npos) << w;
      EXPECT_EQ(w.find('\n'), std::string::npos);
    }
  }
  EXPECT_THROW(resolve_params(m, {{"density", "16"}}), ModelParamError);
  EXPECT_THROW(resolve_params(find_model("deliot_belcour"), {{"density", "-1"}}), ModelParamError);
  // A non-convex polygon light: make_polygon_light's one-line error.
  const std::vector<Vec3<double>> dart = {{0, 0, 1}, {1, 0, 1}, {0.2, 0.2, 1}, {0, 1, 1}};
  EXPECT_THROW(make_polygon_light(dart, {1, 1, 1}), ParameterError);
}

TEST(Kneiphof, MultinomialSplitSumsAndMarginals) {
  const std::vector<double> parts = {0.1, 0.05, 0.2, 0.15};
  double mean1 = 0;
  const int m = 20000;
  for (int i = 0; i < m; ++i) {
    const auto c = kneiphof2024::multinomial_split(1000, parts, 7, std::uint64_t(i));
    std::uint64_t s = 0;
    for (auto x : c) s += x;
    ASSERT_EQ(s, 1000u);
    mean1 += double(c[1]) / m;
  }
  EXPECT_NEAR(mean1, 1000 * 0.05 / 0.5, 0.3);
}

TEST(Kneiphof, AreaTermsOfATinyLightMatchTheCap) {
  // A square of half-width 0.01 at distance 1 straight above: Ω ≈ 4e-4; D_Ωh ≈ Ω D(h)/(4⟨h, ω⟩).
  const double w = 0.01;
  const Vec3<double> c = normalize(Vec3<double>{0.3, 0.1, 1.0});
  const OrthonormalBasis<double> b = basis_from_z(c);
  std::vector<Vec3<double>> v;
  for (auto [x, y] : std::vector<std::pair<double, double>>{{-w, w}, {w, w}, {w, -w}, {-w, -w}})
    v.push_back(c + x * b.x + y * b.y);
  const auto light = make_polygon_light(v, {1, 1, 1});
  const GGX<double> ggx{0.3, 0.3};
  const Vec3<double> wi = dir(0.2, 3.0);
  const kneiphof2024::AreaLightTerms t =
      kneiphof2024::area_light_terms_mc(ggx, wi, light, Vec3<double>{0, 0, 0}, 4096, 11, 0);
  const Vec3<double> h = half_vector(wi, c);
  EXPECT_NEAR(t.solid_angle, 4 * w * w, 4e-6);
  EXPECT_NEAR(t.d_omega_h / (t.solid_angle * ggx.D(h) / (4 * dot(h, c))), 1, 2e-3);
  EXPECT_NEAR(t.lo_over_li / (t.solid_angle * microfacet_brdf(ggx, wi, c, 1.0) * c.z), 1, 2e-3);
}

}  // namespace
}  // namespace glintlab
