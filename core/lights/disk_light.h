// One-sided disk area light with uniform radiance: uniform-area sampling converted to solid angle
// (p_ω = d² / (A cos θ_l), Veach 1997 Eq. 8.10) and the exact subtended solid angle as a boundary
// integral evaluated by the trapezoidal rule (see solid_angle). Podee's only light is this disk.
#pragma once

#include "core/lights/light_sample.h"
#include "core/lights/planar_emitter.h"
#include "core/math/orthonormal_basis.h"
#include "core/parameter_check.h"

namespace glintlab {

// Trapezoidal nodes of the disk's boundary integral. The integrand is smooth and periodic, so the
// rule converges geometrically; its rate falls with the height of the point over the plane
// relative to the radius (measured in tests/core/lights/planar_lights_test.cpp).
inline constexpr int kDiskSolidAngleNodes = 256;

template <class T>
struct DiskLight {
  Vec3<T> center;
  OrthonormalBasis<T> frame;  // frame.z: the unit normal, the side it emits to
  T radius;
  Vec3<T> emitted;  // RGB radiance

  GLINTLAB_FN T area() const { return T(kPi<T>) * radius * radius; }

  GLINTLAB_FN LightSample<T> sample(Vec3<T> p, Vec2<T> u) const {
    // Uniform in area by the polar map r = R √u1, φ = 2π u2 (its Jacobian is constant).
    T sp, cp;
    sincos(T(2 * kPi<T>) * u.y, &sp, &cp);
    const T r = radius * sqrt(u.x);
    const Vec3<T> q = center + (r * cp) * frame.x + (r * sp) * frame.y;
    LightSample<T> s = detail::area_sample_to_solid_angle(frame.z, p, q, area(), emitted);
    const Mask<T> front = dot(p - center, frame.z) > T(0);
    s.valid = s.valid && front;
    s.pdf = select(s.valid, s.pdf, T(0));
    return s;
  }

  GLINTLAB_FN Mask<T> hits(Vec3<T> p, Vec3<T> wi, detail::PlaneHit<T>* h) const {
    *h = detail::hit_plane(center, frame.z, p, wi);
    const Vec3<T> d = h->hit - center;
    return h->front && (dot(d, d) <= radius * radius);
  }

  GLINTLAB_FN T pdf(Vec3<T> p, Vec3<T> wi) const {
    detail::PlaneHit<T> h;
    const Mask<T> ok = hits(p, wi, &h);
    return select(ok, h.t * h.t / (area() * select(ok, h.cos_light, T(1))), T(0));
  }

  GLINTLAB_FN Vec3<T> radiance(Vec3<T> p, Vec3<T> wi) const {
    detail::PlaneHit<T> h;
    return select(hits(p, wi, &h), emitted, Vec3<T>{T(0), T(0), T(0)});
  }

  // Ω = ∫_disk h/|q − p|³ dA. In polar coordinates (ρ, φ) about the foot f of p on the plane, the
  // radial integral is 1 − h/√(h² + ρ²), so Ω = ∮ (1 − h/s) dφ along the boundary (s = √(h²+ρ²)),
  // which holds whether f lies inside the disk or not (the signed dφ cancels the part outside).
  // With the boundary q(ψ) = c + R(cos ψ, sin ψ) and r = q − f, dφ = (r × r')/ρ² dψ and
  // 1 − h/s = ρ²/((s + h) s): the integrand (r × r')/((s + h) s) has no singularity even where f
  // is on the rim. It is periodic and analytic in ψ, so the trapezoidal rule converges
  // geometrically (Trefethen & Weideman 2014, SIAM Review 56(3), Thm. 3.2).
  GLINTLAB_FN T solid_angle(Vec3<T> p) const {
    const Vec3<T> d = p - center;
    const T h = dot(d, frame.z);
    const T ex = -dot(d, frame.x), ey = -dot(d, frame.y);  // centre relative to the foot
    T sum = T(0);
    for (int k = 0; k < kDiskSolidAngleNodes; ++k) {
      T sp, cp;
      sincos(T(2 * kPi<T>) * T(k) / T(kDiskSolidAngleNodes), &sp, &cp);
      const T rx = ex + radius * cp, ry = ey + radius * sp;
      const T cr = radius * (rx * cp + ry * sp);  // r × r' with r' = R(−sin ψ, cos ψ)
      const T s = sqrt(h * h + rx * rx + ry * ry);
      sum = sum + cr / ((s + abs(h)) * s);
    }
    return select(h > T(0), sum * T(2 * kPi<T>) / T(kDiskSolidAngleNodes), T(0));
  }
};

// A validated disk light (host side): radius > 0, a non-zero normal (it emits towards it),
// radiance >= 0.
template <class T = double>
DiskLight<T> make_disk_light(Vec3<double> center, Vec3<double> normal, double radius,
                             Vec3<double> radiance) {
  const char* what = "disk light";
  detail::require_finite(what, "center", center);
  const Vec3<double> n = detail::require_direction(what, "normal", normal);
  detail::require(std::isfinite(radius) && radius > 0, what, "radius", radius,
                  "a finite radius > 0");
  detail::require_radiance(what, radiance);
  const OrthonormalBasis<double> b = basis_from_z(n);
  return {
      cast<T>(center), {cast<T>(b.x), cast<T>(b.y), cast<T>(b.z)}, T(radius), cast<T>(radiance)};
}

}  // namespace glintlab
