// Pixel footprints: the uv Jacobian from ray differentials against its closed form for a plane
// seen head-on and against finite differences across pixels on a sphere; the corner derivatives
// of the half and reflection vectors against neighbouring pixels.
#include "core/scene/footprint.h"

#include <gtest/gtest.h>

#include <cmath>

namespace glintlab {
namespace {

TEST(Footprint, HeadOnPlaneHasTheClosedFormJacobian) {
  // Camera 2 units above the plane z = 0, looking down; uv = world (x, y) / 0.25.
  const int w = 64, h = 48;
  const auto cam = PinholeCamera<double>::look_at({0, 0, 2}, {0, 0, 0}, {0, 1, 0}, 40.0, w, h);
  const Plane<double> plane{{0, 0, 0}, Frame<double>{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, 0.25, 0.0};
  const LightPoint<double> light{{0, 0, 1}, true};
  const PixelFootprint<double> f = pixel_footprint(cam, plane, 32.0, 24.0, light);
  ASSERT_TRUE(f.surface.hit);
  // One pixel spans 2·2·tan(20°)/48 world units vertically (square pixels).
  const double pixel = 2 * 2 * std::tan(20 * std::acos(-1.0) / 180) / h;
  const Vec3<double> right = cam.frame.t;  // world direction of +x on screen
  EXPECT_NEAR(f.footprint.duv_dx.x, right.x * pixel / 0.25, 1e-9);
  EXPECT_NEAR(f.footprint.duv_dx.y, right.y * pixel / 0.25, 1e-9);
  EXPECT_NEAR(f.footprint.duv_dy.x, -cam.frame.b.x * pixel / 0.25, 1e-9);
  EXPECT_NEAR(f.footprint.duv_dy.y, -cam.frame.b.y * pixel / 0.25, 1e-9);
  EXPECT_NEAR(f.wi.z, 1.0, 1e-12);
}

TEST(Footprint, SphereJacobianMatchesFiniteDifferencesAcrossPixels) {
  const int w = 200, h = 200;
  const auto cam = PinholeCamera<double>::look_at({3, 0.5, 1}, {0, 0, 0}, {0, 0, 1}, 30.0, w, h);
  const Sphere<double> s{{0, 0, 0}, 1.0};
  const LightPoint<double> light{{2, 3, 4}, false};
  int checked = 0;
  for (double y : {70.5, 100.5, 130.5}) {
    for (double x : {70.5, 100.5, 130.5}) {
      const auto f = pixel_footprint(cam, s, x, y, light);
      const auto fx0 = pixel_footprint(cam, s, x - 0.5, y, light);
      const auto fx1 = pixel_footprint(cam, s, x + 0.5, y, light);
      const auto fy0 = pixel_footprint(cam, s, x, y - 0.5, light);
      const auto fy1 = pixel_footprint(cam, s, x, y + 0.5, light);
      ASSERT_TRUE(f.surface.hit && fx0.surface.hit && fx1.surface.hit);
      // The tangent-plane differential is first order: agreement to ~1% of a pixel's uv step.
      const Vec2<double> dx = fx1.surface.uv - fx0.surface.uv;
      const Vec2<double> dy = fy1.surface.uv - fy0.surface.uv;
      const double sx = std::hypot(dx.x, dx.y), sy = std::hypot(dy.x, dy.y);
      EXPECT_NEAR(f.footprint.duv_dx.x, dx.x, 0.02 * sx);
      EXPECT_NEAR(f.footprint.duv_dx.y, dx.y, 0.02 * sx);
      EXPECT_NEAR(f.footprint.duv_dy.x, dy.x, 0.02 * sy);
      EXPECT_NEAR(f.footprint.duv_dy.y, dy.y, 0.02 * sy);
      // Reflection vector derivative against the centre-ray reflections half a pixel away.
      const auto refl = [&](const PixelFootprint<double>& g) {
        return reflect(normalize(cam.eye - g.surface.p), g.surface.n);
      };
      const Vec3<double> drx = refl(fx1) - refl(fx0);
      EXPECT_NEAR(length(f.dr_dx - drx), 0.0, 0.02 * length(drx));
      // Half vector in the local frame: compare with the centre-pixel half vectors.
      const auto half = [&](const PixelFootprint<double>& g) { return half_vector(g.wi, g.wl); };
      const Vec3<double> dhy = half(fy1) - half(fy0);
      EXPECT_NEAR(length(f.dh_dy - dhy), 0.0, 0.05 * length(dhy) + 1e-9);
      ++checked;
    }
  }
  EXPECT_EQ(checked, 9);
}

TEST(Footprint, DerivativesGrowWithCurvature) {
  // A control that the corner derivatives see the surface: at the same pixel a smaller sphere
  // (larger curvature) turns the reflection vector faster.
  const int w = 100, h = 100;
  const auto cam = PinholeCamera<double>::look_at({0, 0, 10}, {0, 0, 0}, {0, 1, 0}, 10.0, w, h);
  const LightPoint<double> light{{0, 0, 1}, true};
  const auto big = pixel_footprint(cam, Sphere<double>{{0, 0, 0}, 0.8}, 50.5, 50.5, light);
  const auto plane = pixel_footprint(
      cam, Plane<double>{{0, 0, 0.8}, Frame<double>{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, 1.0, 0.0},
      50.5, 50.5, light);
  EXPECT_GT(length(big.dr_dx), 10 * length(plane.dr_dx));
}

}  // namespace
}  // namespace glintlab
