// One-sided convex polygon area light (3 to kMaxPolygonVertices vertices) with uniform radiance.
// Solid angle: the exact spherical-polygon solid angle, summed over the fan of spherical triangles
// (v0, vk, vk+1), each by Van Oosterom & Strackee 1983 Eq. 8. Samplers: uniform area (fan triangle
// by area, then uniform in it: Turk 1990, Graphics Gems I, "Generating random points in
// triangles"), converted by p_ω = d²/(A cos θ_l) (Veach 1997 Eq. 8.10); or uniform solid angle
// (fan triangle by solid angle, then Arvo 1995), pdf = 1/Ω.
#pragma once

#include <fmt/format.h>

#include <cmath>
#include <span>

#include "core/lights/light_sample.h"
#include "core/lights/planar_emitter.h"
#include "core/lights/spherical_triangle.h"
#include "core/parameter_check.h"

namespace glintlab {

template <class T>
struct PolygonLight {
  Vec3<T> vertex[kMaxPolygonVertices];  // convex, planar, counter-clockwise about `normal`
  int count;
  Vec3<T> normal;  // unit; the emitting side
  T area;
  T fan_cdf[kMaxPolygonVertices];  // fan_cdf[j]: area fraction of fan triangles 0..j; last = 1
  Vec3<T> emitted;
  AreaSampling sampling;

  GLINTLAB_FN Mask<T> in_front(Vec3<T> p) const { return dot(p - vertex[0], normal) > T(0); }

  // Fan triangle j = (v0, v_{j+1}, v_{j+2}) holding u in [cdf_{j−1}, cdf_j); u is rescaled to
  // [0, 1) inside it. Loops run over the light's vertex count, which is the same for every lane.
  GLINTLAB_FN void pick_triangle(const T* cdf, T* u, Vec3<T>* b, Vec3<T>* c) const {
    T lo = T(0), chosen_lo = T(0), chosen_hi = T(1);
    Mask<T> found = Mask<T>(false);
    *b = vertex[1];
    *c = vertex[2];
    for (int j = 0; j < count - 2; ++j) {
      const T hi = select(j == count - 3, T(1), cdf[j]);
      const Mask<T> here = (!found) && (*u < hi);
      *b = select(here, vertex[j + 1], *b);
      *c = select(here, vertex[j + 2], *c);
      chosen_lo = select(here, lo, chosen_lo);
      chosen_hi = select(here, hi, chosen_hi);
      found = found || here;
      lo = hi;
    }
    const T w = chosen_hi - chosen_lo;
    *u = min((*u - chosen_lo) / select(w > T(0), w, T(1)), T(1) - T(1e-7));
  }

  // Unit directions from p to the vertices.
  GLINTLAB_FN PolygonVertices<T> vertices_from(Vec3<T> p) const {
    PolygonVertices<T> v;
    v.count = count;
    for (int k = 0; k < kMaxPolygonVertices; ++k)
      v.v[k] = k < count ? normalize(vertex[k] - p) : Vec3<T>{T(0), T(0), T(0)};
    return v;
  }

  // Solid angle of each fan triangle seen from p, their cumulative fractions, and the total.
  GLINTLAB_FN T fan_solid_angles(Vec3<T> p, T* cdf) const {
    const PolygonVertices<T> w = vertices_from(p);
    T total = T(0);
    for (int j = 0; j < count - 2; ++j) {
      total = total + spherical_triangle_solid_angle(w.v[0], w.v[j + 1], w.v[j + 2]);
      cdf[j] = total;
    }
    for (int j = 0; j < count - 2; ++j) cdf[j] = cdf[j] / select(total > T(0), total, T(1));
    return total;
  }

  GLINTLAB_FN T solid_angle(Vec3<T> p) const {
    T cdf[kMaxPolygonVertices];
    return select(in_front(p), fan_solid_angles(p, cdf), T(0));
  }

  // Inside a convex polygon: on the left of every edge (about the normal).
  GLINTLAB_FN Mask<T> hits(Vec3<T> p, Vec3<T> wi, detail::PlaneHit<T>* h) const {
    *h = detail::hit_plane(vertex[0], normal, p, wi);
    Mask<T> inside = h->front;
    for (int k = 0; k < count; ++k) {
      const Vec3<T> a = vertex[k], b = vertex[k + 1 < count ? k + 1 : 0];
      inside = inside && (dot(cross(b - a, h->hit - a), normal) >= T(0));
    }
    return inside;
  }

  GLINTLAB_FN T pdf(Vec3<T> p, Vec3<T> wi) const {
    detail::PlaneHit<T> h;
    const Mask<T> ok = hits(p, wi, &h);
    if (sampling == AreaSampling::kSolidAngle) {  // a per-light constant, not a per-lane value
      const T s = solid_angle(p);
      return select(ok && (s > T(0)), T(1) / select(s > T(0), s, T(1)), T(0));
    }
    return select(ok, h.t * h.t / (area * select(ok, h.cos_light, T(1))), T(0));
  }

  GLINTLAB_FN Vec3<T> radiance(Vec3<T> p, Vec3<T> wi) const {
    detail::PlaneHit<T> h;
    return select(hits(p, wi, &h), emitted, Vec3<T>{T(0), T(0), T(0)});
  }

