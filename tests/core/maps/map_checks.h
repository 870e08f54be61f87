// Checks shared by the NDF→disk map tests (Kemppinen et al. 2025 Sec. 3.2).
// Round trips, the true Jacobian against finite differences on the sphere, containment in the
// inscribed disk.
// Each check takes the map as callables so the same check can be run on a deliberately broken map.
#pragma once

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>

#include "core/math/vec.h"

namespace glintlab::maptest {

using V3 = Vec3<double>;
using V2 = Vec2<double>;

struct MapFns {
  std::function<V2(V3)> to;              // T(ω) in the unit square
  std::function<V3(V2)> from;            // T⁻¹(p)
  std::function<double(V3)> jacobian;    // claimed |det dT/dω| per steradian
  std::function<double(V3)> step_scale;  // angular length over which T is close to linear at ω
};

struct Alpha {
  double x, y;
};

// Roughness set: 1e-4 to 4, isotropic and anisotropic to 1:1000 both ways.
inline const std::vector<Alpha> kAlphas = {{1e-4, 1e-4}, {1e-3, 1e-3}, {0.05, 0.05}, {0.3, 0.3},
                                           {1, 1},       {4, 4},       {1e-4, 0.1},  {0.1, 1e-4},
                                           {1e-3, 1},    {4, 4e-3},    {0.2, 0.6},   {2.5, 0.7}};

inline V3 direction(double theta, double phi) {
  return {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
}

// θ from +z to 89.9°, geometric near the pole so that the lobes of α = 1e-4 are sampled.
inline std::vector<V3> directions() {
  std::vector<V3> d;
  const double deg = std::numbers::pi / 180;
  const std::vector<double> thetas = {0,   1e-5, 1e-4, 1e-3, 5e-3, 0.02, 0.1,       0.3,
                                      0.6, 0.9,  1.2,  1.4,  1.5,  1.55, 89.9 * deg};
  const std::vector<double> phis = {0, 0.3, std::numbers::pi / 2, 2.0, 3.5, 5.1};
  for (double t : thetas)
    for (double p : phis) d.push_back(direction(t, p));
  return d;
}

// Points of the unit square inside the inscribed disk, from the centre to the rim (r = 1 − 1e-9
// and r = 1 included).
inline std::vector<V2> disk_points() {
  std::vector<V2> p;
  const std::vector<double> radii = {0,   1e-9, 1e-5, 0.01,  0.1,      0.3,      0.5,
                                     0.7, 0.9,  0.99, 0.999, 1 - 1e-6, 1 - 1e-9, 1};
  for (double r : radii)
    for (int k = 0; k < 8; ++k) {
      const double a = 0.37 + k * std::numbers::pi / 4;
      p.push_back({0.5 + 0.5 * r * std::cos(a), 0.5 + 0.5 * r * std::sin(a)});
    }
  return p;
}

inline double dist(V2 a, V2 b) { return std::hypot(a.x - b.x, a.y - b.y); }
inline double dist(V3 a, V3 b) { return std::sqrt(length_sqr(a - b)); }

// max |T(T⁻¹(p)) − p| over disk points.
inline double roundtrip_square_error(const MapFns& m, const std::vector<V2>& pts) {
  double e = 0;
  for (V2 p : pts) e = std::max(e, dist(m.to(m.from(p)), p));
  return e;
}

// max |T⁻¹(T(ω)) − ω| over directions.
inline double roundtrip_direction_error(const MapFns& m, const std::vector<V3>& dirs) {
  double e = 0;
  for (V3 w : dirs) e = std::max(e, dist(m.from(m.to(w)), w));
  return e;
}

// |det dT/dω| by central differences in double on the tangent plane at ω: ω(s, t) =
// normalize(ω + s e1 + t e2) has ∂ω/∂s = e1, ∂ω/∂t = e2 at 0, an orthonormal pair, so the
// determinant of [∂T/∂s ∂T/∂t] is the Jacobian per steradian. e1, e2 are the azimuthal and polar
// directions, which are (near) the principal directions of these maps: in a generic frame the two
// columns are almost parallel where T squeezes radially (tangential/radial stretch up to ~1e4) and
// the determinant cancels. The O(h²) error of central differences is removed by one Richardson
// step (J(h/2)·4 − J(h))/3; h = 1e-2 × the local scale: truncation ~(1e-2)⁴, rounding
// ~ε/1e-2, each times the squeeze ratio (the scale is set by the smaller α, so along the other
// axis of a 1:1000 lobe the step is short and rounding dominates: ~2e-7 there, ~1e-9 elsewhere).
inline double fd_jacobian_at(const MapFns& m, V3 w, V3 e1, V3 e2, double h) {
  auto at = [&](double s, double t) { return m.to(normalize(w + s * e1 + t * e2)); };
  const V2 ds = (1 / (2 * h)) * (at(h, 0) - at(-h, 0));
  const V2 dt = (1 / (2 * h)) * (at(0, h) - at(0, -h));
  return std::abs(ds.x * dt.y - ds.y * dt.x);
}

inline double fd_jacobian(const MapFns& m, V3 w) {
  const double st = std::hypot(w.x, w.y);
  const V3 e1 = st > 1e-9 ? V3{-w.y / st, w.x / st, 0} : V3{0, 1, 0};
  const V3 e2 = normalize(cross(e1, w));
  const double h = 1e-2 * m.step_scale(w);
  return (4 * fd_jacobian_at(m, w, e1, e2, h / 2) - fd_jacobian_at(m, w, e1, e2, h)) / 3;
}

// max |log(J_fd/J)| over directions (symmetric in over- and underestimates).
inline double jacobian_fd_rel_error(const MapFns& m, const std::vector<V3>& dirs) {
  double e = 0;
  for (V3 w : dirs) e = std::max(e, std::abs(std::log(fd_jacobian(m, w) / m.jacobian(w))));
  return e;
}

// max over directions of |T(ω) − (½, ½)| − ½: ≤ 0 when T stays in the inscribed disk.
inline double outside_disk_excess(const MapFns& m, const std::vector<V3>& dirs) {
  double e = -1;
  for (V3 w : dirs) e = std::max(e, dist(m.to(w), V2{0.5, 0.5}) - 0.5);
  return e;
}

// Directions on the whole upper hemisphere, horizon included, for containment.
inline std::vector<V3> hemisphere_directions() {
  std::vector<V3> d;
  for (int i = 0; i <= 40; ++i)
    for (int j = 0; j < 24; ++j)
      d.push_back(direction(i * std::numbers::pi / 80, j * 2 * std::numbers::pi / 24 + 0.1));
  return d;
}

// float: finite, inside the disk and on the hemisphere at ω = +z, exactly at the horizon and at
// grazing angles, for α 1e-4..4 and anisotropy to 1:1000; p → ω → p to a few float ulps of ½.
// `Ndf` is GGX<float> or Beckmann<float>; the GGX Jacobian is strictly positive everywhere, the
// Beckmann one may underflow to 0 at grazing angles.
template <class Ndf>
void check_float_stable(bool jacobian_true_positive) {
  std::vector<Vec3<float>> dirs = {{0, 0, 1}, {1, 0, 0}, {0, 1, 0}, {-0.6f, 0.8f, 0}};
  for (V3 w : directions()) dirs.push_back(cast<float>(w));
  for (double deg : {89.99, 89.999, 89.9999})
    for (double phi : {0.0, 0.7, 1.5707963})
      dirs.push_back(cast<float>(direction(deg * std::numbers::pi / 180, phi)));
  for (const Alpha& a : kAlphas) {
    const Ndf g{float(a.x), float(a.y)};
    for (Vec3<float> w : dirs) {
      const Vec2<float> p = map_to_square(g, w);
      ASSERT_TRUE(std::isfinite(p.x) && std::isfinite(p.y));
      EXPECT_LE(std::hypot(p.x - 0.5f, p.y - 0.5f), 0.5f + 1e-6f);
      const float jt = map_jacobian_true(g, w), jp = map_jacobian_paper(g, w);
      EXPECT_TRUE(std::isfinite(jt) && (jacobian_true_positive ? jt > 0 : jt >= 0));
      EXPECT_TRUE(std::isfinite(jp) && jp >= 0);
    }
    float worst = 0;
    for (V2 pd : disk_points()) {
      const Vec2<float> p{float(pd.x), float(pd.y)};
      const Vec3<float> w = map_from_square(g, p);
      ASSERT_TRUE(std::isfinite(w.x) && std::isfinite(w.y) && std::isfinite(w.z));
      EXPECT_GE(w.z, 0.0f);
      EXPECT_NEAR(length(w), 1.0f, 3e-7f);
      const Vec2<float> q = map_to_square(g, w);
      worst = std::max(worst, std::hypot(q.x - p.x, q.y - p.y));
    }
    EXPECT_LT(worst, 4e-7f) << a.x << " " << a.y;  // ≈ 7 ulp of ½
  }
}

}  // namespace glintlab::maptest
