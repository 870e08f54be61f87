// One-sided convex polygon area light (3 to kMaxPolygonVertices vertices) with uniform radiance.
// Solid angle: the exact spherical-polygon solid angle, summed over the fan of spherical triangles
// (v0, vk, vk+1), each by Van Oosterom & Strackee 1983 Eq. 8. Samplers: uniform area (fan triangle
// by area, then uniform in it: Turk 1990, Graphics Gems I, "Generating random points in
// triangles"), converted by p_ω = d²/(A cos θ_l) (Veach 1997 Eq. 8.10); or uniform solid angle
// (fan triangle by solid angle, then Arvo 1995), pdf = 1/Ω.
#pragma once

#include <cmath>
#include <span>

#include "core/lights/light_sample.h"
#include "core/lights/planar_emitter.h"
#include "core/lights/spherical_triangle.h"

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

}  // namespace glintlab
