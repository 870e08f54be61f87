// Podee et al. Sec. 3 kernels: the circle–polygon and circle–circle areas against closed forms and
// a dense grid count, the selected point against a brute-force search of the reflection space,
// the weights' range, float/double agreement, and the host-side light check.
#include "core/shading/podee_light_check.h"
#include "core/shading/podee_shade.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/math/rng.h"

namespace glintlab {
namespace {

constexpr double kPiD = std::numbers::pi;

// Area of circle ∩ polygon by counting an n × n grid of cell centres over the bounding box.
template <int N>
double grid_area(const Vec2<double> (&q)[N], Vec2<double> c, double r, int n) {
  double x0 = c.x - r, x1 = c.x + r, y0 = c.y - r, y1 = c.y + r;
  const double hx = (x1 - x0) / n, hy = (y1 - y0) / n;
  long count = 0;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const Vec2<double> p{x0 + (i + 0.5) * hx, y0 + (j + 0.5) * hy};
      if (dot(p - c, p - c) > r * r) continue;
      double w = 0;  // winding number
      for (int k = 0; k < N; ++k) {
        const Vec2<double> a = q[k] - p, b = q[(k + 1) % N] - p;
        w += std::atan2(perp_dot(a, b), dot(a, b));
      }
      if (std::abs(w) > kPiD) ++count;
    }
  return double(count) * hx * hy;
}

TEST(CircleIntersectionArea, ClosedFormCases) {
  const Vec2<double> sq[4] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
  const Vec2<double> o{0, 0};
  EXPECT_NEAR(circle_polygon_area(sq, o, 1.0), kPiD, 1e-12);            // circle inside
  EXPECT_NEAR(circle_polygon_area(sq, o, 2.0), 4.0, 1e-12);             // square inside
  EXPECT_NEAR(circle_polygon_area(sq, {1, 1}, 0.5), kPiD / 16, 1e-12);  // quarter at a corner
  EXPECT_NEAR(circle_polygon_area(sq, {1, 0}, 0.5), kPiD / 8, 1e-12);   // half on an edge
  EXPECT_NEAR(circle_polygon_area(sq, {3, 0}, 0.5), 0.0, 1e-12);        // apart
  const Vec2<double> cw[4] = {{-1, -1}, {-1, 1}, {1, 1}, {1, -1}};      // clockwise
  EXPECT_NEAR(circle_polygon_area(cw, o, 1.0), kPiD, 1e-12);
  EXPECT_NEAR(polygon_signed_area(sq), 4.0, 1e-15);
  EXPECT_NEAR(polygon_signed_area(cw), -4.0, 1e-15);
  // Circle of radius √2 on the square: the square minus 4 segments of angle π/2... no: the
  // circle of radius 1.2 about the centre, 4 caps cut off, each r² (θ − sin θ)/2 with cos(θ/2) =
  // 1/r.
  const double r = 1.2, th = 2 * std::acos(1 / r);
  EXPECT_NEAR(circle_polygon_area(sq, o, r), kPiD * r * r - 4 * 0.5 * r * r * (th - std::sin(th)),
              1e-12);
  EXPECT_NEAR(circle_circle_area<double>({0, 0}, 1, {3, 0}, 1), 0.0, 1e-15);
  EXPECT_NEAR(circle_circle_area<double>({0, 0}, 1, {0.2, 0}, 0.5), kPiD * 0.25, 1e-15);
  EXPECT_NEAR(circle_circle_area<double>({0, 0}, 1, {1, 0}, 1), 2 * kPiD / 3 - std::sqrt(3) / 2,
              1e-12);
}

TEST(CircleIntersectionArea, MatchesGridCountOnRandomQuads) {
  for (int t = 0; t < 20; ++t) {
    Vec2<double> q[4];
    for (int k = 0; k < 4; ++k) {  // star-shaped around the origin: simple, convex or not
      const double ang = (k + 0.8 * counter_uniform<double>(11, t, 2 * k)) * kPiD / 2;
      const double rad = 0.3 + 1.5 * counter_uniform<double>(11, t, 2 * k + 1);
      q[k] = {rad * std::cos(ang), rad * std::sin(ang)};
    }
    const Vec2<double> c{counter_uniform<double>(12, t, 0) - 0.5,
                         counter_uniform<double>(12, t, 1) - 0.5};
    const double r = 0.2 + counter_uniform<double>(12, t, 2);
    const int n = 500;
    const double want = grid_area(q, c, r, n);
    // grid error: about the boundary length × cell size
    EXPECT_NEAR(circle_polygon_area(q, c, r), want, 12 * r * (2 * r / n) * 4) << t;
    const Vec2<double> c2{counter_uniform<double>(13, t, 0), counter_uniform<double>(13, t, 1)};
    const double r2 = 0.2 + counter_uniform<double>(13, t, 2);
    long count = 0;
    const double h = 2 * r / n;
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const Vec2<double> p{c.x - r + (i + 0.5) * h, c.y - r + (j + 0.5) * h};
        if (dot(p - c, p - c) <= r * r && dot(p - c2, p - c2) <= r2 * r2) ++count;
      }
    EXPECT_NEAR(circle_circle_area(c, r, c2, r2), double(count) * h * h, 8 * (r + r2) * h) << t;
  }
}

