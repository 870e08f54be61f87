// One-sided rectangular area light with uniform radiance. Two samplers, chosen per light: uniform
// area (p_ω = d²/(A cos θ_l), Veach 1997 Eq. 8.10) or uniform solid angle by Ureña, Fajardo &
// King 2013 (pdf = 1/S). Solid angle: S of Ureña et al. Sec. 3 (the spherical quadrilateral's
// angle excess, Girard's theorem).
#pragma once

#include "core/lights/light_sample.h"
#include "core/lights/planar_emitter.h"
#include "core/lights/spherical_rectangle.h"
#include "core/parameter_check.h"

namespace glintlab {

template <class T>
struct RectangleLight {
  Vec3<T> corner, edge_u, edge_v;  // orthogonal edges; emits towards edge_u × edge_v
  Vec3<T> normal;                  // unit
  Vec3<T> emitted;                 // RGB radiance
  AreaSampling sampling;

  GLINTLAB_FN T area() const { return length(cross(edge_u, edge_v)); }
  GLINTLAB_FN Mask<T> in_front(Vec3<T> p) const { return dot(p - corner, normal) > T(0); }

  GLINTLAB_FN T solid_angle(Vec3<T> p) const {
    return select(in_front(p), spherical_rectangle(corner, edge_u, edge_v, p).solid_angle, T(0));
  }

  GLINTLAB_FN Mask<T> hits(Vec3<T> p, Vec3<T> wi, detail::PlaneHit<T>* h) const {
    *h = detail::hit_plane(corner, normal, p, wi);
    const Vec3<T> d = h->hit - corner;
    const T a = dot(d, edge_u), b = dot(d, edge_v);
    return h->front && (a >= T(0)) && (a <= dot(edge_u, edge_u)) && (b >= T(0)) &&
           (b <= dot(edge_v, edge_v));
  }

  GLINTLAB_FN T pdf(Vec3<T> p, Vec3<T> wi) const {
    detail::PlaneHit<T> h;
    const Mask<T> ok = hits(p, wi, &h);
    if (sampling == AreaSampling::kSolidAngle) {  // a per-light constant, not a per-lane value
      const T s = spherical_rectangle(corner, edge_u, edge_v, p).solid_angle;
      return select(ok && (s > T(0)), T(1) / select(s > T(0), s, T(1)), T(0));
    }
    return select(ok, h.t * h.t / (area() * select(ok, h.cos_light, T(1))), T(0));
  }

  GLINTLAB_FN Vec3<T> radiance(Vec3<T> p, Vec3<T> wi) const {
    detail::PlaneHit<T> h;
    return select(hits(p, wi, &h), emitted, Vec3<T>{T(0), T(0), T(0)});
  }

  GLINTLAB_FN LightSample<T> sample(Vec3<T> p, Vec2<T> u) const {
    const Mask<T> front = in_front(p);
    if (sampling == AreaSampling::kSolidAngle) {
      const SphericalRectangle<T> r = spherical_rectangle(corner, edge_u, edge_v, p);
      const Vec3<T> wi = sample_spherical_rectangle(r, u);
      const detail::PlaneHit<T> h = detail::hit_plane(corner, normal, p, wi);
      const Mask<T> ok = front && h.front && (r.solid_angle > T(0));
      return {wi, h.t, emitted, select(ok, T(1) / select(ok, r.solid_angle, T(1)), T(0)), ok};
    }
    const Vec3<T> q = corner + u.x * edge_u + u.y * edge_v;
    LightSample<T> s = detail::area_sample_to_solid_angle(normal, p, q, area(), emitted);
    s.valid = s.valid && front;
    s.pdf = select(s.valid, s.pdf, T(0));
    return s;
  }

  // Corners counter-clockwise about the normal, as unit directions from p.
  GLINTLAB_FN PolygonVertices<T> vertices_from(Vec3<T> p) const {
    PolygonVertices<T> v;
    v.count = 4;
    v.v[0] = normalize(corner - p);
    v.v[1] = normalize(corner + edge_u - p);
    v.v[2] = normalize(corner + edge_u + edge_v - p);
    v.v[3] = normalize(corner + edge_v - p);
    return v;
  }
};

// A validated rectangle light (host side): non-zero, orthogonal edges (|û·v̂| ≤ 1e-9),
// radiance >= 0. It emits towards edge_u × edge_v.
template <class T = double>
RectangleLight<T> make_rectangle_light(Vec3<double> corner, Vec3<double> edge_u,
                                       Vec3<double> edge_v, Vec3<double> radiance,
                                       AreaSampling sampling = AreaSampling::kSolidAngle) {
  const char* what = "rectangle light";
  detail::require_finite(what, "corner", corner);
  const Vec3<double> u = detail::require_direction(what, "edge_u", edge_u);
  const Vec3<double> v = detail::require_direction(what, "edge_v", edge_v);
  detail::require(std::abs(dot(u, v)) <= 1e-9, what, "the cosine between edge_u and edge_v",
                  dot(u, v), "|cos| <= 1e-9: the edges of a rectangle are orthogonal");
  detail::require_radiance(what, radiance);
  return {cast<T>(corner),   cast<T>(edge_u), cast<T>(edge_v), cast<T>(normalize(cross(u, v))),
          cast<T>(radiance), sampling};
}

}  // namespace glintlab
