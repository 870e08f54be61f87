// Shared helpers for the light tests: seeds, counter-based u, the frame about a light's centre and
// the boundary of a planar light seen from a point (cubature breakpoints), written as functions
// of the light so the same checks run on every light and on deliberately wrong pdfs.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <numbers>
#include <string>
#include <vector>

#include "core/lights/light_sample.h"
#include "core/math/orthonormal_basis.h"
#include "core/math/rng.h"
#include "verify/check.h"
#include "verify/stats/chi_square.h"
#include "verify/stats/sphere_cubature.h"

namespace glintlab::light_checks {

using V2 = Vec2<double>;
using V3 = Vec3<double>;
inline constexpr double kPiD = std::numbers::pi;

inline V2 u2(std::uint64_t seed, std::uint64_t i) {
  return {counter_uniform<double>(seed, i, 0), counter_uniform<double>(seed, i, 1)};
}

// The significance level of one statistical test here: the suite's level for one check.
inline double level() { return verify::check_level(); }

// Directions as a light's sampler produces them; the zero vector for an invalid sample.
template <class Light>
verify::DirectionSampler sampler_of(const Light& light, V3 p, std::uint64_t seed) {
  return [&light, p, seed](std::uint64_t i) {
    const LightSample<double> s = light.sample(p, u2(seed, i));
    return s.valid ? s.wi : V3{0, 0, 0};
  };
}

// θ(φ) of a convex planar region's boundary in the frame whose pole is the direction from p to a
// point c inside it: the half-plane of directions at azimuth φ meets the light's plane in a ray
// from c; `exit(c, w)` returns how far along the in-plane unit direction w the region extends.
struct PlanarBoundary {
  V3 p, c, n;
  OrthonormalBasis<double> frame;
  std::function<double(V3 c, V3 w)> exit;

  double theta_at(double phi) const {
    const V3 e = std::cos(phi) * frame.x + std::sin(phi) * frame.y;
    V3 w = cross(cross(frame.z, e), n);
    if (dot(w, e) < 0) w = -w;
    w = normalize(w);
    const V3 q = c + exit(c, w) * w;
    return std::acos(std::clamp(dot(frame.z, normalize(q - p)), -1.0, 1.0));
  }
};

// Azimuths of points (polygon vertices) in the boundary's frame: where θ(φ) has its kinks.
inline std::vector<double> azimuths(const PlanarBoundary& b, const std::vector<V3>& points) {
  std::vector<double> out;
  for (const V3& q : points) {
    const V3 l = b.frame.to_local(q - b.p);
    double a = std::atan2(l.y, l.x);
    if (a < 0) a += 2 * kPiD;
    out.push_back(a);
  }
  std::sort(out.begin(), out.end());
  return out;
}

inline PlanarBoundary planar_boundary(V3 p, V3 c, V3 n, std::function<double(V3, V3)> exit) {
  return {p, c, n, basis_from_z(normalize(c - p)), std::move(exit)};
}

// Exit distance from c along w for a convex polygon (vertices in order).
inline std::function<double(V3, V3)> polygon_exit(std::vector<V3> v, V3 n) {
  return [v, n](V3 c, V3 w) {
    double best = 1e300;
    for (std::size_t k = 0; k < v.size(); ++k) {
      const V3 a = v[k], b = v[(k + 1) % v.size()];
      // c + λ w = a + μ (b − a) in the plane: solve with cross products about n.
      const V3 e = b - a;
      const double den = dot(cross(w, e), n);
      if (std::abs(den) < 1e-300) continue;
      const double lambda = dot(cross(a - c, e), n) / den;
      const double mu = dot(cross(a - c, w), n) / den;
      if (lambda > 0 && mu >= -1e-12 && mu <= 1 + 1e-12) best = std::min(best, lambda);
    }
    return best;
  };
}

// ∫ f over the sphere in the frame of `b` (f is given world directions), with the boundary as
// φ-dependent breakpoints.
inline verify::Integral integrate_about(const PlanarBoundary& b,
                                        const std::function<double(const V3&)>& f,
                                        std::vector<double> phi_breaks = {},
                                        double rel_tol = 1e-9) {
  verify::SphereCubatureOptions o;
  o.phi_breaks = std::move(phi_breaks);
  o.theta_breaks_at_phi = [&b](double phi, std::vector<double>& breaks) {
    breaks.push_back(b.theta_at(phi));
  };
  o.rel_tol = rel_tol;
  o.max_depth = 22;
  return verify::integrate_sphere([&](const V3& w) { return f(b.frame.to_world(w)); }, o);
}

}  // namespace glintlab::light_checks