// Four corner reflection vectors around the light direction l: the light-plane points q_k.
std::array<Vec3<double>, 4> corners_from_plane(Vec3<double> l, const Vec2<double> (&p)[4]) {
  const OrthonormalBasis<double> b = basis_from_z(l);
  std::array<Vec3<double>, 4> r{};
  for (int k = 0; k < 4; ++k) r[k] = normalize(l + p[k].x * b.x + p[k].y * b.y);
  return r;
}

TEST(PodeeShade, SelectsTheClosestPointOfTheReflectionSpace) {
  const Vec3<double> l = normalize(Vec3<double>{0.3, -0.2, 0.9});
  for (int t = 0; t < 200; ++t) {
    // Corners in footprint order of a random convex quad (a jittered square, shifted).
    const double s = 0.05 + 0.3 * counter_uniform<double>(21, t, 0);
    const Vec2<double> shift{0.6 * (counter_uniform<double>(21, t, 1) - 0.5),
                             0.6 * (counter_uniform<double>(21, t, 2) - 0.5)};
    Vec2<double> p[4];
    const double ox[4] = {-1, 1, -1, 1}, oy[4] = {-1, -1, 1, 1};
    for (int k = 0; k < 4; ++k)
      p[k] = {shift.x + s * (ox[k] + 0.3 * (counter_uniform<double>(22, t, k) - 0.5)),
              shift.y + s * (oy[k] + 0.3 * (counter_uniform<double>(23, t, k) - 0.5))};
    const auto r = corners_from_plane(l, p);
    const double tan_radius = 0.02 + 0.1 * counter_uniform<double>(21, t, 3);
    const podee::Result<double> res = podee::shade(r, l, tan_radius);
    // Brute force: bilinear combinations of the corner vectors, projected.
    const OrthonormalBasis<double> b = basis_from_z(l);
    double best = 1e300;
    const int n = 200;
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i) {
        const double a = double(i) / n, c = double(j) / n;
        const Vec3<double> v =
            (1 - a) * (1 - c) * r[0] + a * (1 - c) * r[1] + (1 - a) * c * r[2] + a * c * r[3];
        const Vec2<double> x{dot(v, b.x) / dot(v, b.z), dot(v, b.y) / dot(v, b.z)};
        best = std::min(best, std::sqrt(dot(x, x)));
      }
    EXPECT_LE(res.distance, best + 1e-12) << t;
    EXPECT_GE(res.distance, best - 3 * s / n) << t;
    EXPECT_EQ(static_cast<bool>(res.inside), res.distance == 0.0) << t;
    EXPECT_NEAR(length(res.r), 1.0, 1e-14);
    EXPECT_GE(res.weight, 0.0);
    EXPECT_LE(res.weight, 1.0);
    // mirror + uniform disk (podee_shade.h header); the sectors of a missed circle cancel to
    // rounding
    EXPECT_EQ(res.lit > 0, res.weight > 1e-12) << t << " " << res.weight;
    // The wrong rules never select a closer point, and are farther on some quads.
    EXPECT_GE(
        podee::shade(r, l, tan_radius, podee::Weighting::kExact, podee::Selection::kNearestCorner)
            .distance,
        res.distance - 1e-15);
  }
}

