// Point light with a radius: a uniformly emitting ball of radius r, seen from a shading point at
// distance d as the spherical cap of half-angle γ, sin γ = r/d (Kneiphof & Klein 2024 Sec. 5:
// "little balls", |Ω_i| = 2π(1 − cos γ) in Eq. 20). Sampled uniformly over the cap (the cone of
// directions the ball subtends; e.g. PBRT 4th ed. Sec. 12.2.2, "Sphere sampling").
#pragma once

#include "core/lights/light_sample.h"
#include "core/lights/spherical_cap.h"
#include "core/parameter_check.h"

namespace glintlab {

template <class T>
struct PointLight {
  Vec3<T> center;
  T radius;         // > 0
  Vec3<T> emitted;  // RGB radiance of the ball's surface, the same in every direction

  // The cap seen from p, and whether p is outside the ball (inside, the support is empty).
  // 1 − cos γ = s²/(1 + √(1 − s²)), s² = r²/d²: no cancellation for a far, small ball.
  GLINTLAB_FN SphericalCap<T> cap(Vec3<T> p, Mask<T>* outside) const {
    const Vec3<T> v = center - p;
    const T d2 = dot(v, v);
    *outside = d2 > radius * radius;
    const T s2 = min(radius * radius / select(d2 > T(0), d2, T(1)), T(1));
    const T omc = s2 / (T(1) + safe_sqrt(T(1) - s2));
    return {rsqrt(select(d2 > T(0), d2, T(1))) * v, omc};
  }

  GLINTLAB_FN T solid_angle(Vec3<T> p) const {
    Mask<T> outside;
    const SphericalCap<T> c = cap(p, &outside);
    return select(outside, cap_solid_angle(c), T(0));
  }

  GLINTLAB_FN T pdf(Vec3<T> p, Vec3<T> wi) const {
    Mask<T> outside;
    const SphericalCap<T> c = cap(p, &outside);
    return select(outside, cap_pdf(c, wi), T(0));
  }

  GLINTLAB_FN Vec3<T> radiance(Vec3<T> p, Vec3<T> wi) const {
    Mask<T> outside;
    const SphericalCap<T> c = cap(p, &outside);
    const Vec3<T> zero{T(0), T(0), T(0)};
    return select(outside && cap_contains(c, wi), emitted, zero);
  }

  // Uniform in the cap; the distance is the first intersection with the ball,
  // t = d cos θ − √(r² − d² sin²θ) (clamped where rounding puts the ray at the silhouette).
  GLINTLAB_FN LightSample<T> sample(Vec3<T> p, Vec2<T> u) const {
    Mask<T> outside;
    const SphericalCap<T> c = cap(p, &outside);
    const Vec3<T> wi = sample_cap(c, u);
    const Vec3<T> v = center - p;
    const T tc = dot(v, wi);
    const Vec3<T> perp = v - tc * wi;
    const T t = tc - safe_sqrt(radius * radius - dot(perp, perp));
    return {wi, t, emitted, select(outside, T(1) / cap_solid_angle(c), T(0)), outside};
  }
};

// A validated point light (host side). radius > 0; radiance >= 0. A point light of intensity I
// (W/sr) corresponds to emitted radiance I / (π r²): the ball then has intensity I from afar.
template <class T = double>
PointLight<T> make_point_light(Vec3<double> center, double radius, Vec3<double> radiance) {
  const char* what = "point light";
  detail::require_finite(what, "center", center);
  detail::require(std::isfinite(radius) && radius > 0, what, "radius", radius,
                  "a finite radius > 0");
  detail::require_radiance(what, radiance);
  return {cast<T>(center), T(radius), cast<T>(radiance)};
}

}  // namespace glintlab
