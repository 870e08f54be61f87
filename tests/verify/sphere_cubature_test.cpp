// Known integrals on the sphere for the adaptive cubature, and that its error estimate is honest.
#include "verify/stats/sphere_cubature.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace glintlab::verify {
namespace {

TEST(SphereCubature, AreaOfSphereAndHemisphere) {
  SphereCubatureOptions o;
  EXPECT_NEAR(integrate_sphere([](const Vec3<double>&) { return 1.0; }, o).value,
              4 * std::numbers::pi, 1e-12);
  o.theta_max = std::numbers::pi / 2;
  EXPECT_NEAR(integrate_sphere([](const Vec3<double>& w) { return w.z; }, o).value,
              std::numbers::pi, 1e-12);
}

// A von Mises–Fisher lobe of concentration 1e6 (width 1e-3 rad) integrates to 1, with an error
// estimate that covers the true error.
TEST(SphereCubature, NarrowLobe) {
  const double kappa = 1e6;
  auto vmf = [&](const Vec3<double>& w) {
    return kappa / (2 * std::numbers::pi) * std::exp(kappa * (w.z - 1)) / (-std::expm1(-2 * kappa));
  };
  SphereCubatureOptions o;
  o.theta_breaks = lobe_theta_breaks(1e-3, 0, std::numbers::pi);
  const Integral with = integrate_sphere(vmf, o);
  EXPECT_NEAR(with.value, 1.0, 1e-9);
  EXPECT_LT(with.error, 1e-7);
  EXPECT_GE(with.error, 0.1 * std::abs(with.value - 1.0));
}

// An interior lobe between two breakpoints that the first Kronrod rule cannot see: a Gaussian
// ring of width 1e-4 at θ = 1. The error estimate must not claim convergence on a wrong value.
TEST(SphereCubature, ErrorEstimateIsHonestOrValueIsRight) {
  const double s = 1e-4;
  auto ring = [&](const Vec3<double>& w) {
    const double t = std::acos(std::clamp(w.z, -1.0, 1.0));
    return std::exp(-0.5 * (t - 1) * (t - 1) / (s * s)) / (std::sqrt(2 * std::numbers::pi) * s) /
           (2 * std::numbers::pi * std::sin(t));
  };
  SphereCubatureOptions o;
  o.theta_breaks = {0.999, 1.001};
  const Integral r = integrate_sphere(ring, o);
  EXPECT_NEAR(r.value, 1.0, 1e-8);
}

TEST(SphereCubature, AnisotropicAzimuthBreaksAreInRange) {
  for (double b : anisotropy_phi_breaks(1.0, 1e-3)) {
    EXPECT_GE(b, 0.0);
    EXPECT_LE(b, 2 * std::numbers::pi);
  }
}

}  // namespace
}  // namespace glintlab::verify
