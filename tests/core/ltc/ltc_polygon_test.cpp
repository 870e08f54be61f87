// Tests of the LTC lobe and polygon integral (core/ltc/ltc.h, Heitz et al. 2016 Eq. 1–2, 10–11):
// exact form factors, Monte Carlo of the lobe over polygons, horizon clipping, and a perturbed
// lobe that the Monte Carlo check must reject.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "core/lights/polygon_light.h"
#include "core/ltc/ltc.h"
#include "core/ltc/ltc_polygon_check.h"
#include "core/math/rng.h"

namespace glintlab {
namespace {

using V = Vec3<double>;

LtcLobe<double> identity_lobe() { return make_ltc_lobe_isotropic(1.0, 0.0, 0.0, 1.0, 1.0); }

// A skewed, stretched lobe like a grazing-view GGX fit.
LtcLobe<double> skewed_lobe() {
  const double m_inv[3][3] = {{2.5, 0.3, -1.2}, {-0.2, 1.7, 0.4}, {0.9, 0.1, 1.0}};
  return make_ltc_lobe(m_inv, 1.0);
}

// Counter-clockwise seen from the origin: the winding whose right-hand normal faces the origin.
std::vector<V> facing_origin(std::vector<V> v) {
  V newell{0, 0, 0};
  for (std::size_t k = 0; k < v.size(); ++k) newell = newell + cross(v[k], v[(k + 1) % v.size()]);
  if (dot(newell, v[0]) > 0) std::reverse(v.begin(), v.end());
  return v;
}

// Square of half-size L centred above the origin at height 1.
std::vector<V> square_above(double L) {
  return facing_origin({{-L, -L, 1}, {L, -L, 1}, {L, L, 1}, {-L, L, 1}});
}

// Form factor of the centred square (four corner rectangles of Howell's catalogue, C-11:
// F = (1/2π)[X/√(1+X²) atan(Y/√(1+X²)) + Y/√(1+Y²) atan(X/√(1+Y²))] each, X = Y = L).
double square_form_factor(double L) {
  const double s = std::sqrt(1 + L * L);
  return 4 * (2 * L / s * std::atan(L / s)) / (2 * std::numbers::pi);
}

struct McResult {
  double mean, sigma;
};

// Fraction of n samples of the lobe that hit the polygon: an unbiased estimate of ∫_P D_ltc.
McResult mc_lobe_over_polygon(const LtcLobe<double>& lobe, const std::vector<V>& poly,
                              const char* id, int n) {
  const PolygonLight<double> light = make_polygon_light<double>(poly, {1, 1, 1});
  const std::uint64_t seed = hash_string(id);
  long hits = 0;
  for (int i = 0; i < n; ++i) {
    const Vec2<double> u{counter_uniform<double>(seed, std::uint64_t(i), 0),
                         counter_uniform<double>(seed, std::uint64_t(i), 1)};
    const LtcSample<double> s = ltc_sample(lobe, u);
    detail::PlaneHit<double> h;
    if (light.hits(V{0, 0, 0}, s.dir, &h)) ++hits;
  }
  const double p = double(hits) / n;
  return {p, std::sqrt(std::max(p * (1 - p), 1.0 / n) / n)};
}

TEST(LtcPolygon, ClampedCosineSquareMatchesClosedForm) {
  for (double L : {0.1, 1.0, 10.0}) {
    const std::vector<V> sq = square_above(L);
    EXPECT_NEAR(clamped_cosine_polygon_integral(sq.data(), 4), square_form_factor(L), 1e-12) << L;
    EXPECT_NEAR(ltc_polygon_integral(identity_lobe(), sq.data(), 4), square_form_factor(L), 1e-12);
  }
}

TEST(LtcPolygon, HemisphereCoveringPolygonIntegratesToOne) {
  const std::vector<V> sq = square_above(1e6);
  EXPECT_NEAR(clamped_cosine_polygon_integral(sq.data(), 4), 1.0, 1e-6);
  // Any lobe integrates to 1 over the sphere: a huge polygon covering the lobe's support. The
  // support of D_ltc is the half-space (M⁻¹ω).z > 0, bounded by the plane row 2 of M⁻¹ · ω = 0;
  // a square far along that half-space's normal covers it.
  const LtcLobe<double> lobe = skewed_lobe();
  const V n = normalize(V{lobe.m_inv[2][0], lobe.m_inv[2][1], lobe.m_inv[2][2]});
  const V t = normalize(cross(n, std::abs(n.x) < 0.9 ? V{1, 0, 0} : V{0, 1, 0}));
  const V b = cross(n, t);
  const double L = 1e6;
  const std::vector<V> big =
      facing_origin({n + L * t + L * b, n - L * t + L * b, n - L * t - L * b, n + L * t - L * b});
  EXPECT_NEAR(ltc_polygon_integral(lobe, big.data(), 4), 1.0, 1e-5);
}

TEST(LtcPolygon, BackFacingIsZeroUnlessTwoSided) {
  std::vector<V> sq = square_above(1.0);
  std::reverse(sq.begin(), sq.end());
  EXPECT_EQ(clamped_cosine_polygon_integral(sq.data(), 4), 0.0);
  EXPECT_NEAR(clamped_cosine_polygon_integral(sq.data(), 4, true), square_form_factor(1.0), 1e-12);
}

TEST(LtcPolygon, HorizonClippingMatchesPreClippedPolygon) {
  // A wall at y = 2 reaching below the horizon, against the same wall cut at z = 0 by hand.
  const std::vector<V> wall = facing_origin({{-3, 2, -1.5}, {3, 2, -1.5}, {3, 2, 2}, {-3, 2, 2}});
  const std::vector<V> cut = facing_origin({{-3, 2, 0}, {3, 2, 0}, {3, 2, 2}, {-3, 2, 2}});
  EXPECT_NEAR(clamped_cosine_polygon_integral(wall.data(), 4),
              clamped_cosine_polygon_integral(cut.data(), 4), 1e-13);
  // A triangle with one vertex below (clipped polygon has 4 vertices) and one entirely below.
  const std::vector<V> tri = facing_origin({{-1, 1, 1}, {1, 1, 1}, {0, 1.5, -1}});
  const std::vector<V> tri_cut =
      facing_origin({{-1, 1, 1}, {1, 1, 1}, {0.5, 1.25, 0}, {-0.5, 1.25, 0}});
  EXPECT_NEAR(clamped_cosine_polygon_integral(tri.data(), 3),
              clamped_cosine_polygon_integral(tri_cut.data(), 4), 1e-13);
  const std::vector<V> below = facing_origin({{-1, 1, -1}, {1, 1, -1}, {0, 2, -0.5}});
  EXPECT_EQ(clamped_cosine_polygon_integral(below.data(), 3), 0.0);
}

TEST(LtcLobe, DensityIntegratesToOneAndMatchesSampler) {
  // ∫ D_ltc over the sphere by a midpoint grid in (cos θ, φ): 1 within the grid's error.
  const LtcLobe<double> lobe = skewed_lobe();
  const int n = 800;
  double sum = 0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < 2 * n; ++j) {
      const double z = -1 + 2 * (i + 0.5) / n, phi = std::numbers::pi * (j + 0.5) / n;
      const double r = std::sqrt(1 - z * z);
      sum += ltc_density(lobe, V{r * std::cos(phi), r * std::sin(phi), z});
    }
  EXPECT_NEAR(sum * 4 * std::numbers::pi / (2.0 * n * n), 1.0, 2e-3);
  // The sampler's pdf is the density at the sampled direction.
  const LtcSample<double> s = ltc_sample(lobe, Vec2<double>{0.3, 0.7});
  EXPECT_NEAR(s.pdf, ltc_density(lobe, s.dir), 1e-12 * s.pdf);
  EXPECT_NEAR(length(s.dir), 1.0, 1e-12);
}

// The analytic polygon integral against the fraction of lobe samples that hit the polygon, over
// polygons in front, across the lobe's horizon, and pentagons; tolerance 5 binomial σ.
std::vector<std::vector<V>> test_polygons() {
  return {facing_origin({{-0.5, -0.5, 0.9}, {0.6, -0.4, 1.02}, {0.5, 0.5, 1.1}, {-0.4, 0.6, 1.02}}),
          facing_origin({{0.05, 0.05, 1}, {0.15, 0.05, 1}, {0.15, 0.15, 1}, {0.05, 0.15, 1}}),
          facing_origin({{-3, 2, -1.5}, {3, 2, -1.5}, {3, 2, 2}, {-3, 2, 2}}),
          facing_origin({{2, -1, -0.5}, {2, 1, -0.5}, {2, 1.5, 1}, {2, 0, 2}, {2, -1.5, 1}}),
          facing_origin({{-1, 1, 1}, {1, 1, 1}, {0, 1.5, -1}})};
}

TEST(LtcPolygon, IntegralMatchesMonteCarloOfLobe) {
  const int n = 200000;
  int k = 0;
  for (const LtcLobe<double>& lobe : {identity_lobe(), skewed_lobe()})
    for (const std::vector<V>& poly : test_polygons()) {
      const double exact = ltc_polygon_integral(lobe, poly.data(), int(poly.size()));
      const McResult mc = mc_lobe_over_polygon(lobe, poly, "ltc.polygon-vs-mc", n);
      EXPECT_NEAR(exact, mc.mean, 5 * mc.sigma) << "lobe/polygon " << k;
      ++k;
    }
}

TEST(LtcPolygon, NegativeControlPerturbedLobeIsRejected) {
  // The integral of a lobe whose M⁻¹ is off by 5 % in one entry, against Monte Carlo of the true
  // lobe: at least one polygon must fall outside the same 5σ band.
  const int n = 200000;
  const LtcLobe<double> lobe = skewed_lobe();
  double m_inv[3][3];
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) m_inv[r][c] = lobe.m_inv[r][c];
  m_inv[0][2] *= 1.05;
  const LtcLobe<double> wrong = make_ltc_lobe(m_inv, 1.0);
  int rejected = 0;
  for (const std::vector<V>& poly : test_polygons()) {
    const McResult mc = mc_lobe_over_polygon(lobe, poly, "ltc.polygon-vs-mc", n);
    const double value = ltc_polygon_integral(wrong, poly.data(), int(poly.size()));
    if (std::abs(value - mc.mean) > 5 * mc.sigma) ++rejected;
  }
  EXPECT_GE(rejected, 1);
}

TEST(LtcPolygonCheck, RejectsBadPolygons) {
  const std::vector<V> ok = square_above(1.0);
  EXPECT_NO_THROW(check_ltc_polygon(ok));
  const std::vector<V> nonconvex{{0, 0, 1}, {2, 0, 1}, {0.5, 0.5, 1}, {0, 2, 1}};
  EXPECT_THROW(check_ltc_polygon(nonconvex), ParameterError);
  const std::vector<V> collinear{{0, 0, 1}, {1, 0, 1}, {2, 0, 1}};
  EXPECT_THROW(check_ltc_polygon(collinear), ParameterError);
  const std::vector<V> through_origin{{-1, 0, -1}, {1, 0, -1}, {1, 0, 1}, {-1, 0, 1}};
  try {
    check_ltc_polygon(through_origin);
    ADD_FAILURE() << "no error";
  } catch (const ParameterError& e) {
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("plane"), std::string::npos);
  }
}

}  // namespace
}  // namespace glintlab