TEST(PodeeShade, WeightsAreAreaFractions) {
  const Vec3<double> l{0, 0, 1};
  const Vec2<double> p[4] = {{-0.1, -0.1}, {0.1, -0.1}, {-0.1, 0.1}, {0.1, 0.1}};
  const auto r = corners_from_plane(l, p);
  // A circle of radius 0.05 fully inside the 0.2 × 0.2 quad: weight = π 0.05² / 0.04.
  const podee::Result<double> in = podee::shade(r, l, 0.05);
  EXPECT_TRUE(in.inside);
  EXPECT_NEAR(in.weight, kPiD * 0.0025 / 0.04, 1e-9);
  EXPECT_NEAR(podee::shade(r, l, 0.05, podee::Weighting::kQuadAsCircle).weight, in.weight, 1e-9);
  EXPECT_EQ(podee::shade(r, l, 0.05, podee::Weighting::kNone).weight, 1.0);
  // A circle covering the quad: weight 1.
  EXPECT_NEAR(podee::shade(r, l, 0.5).weight, 1.0, 1e-12);
  // Light off to the side: not lit, weight 0.
  const Vec3<double> l2 = normalize(Vec3<double>{0.5, 0, 1});
  const podee::Result<double> off = podee::shade(r, l2, 0.05);
  EXPECT_FALSE(off.inside);
  EXPECT_EQ(off.lit, 0.0);
  EXPECT_EQ(off.value, 0.0);
}

TEST(PodeeShade, FloatAgreesWithDouble) {
  const Vec3<double> l = normalize(Vec3<double>{0.1, 0.2, 0.95});
  const Vec2<double> p[4] = {{-0.05, -0.08}, {0.12, -0.1}, {-0.07, 0.09}, {0.1, 0.12}};
  const auto r = corners_from_plane(l, p);
  std::array<Vec3<float>, 4> rf{};
  for (int k = 0; k < 4; ++k) rf[k] = {float(r[k].x), float(r[k].y), float(r[k].z)};
  const Vec3<float> lf{float(l.x), float(l.y), float(l.z)};
  for (int w = 0; w < 3; ++w) {
    const auto d = podee::shade(r, l, 0.07, podee::Weighting(w));
    const auto f = podee::shade(rf, lf, 0.07f, podee::Weighting(w));
    EXPECT_NEAR(f.weight, d.weight, 2e-4) << w;
    EXPECT_NEAR(f.distance, d.distance, 1e-5) << w;
  }
}

TEST(PodeeShade, HostCheckRejectsBadLights) {
  EXPECT_THROW(podee::require_light("podee", 0.0, 1.0), ParameterError);
  EXPECT_THROW(podee::require_light("podee", -1.0, 1.0), ParameterError);
  EXPECT_THROW(podee::require_light("podee", 0.1, -0.5), ParameterError);
  EXPECT_NO_THROW(podee::require_light("podee", 0.1, 0.5));
  try {
    podee::require_light("podee scene", 0.0, 1.0);
  } catch (const ParameterError& e) {
    EXPECT_EQ(std::string(e.what()),
              "podee scene: disk radius = 0 is out of range (valid: a finite radius > 0)");
  }
  EXPECT_NEAR(podee::tan_radius(std::cos(0.1)), std::tan(0.1), 1e-14);
}

}  // namespace
}  // namespace glintlab