  GLINTLAB_FN LightSample<T> sample(Vec3<T> p, Vec2<T> u) const {
    const Mask<T> front = in_front(p);
    T ux = u.x;
    Vec3<T> b, c;
    if (sampling == AreaSampling::kSolidAngle) {
      T cdf[kMaxPolygonVertices];
      const T total = fan_solid_angles(p, cdf);
      pick_triangle(cdf, &ux, &b, &c);
      const Vec3<T> wi = sample_spherical_triangle(normalize(vertex[0] - p), normalize(b - p),
                                                   normalize(c - p), Vec2<T>{ux, u.y});
      const detail::PlaneHit<T> h = detail::hit_plane(vertex[0], normal, p, wi);
      const Mask<T> ok = front && h.front && (total > T(0));
      return {wi, h.t, emitted, select(ok, T(1) / select(ok, total, T(1)), T(0)), ok};
    }
    pick_triangle(fan_cdf, &ux, &b, &c);
    // Uniform in the triangle: barycentrics (1 − √u1, u2 √u1) (Turk 1990).
    const T su = sqrt(ux);
    const T b0 = T(1) - su, b1 = u.y * su;
    const Vec3<T> q = b0 * vertex[0] + b1 * b + (T(1) - b0 - b1) * c;
    LightSample<T> s = detail::area_sample_to_solid_angle(normal, p, q, area, emitted);
    s.valid = s.valid && front;
    s.pdf = select(s.valid, s.pdf, T(0));
    return s;
  }
};

// A validated convex polygon light (host side). The vertices, 3 to kMaxPolygonVertices, must be
// finite, planar (off their plane by at most 1e-9 of the polygon's diameter), non-degenerate (no
// coincident vertices, no three consecutive collinear ones, area > 0) and convex (every turn the
// same way, once around). Either winding is accepted: the light emits towards the side from which
// its vertices appear counter-clockwise (the right-hand normal).
template <class T = double>
PolygonLight<T> make_polygon_light(std::span<const Vec3<double>> vertices, Vec3<double> radiance,
                                   AreaSampling sampling = AreaSampling::kSolidAngle) {
  const char* what = "polygon light";
  const int n = static_cast<int>(vertices.size());
  detail::require(n >= 3 && n <= kMaxPolygonVertices, what, "the vertex count", n,
                  "3 to 8 vertices");
  double diameter = 0;
  for (int k = 0; k < n; ++k) {
    detail::require_finite(what, fmt::format("vertex {}", k), vertices[k]);
    for (int j = 0; j < n; ++j) diameter = std::max(diameter, length(vertices[k] - vertices[j]));
  }
  detail::require(diameter > 0, what, "the polygon's diameter", diameter,
                  "> 0: the vertices must not all coincide");
  const auto vk = [&](int k) { return vertices[((k % n) + n) % n]; };
  for (int k = 0; k < n; ++k)
    if (!(length(vk(k + 1) - vk(k)) > 1e-12 * diameter))
      throw ParameterError(
          fmt::format("{}: vertices {} and {} coincide (valid: distinct consecutive vertices)",
                      what, k, (k + 1) % n));
  // Newell's normal: twice the vector area, exact for a planar polygon.
  Vec3<double> newell{0, 0, 0};
  for (int k = 0; k < n; ++k) newell = newell + cross(vk(k), vk(k + 1));
  const double area = 0.5 * length(newell);
  detail::require(area > 1e-12 * diameter * diameter, what, "the polygon's area", area,
                  "> 1e-12 diameter^2: the vertices must not be collinear");
  const Vec3<double> normal = (1 / length(newell)) * newell;
  for (int k = 0; k < n; ++k) {
    const double off = dot(vk(k) - vk(0), normal);
    if (!(std::abs(off) <= 1e-9 * diameter))
      throw ParameterError(fmt::format(
          "{}: vertex {} is off the polygon's plane by {} (valid: planar within 1e-9 of the "
          "diameter {})",
          what, k, off, diameter));
  }
  double turning = 0;
  for (int k = 0; k < n; ++k) {
    const Vec3<double> e0 = vk(k) - vk(k - 1), e1 = vk(k + 1) - vk(k);
    const double s = dot(cross(e0, e1), normal), c = dot(e0, e1);
    if (!(s > 1e-12 * length(e0) * length(e1)))
      throw ParameterError(fmt::format(
          "{}: the polygon is {} at vertex {} (valid: a strictly convex polygon, every turn the "
          "same way)",
          what,
          std::abs(s) <= 1e-12 * length(e0) * length(e1) ? "degenerate (collinear edges)"
                                                         : "not convex",
          k));
    turning += std::atan2(s, c);
  }
  detail::require(std::abs(turning - 2 * 3.14159265358979323846) < 1e-6, what,
                  "the total turning angle", turning,
                  "2 pi: a convex polygon winds once (a star polygon winds more)");
  detail::require_radiance(what, radiance);
  PolygonLight<T> light{};
  light.count = n;
  for (int k = 0; k < n; ++k) light.vertex[k] = cast<T>(vertices[k]);
  light.normal = cast<T>(normal);
  light.area = T(area);
  double acc = 0;
  for (int j = 0; j < n - 2; ++j) {
    acc += 0.5 * length(cross(vertices[j + 1] - vertices[0], vertices[j + 2] - vertices[0]));
    light.fan_cdf[j] = T(j == n - 3 ? 1.0 : acc / area);
  }
  light.emitted = cast<T>(radiance);
  light.sampling = sampling;
  return light;
}

}  // namespace glintlab
