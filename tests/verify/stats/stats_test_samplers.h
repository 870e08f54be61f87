// Exact samplers and their densities, written for the statistics tests (counter RNG, so each
// sample depends only on (seed, index)).
#pragma once

#include <cmath>
#include <cstdint>
#include <numbers>

#include "core/math/rng.h"
#include "core/math/vec.h"

namespace glintlab::verify::testing {

inline constexpr double kPi = std::numbers::pi;

inline double uniform(std::uint64_t seed, std::uint64_t i, std::uint64_t dim) {
  return counter_uniform<double>(seed, i, dim);
}

inline Vec3<double> unit(Vec3<double> v) {
  const double l = std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
  return (1.0 / l) * v;
}

// A right-handed orthonormal frame (x, y, z = n) by Gram–Schmidt against a helper axis.
struct Frame {
  Vec3<double> x, y, z;
  explicit Frame(Vec3<double> n) : z(unit(n)) {
    const Vec3<double> a = std::abs(z.x) < 0.9 ? Vec3<double>{1, 0, 0} : Vec3<double>{0, 1, 0};
    x = unit(a - dot(a, z) * z);
    y = cross(z, x);
  }
  Vec3<double> to_world(Vec3<double> v) const { return v.x * x + v.y * y + v.z * z; }
};

inline Vec3<double> uniform_sphere(std::uint64_t seed, std::uint64_t i) {
  const double z = 1 - 2 * uniform(seed, i, 0), phi = 2 * kPi * uniform(seed, i, 1);
  const double r = std::sqrt(std::max(0.0, 1 - z * z));
  return {r * std::cos(phi), r * std::sin(phi), z};
}

// Cosine-weighted hemisphere about +z (Malley): pdf z/π.
inline Vec3<double> cosine_hemisphere(std::uint64_t seed, std::uint64_t i) {
  const double u = uniform(seed, i, 0), phi = 2 * kPi * uniform(seed, i, 1);
  const double r = std::sqrt(u);
  return {r * std::cos(phi), r * std::sin(phi), std::sqrt(1 - u)};
}
inline double cosine_pdf(const Vec3<double>& w) { return w.z > 0 ? w.z / kPi : 0.0; }

// von Mises–Fisher lobe of concentration kappa about `axis` (angular width 1/√kappa), sampled
// exactly by inverting its cosine marginal 1 − cosθ = −log(ξ + (1 − ξ)e^{−2κ})/κ.
struct VonMisesFisher {
  double kappa;
  Frame frame;
  VonMisesFisher(double k, Vec3<double> axis) : kappa(k), frame(axis) {}
  Vec3<double> sample(std::uint64_t seed, std::uint64_t i) const {
    const double xi = 1 - uniform(seed, i, 0);  // (0, 1]
    const double a = -std::log(xi + (1 - xi) * std::exp(-2 * kappa)) / kappa;  // 1 − cosθ
    const double st = std::sqrt(std::max(0.0, a * (2 - a)));
    const double phi = 2 * kPi * uniform(seed, i, 1);
    return frame.to_world({st * std::cos(phi), st * std::sin(phi), 1 - a});
  }
  double pdf(const Vec3<double>& w) const {
    return kappa / (2 * kPi * -std::expm1(-2 * kappa)) * std::exp(kappa * (dot(w, frame.z) - 1));
  }
};

// Uniform on the disk of centre (½, ½) and radius ½ (density 4/π).
inline Vec2<double> uniform_disk_polar(std::uint64_t seed, std::uint64_t i) {
  const double r = 0.5 * std::sqrt(uniform(seed, i, 0)), phi = 2 * kPi * uniform(seed, i, 1);
  return {0.5 + r * std::cos(phi), 0.5 + r * std::sin(phi)};
}
// Shirley–Chiu concentric map of the unit square onto the same disk.
inline Vec2<double> uniform_disk_concentric(std::uint64_t seed, std::uint64_t i) {
  const double a = 2 * uniform(seed, i, 0) - 1, b = 2 * uniform(seed, i, 1) - 1;
  if (a == 0 && b == 0) return {0.5, 0.5};
  double r, phi;
  if (std::abs(a) > std::abs(b)) {
    r = a;
    phi = kPi / 4 * (b / a);
  } else {
    r = b;
    phi = kPi / 2 - kPi / 4 * (a / b);
  }
  return {0.5 + 0.5 * r * std::cos(phi), 0.5 + 0.5 * r * std::sin(phi)};
}
inline double disk_pdf(const Vec2<double>& p) {
  const double dx = p.x - 0.5, dy = p.y - 0.5;
  return dx * dx + dy * dy <= 0.25 ? 4 / kPi : 0.0;
}

// A standard normal by Box–Muller from two counter uniforms.
inline double normal(std::uint64_t seed, std::uint64_t i) {
  const double u1 = 1 - uniform(seed, i, 0), u2 = uniform(seed, i, 1);
  return std::sqrt(-2 * std::log(u1)) * std::cos(2 * kPi * u2);
}

}  // namespace glintlab::verify::testing
