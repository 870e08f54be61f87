// Known integrals on the sphere for the adaptive cubature, and that its error estimate is honest.
#include "verify/stats/sphere_cubature.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numbers>
#include <span>
#include <vector>

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

// integrate_sphere_rows (the integrand over many directions per call) takes the same points,
// rules and bisections as integrate_sphere: the same value, error and evaluation count, bit for
// bit, in far fewer calls; here with a kink along a tilted great circle that the θ breaks at each
// φ follow (as the conformance suite's cubature about the mirror direction) and a narrow lobe.
TEST(SphereCubature, RowsGiveTheSameIntegralBitForBit) {
  const Vec3<double> n{0.3, -0.2, std::sqrt(1 - 0.13)};
  auto f = [&](const Vec3<double>& w) {
    const double c = w.x * n.x + w.y * n.y + w.z * n.z;
    return std::max(c, 0.0) / std::numbers::pi + 50 * std::exp(400 * (w.z - 1));
  };
  SphereCubatureOptions o;
  o.theta_breaks = lobe_theta_breaks(0.05, 0, std::numbers::pi);
  o.theta_breaks_at_phi = [&](double phi, std::vector<double>& breaks) {
    breaks.push_back(plane_crossing_theta(n, phi));
  };
  o.rel_tol = 1e-6;
  o.max_depth = 12;
  long calls = 0;
  const Integral one = integrate_sphere(f, o);
  const Integral rows = integrate_sphere_rows(
      [&](std::span<const Vec3<double>> w, std::span<double> out) {
        ++calls;
        for (std::size_t i = 0; i < w.size(); ++i) out[i] = f(w[i]);
      },
      o);
  EXPECT_EQ(std::memcmp(&one.value, &rows.value, sizeof(double)), 0) << one.value << " " << rows.value;
  EXPECT_EQ(std::memcmp(&one.error, &rows.error, sizeof(double)), 0) << one.error << " " << rows.error;
  EXPECT_EQ(one.evaluations, rows.evaluations);
  EXPECT_LT(calls * 100, rows.evaluations) << calls;
}

}  // namespace
}  // namespace glintlab::verify
