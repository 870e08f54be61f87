// One-sided disk area light with uniform radiance: uniform-area sampling converted to solid angle
// (p_ω = d² / (A cos θ_l), Veach 1997 Eq. 8.10) and the exact subtended solid angle in closed form
// by complete and incomplete elliptic integrals (Paxton 1959). Podee's only light is this disk.
#pragma once

#include "core/lights/light_sample.h"
#include "core/lights/planar_emitter.h"
#include "core/math/elliptic_integrals.h"
#include "core/math/orthonormal_basis.h"
#include "core/parameter_check.h"

namespace glintlab {

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

  // Ω in closed form (Paxton 1959, "Solid angle calculation for a circular disk", Rev. Sci.
  // Instrum. 30(4), Eq. 27–29; with Heuman's Lambda function as in DLMF 19.2.iv / Byrd & Friedman
  // 150.03): with h the height of p over the plane, e the distance of its foot from the centre,
  // R_max = √(h² + (e + R)²), R_1 = √(h² + (e − R)²), k² = 4eR/R_max², k' = R_1/R_max and
  // ξ = atan(h / |e − R|),
  //   Ω = π − 2 (h/R_max) K(k) + sgn(R − e) π (1 − Λ0(ξ, k)),
  //   Λ0(ξ, k) = (2/π) [E(k) F(ξ, k') + K(k) E(ξ, k') − K(k) F(ξ, k')],
  // which joins Paxton's three cases (e < R, e = R, e > R: Λ0(π/2, k) = 1 by Legendre's relation).
  // K, E, F through Carlson's R_F, R_D with k'² passed directly, so a point just above the rim
  // (k → 1) keeps its digits. An earlier trapezoidal boundary integral failed there (measured:
  // Ω = 10.4 > 2π at h = 1e-3 R, e = 0.999 R).
  GLINTLAB_FN T solid_angle(Vec3<T> p) const {
    const Vec3<T> d = p - center;
    const T h = dot(d, frame.z);
    const T ex = dot(d, frame.x), ey = dot(d, frame.y);
    const T e = sqrt(ex * ex + ey * ey);
    const T rmax2 = h * h + sqr(e + radius);
    const T r12 = h * h + sqr(e - radius);
    const T m = T(4) * e * radius / rmax2;  // k²
    const T mc = r12 / rmax2;               // k'² = 1 − k², without the cancellation
    const T kk = carlson_rf(T(0), mc, T(1));
    const T ek = kk - m / T(3) * carlson_rd(T(0), mc, T(1));
    const T xi = atan2(abs(h), abs(e - radius));
    T sx, cx;
    sincos(xi, &sx, &cx);
    const T dd = T(1) - mc * sx * sx;  // 1 − k'² sin²ξ
    const T rf = carlson_rf(cx * cx, dd, T(1));
    const T f_xi = sx * rf;
    const T e_xi = f_xi - mc * sx * sx * sx / T(3) * carlson_rd(cx * cx, dd, T(1));
    const T lambda0 = T(2 * kInvPi<T>) * (ek * f_xi + kk * e_xi - kk * f_xi);
    const T om = T(kPi<T>) - T(2) * abs(h) * rsqrt(rmax2) * kk +
                 sign_not_zero(radius - e) * T(kPi<T>) * (T(1) - lambda0);
    return select(h > T(0), max(om, T(0)), T(0));
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
