// What the one-sided planar lights (disk, rectangle, polygon) share: the emitting side, the ray–
// plane hit, and the area-to-solid-angle change of density p_ω = p_A d² / cos θ_l (Veach 1997
// Eq. 8.10; PBRT 4th ed. Eq. 4.9).
#pragma once

#include "core/lights/light_sample.h"

namespace glintlab::detail {

// A ray from p along wi against the plane through `origin` with unit normal n that emits towards
// +n: p must be in front (h = (p − origin)·n > 0) and wi must point at the front face
// (cos θ_l = −wi·n > 0). `t` is the distance to the plane, `hit` the point there.
template <class T>
struct PlaneHit {
  Mask<T> front;  // p in front and wi towards the face
  T t;
  T cos_light;
  Vec3<T> hit;
};

template <class T>
GLINTLAB_FN PlaneHit<T> hit_plane(Vec3<T> origin, Vec3<T> n, Vec3<T> p, Vec3<T> wi) {
  const T h = dot(p - origin, n);
  const T cl = -dot(wi, n);
  const Mask<T> front = (h > T(0)) && (cl > T(0));
  const T t = h / select(front, cl, T(1));
  return {front, t, cl, p + t * wi};
}

// Solid-angle density of a point q on the emitter drawn with area density 1/area:
// d² / (area cos θ_l). Returns the direction, the distance and the density; invalid where p is
// behind the face or the point is seen edge-on.
template <class T>
GLINTLAB_FN LightSample<T> area_sample_to_solid_angle(Vec3<T> n, Vec3<T> p, Vec3<T> q, T area,
                                                      Vec3<T> emitted) {
  const Vec3<T> v = q - p;
  const T d2 = dot(v, v);
  const T d = sqrt(d2);
  const Vec3<T> wi = (T(1) / select(d > T(0), d, T(1))) * v;
  const T cl = -dot(wi, n);
  const Mask<T> ok = (d > T(0)) && (cl > T(0));
  const T pdf = select(ok, d2 / (area * select(ok, cl, T(1))), T(0));
  return {wi, d, emitted, pdf, ok && (pdf > T(0))};
}

}  // namespace glintlab::detail

namespace glintlab {

// How a polygonal light (rectangle, convex polygon) draws its samples; the pdf always matches.
enum class AreaSampling {
  kArea,        // uniform over the light's area, converted to solid angle (Veach 1997 Eq. 8.10)
  kSolidAngle,  // uniform over the spherical projection: pdf = 1/Ω (Ureña 2013 / Arvo 1995)
};

inline constexpr int kMaxPolygonVertices = 8;

// A polygon light's vertices as seen from a shading point: unit directions from p to each vertex,
// in world space, in the light's winding (counter-clockwise about its emitting normal, hence
// counter-clockwise as seen from a point in front). Rotating into the shading frame and clipping
// at the horizon are left to the integrator (LTC, Heitz et al. 2016 Sec. 3.2).
template <class T>
struct PolygonVertices {
  Vec3<T> v[kMaxPolygonVertices];
  int count;
};

}  // namespace glintlab
