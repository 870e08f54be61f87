// Shapes: intersection distances and normals, and ∂p/∂u, ∂p/∂v against finite differences of the
// uv parameterization.
#include "core/scene/shapes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace glintlab {
namespace {

constexpr double kPi = std::numbers::pi;

void expect_near(Vec3<double> a, Vec3<double> b, double tol) {
  EXPECT_NEAR(a.x, b.x, tol);
  EXPECT_NEAR(a.y, b.y, tol);
  EXPECT_NEAR(a.z, b.z, tol);
}

TEST(Sphere, HitsFrontAndReportsOutwardNormal) {
  const Sphere<double> s{{0, 0, 0}, 2.0};
  const SurfaceHit<double> h = s.intersect({{0, 0, 5}, {0, 0, -1}});
  ASSERT_TRUE(h.hit);
  EXPECT_NEAR(h.t, 3.0, 1e-12);
  expect_near(h.p, {0, 0, 2}, 1e-12);
  expect_near(h.n, {0, 0, 1}, 1e-12);
  EXPECT_FALSE(s.intersect({{0, 3, 5}, {0, 0, -1}}).hit);  // passes beside it
  EXPECT_FALSE(s.intersect({{0, 0, 5}, {0, 0, 1}}).hit);   // points away
  EXPECT_TRUE(s.intersect({{0, 0, 0}, {1, 0, 0}}).hit);    // from inside
}

// p(u, v) of the sphere's parameterization, written independently of the kernel.
Vec3<double> sphere_point(double r, double u, double v) {
  return {r * std::sin(kPi * v) * std::cos(2 * kPi * u),
          r * std::sin(kPi * v) * std::sin(2 * kPi * u), r * std::cos(kPi * v)};
}

TEST(Sphere, UvAndDerivativesMatchTheParameterization) {
  const Sphere<double> s{{0, 0, 0}, 1.5};
  const double e = 1e-6;
  for (double u : {0.05, 0.3, 0.61, 0.9}) {
    for (double v : {0.1, 0.45, 0.8}) {
      const Vec3<double> p = sphere_point(1.5, u, v);
      const SurfaceHit<double> h = s.surface_at(p, true, 1.0);
      EXPECT_NEAR(h.uv.x, u, 1e-12);
      EXPECT_NEAR(h.uv.y, v, 1e-12);
      expect_near(h.dpdu,
                  (1 / (2 * e)) * (sphere_point(1.5, u + e, v) - sphere_point(1.5, u - e, v)),
                  1e-6);
      expect_near(h.dpdv,
                  (1 / (2 * e)) * (sphere_point(1.5, u, v + e) - sphere_point(1.5, u, v - e)),
                  1e-6);
      const Frame<double> f = h.frame();
      EXPECT_NEAR(dot(f.t, f.n), 0, 1e-12);
      EXPECT_NEAR(dot(f.b, f.n), 0, 1e-12);
      EXPECT_NEAR(length(f.t), 1, 1e-12);
    }
  }
}

TEST(Sphere, FrameAtThePoleIsOrthonormal) {
  const Sphere<double> s{{0, 0, 0}, 1.0};
  const Frame<double> f = s.intersect({{0, 0, 3}, {0, 0, -1}}).frame();
  EXPECT_NEAR(length(f.t), 1, 1e-12);
  EXPECT_NEAR(dot(f.t, f.n), 0, 1e-12);
  EXPECT_NEAR(length(cross(f.t, f.b) - f.n), 0, 1e-12);
}

TEST(Cylinder, HitsTheWallWithinItsLength) {
  const Frame<double> axis{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  const Cylinder<double> c{{0, 0, 1}, axis, 0.5, 2.0};
  const SurfaceHit<double> h = c.intersect({{3, 0, 1.5}, {-1, 0, 0}});
  ASSERT_TRUE(h.hit);
  EXPECT_NEAR(h.t, 2.5, 1e-12);
  expect_near(h.n, {1, 0, 0}, 1e-12);
  EXPECT_NEAR(h.uv.x, 0.0, 1e-12);
  EXPECT_NEAR(h.uv.y, (0.5 + 2.0) / 4.0, 1e-12);
  EXPECT_FALSE(c.intersect({{3, 0, 3.5}, {-1, 0, 0}}).hit);  // above the tube's end
  EXPECT_FALSE(c.intersect({{3, 0, 1}, {0, 0, 1}}).hit);     // parallel to the axis, outside
  // From inside the tube the far wall is hit.
  const SurfaceHit<double> in = c.intersect({{0, 0, 1}, {0, 1, 0}});
  ASSERT_TRUE(in.hit);
  EXPECT_NEAR(in.t, 0.5, 1e-12);
}

TEST(Cylinder, DerivativesMatchTheParameterizationOnATiltedAxis) {
  const Vec3<double> n = normalize(Vec3<double>{0.3, -0.2, 0.9});
  const Frame<double> axis = frame_from_normal_tangent(n, Vec3<double>{1, 0, 0});
  const Cylinder<double> c{{0.2, 0.1, -0.3}, axis, 0.7, 1.2};
  const auto point = [&](double u, double v) {
    const Vec3<double> l{0.7 * std::cos(2 * kPi * u), 0.7 * std::sin(2 * kPi * u), v * 2.4 - 1.2};
    return c.center + axis.to_world(l);
  };
  const double e = 1e-6;
  for (double u : {0.1, 0.4, 0.7}) {
    for (double v : {0.2, 0.6}) {
      const Vec3<double> p = point(u, v);
      const Vec3<double> nrm =
          normalize(axis.to_world({std::cos(2 * kPi * u), std::sin(2 * kPi * u), 0}));
      const SurfaceHit<double> h = c.intersect({p + 2.0 * nrm, -1.0 * nrm});
      ASSERT_TRUE(h.hit);
      expect_near(h.p, p, 1e-9);
      expect_near(h.n, nrm, 1e-9);
      EXPECT_NEAR(h.uv.x, u, 1e-9);
      EXPECT_NEAR(h.uv.y, v, 1e-9);
      expect_near(h.dpdu, (1 / (2 * e)) * (point(u + e, v) - point(u - e, v)), 1e-6);
      expect_near(h.dpdv, (1 / (2 * e)) * (point(u, v + e) - point(u, v - e)), 1e-6);
    }
  }
}

TEST(Plane, UvIsTheScaledLocalPosition) {
  const Frame<double> f{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  const Plane<double> p{{0, 0, 0}, f, 0.5, 0.0};
  const SurfaceHit<double> h = p.intersect({{1, 2, 3}, {0, 0, -1}});
  ASSERT_TRUE(h.hit);
  EXPECT_NEAR(h.uv.x, 2.0, 1e-12);
  EXPECT_NEAR(h.uv.y, 4.0, 1e-12);
  expect_near(h.dpdu, {0.5, 0, 0}, 1e-15);
  const Plane<double> bounded{{0, 0, 0}, f, 1.0, 1.5};
  EXPECT_FALSE(bounded.intersect({{1, 2, 3}, {0, 0, -1}}).hit);
  EXPECT_FALSE(p.intersect({{1, 2, 3}, {1, 0, 0}}).hit);  // parallel
}

}  // namespace
}  // namespace glintlab
