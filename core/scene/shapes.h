// Analytic shapes of the papers' scenes — plane, sphere, cylinder (tube) — with ray intersection,
// uv parameterization and the surface derivatives ∂p/∂u, ∂p/∂v (Pharr, Jakob & Humphreys,
// "Physically Based Rendering", 3rd ed., Sec. 3.2–3.4 for the sphere and cylinder uv).
#pragma once

#include "core/math/vec.h"
#include "core/scene/frame.h"

namespace glintlab {

template <class T>
struct Ray {
  Vec3<T> o, d;  // d need not be unit; hit distances are in units of |d|
};

// A ray–surface intersection. hit = the ray meets the surface at t > 0; the other fields are
// finite (but meaningless) where it does not.
template <class T>
struct SurfaceHit {
  Mask<T> hit;
  T t;
  Vec3<T> p;
  Vec3<T> n;  // unit geometric (= shading) normal, facing outward
  Vec2<T> uv;
  Vec3<T> dpdu, dpdv;  // ∂p/∂u, ∂p/∂v
  // Shading frame: tangent along ∂p/∂u (or any tangent where ∂p/∂u = 0), normal n.
  GLINTLAB_FN Frame<T> frame() const { return frame_from_normal_tangent(n, dpdu); }
};

// A plane through `origin` with the orthonormal `frame` (n = normal); uv = local (x, y) / scale,
// so u runs along frame.t. half_extent > 0 bounds it to |x|, |y| <= half_extent (world units);
// 0 = unbounded.
template <class T>
struct Plane {
  Vec3<T> origin;
  Frame<T> frame;
  T scale;
  T half_extent;

  GLINTLAB_FN SurfaceHit<T> intersect(const Ray<T>& r) const {
    const T dn = dot(r.d, frame.n);
    const Mask<T> facing = abs(dn) > T(0);
    const T t = dot(origin - r.o, frame.n) / select(facing, dn, T(1));
    const Vec3<T> p = r.o + t * r.d;
    const Vec3<T> l = frame.to_local(p - origin);
    const Mask<T> inside =
        (half_extent <= T(0)) || (abs(l.x) <= half_extent && abs(l.y) <= half_extent);
    return {facing && t > T(0) && inside,
            t,
            p,
            frame.n,
            Vec2<T>{l.x / scale, l.y / scale},
            scale * frame.t,
            scale * frame.b};
  }
};

// A sphere; u = φ/(2π) with φ = atan2(y, x) in [0, 2π) about the z axis, v = θ/π from +z (PBRT
// Sec. 3.2 with v measured from the north pole).
template <class T>
struct Sphere {
  Vec3<T> center;
  T radius;

  GLINTLAB_FN SurfaceHit<T> intersect(const Ray<T>& r) const {
    // Quadratic |o + t d − c|² = R², written with the numerically safer discriminant of PBRT-v4
    // Sec. 6.8.4 (the distance of the centre to the ray line).
    const Vec3<T> oc = r.o - center;
    const T a = dot(r.d, r.d);
    const T b = dot(oc, r.d);
    const Vec3<T> perp = oc - (b / a) * r.d;
    const T disc = a * (radius * radius - dot(perp, perp));
    const Mask<T> real = disc >= T(0);
    const T sq = sqrt(select(real, disc, T(0)));
    const T q = -b - copysign(sq, b);
    const T t0 = q / a;
    const T t1 = select(q != T(0), (dot(oc, oc) - radius * radius) / q, t0);
    const T tn = min(t0, t1), tf = max(t0, t1);
    const T t = select(tn > T(0), tn, tf);
    const Vec3<T> p = r.o + t * r.d;
    return surface_at(p, real && t > T(0), t);
  }

  // The hit record at a point of the sphere.
  GLINTLAB_FN SurfaceHit<T> surface_at(Vec3<T> p, Mask<T> hit, T t) const {
    const Vec3<T> l = p - center;
    const Vec3<T> n = (T(1) / radius) * l;
    T phi = atan2(l.y, l.x);
    phi = select(phi < T(0), phi + T(2 * kPi<T>), phi);
    const T theta = safe_acos(n.z);
    const T rxy = sqrt(l.x * l.x + l.y * l.y);
    const Mask<T> off_axis = rxy > T(0);
    const T cphi = select(off_axis, l.x / select(off_axis, rxy, T(1)), T(1));
    const T sphi = select(off_axis, l.y / select(off_axis, rxy, T(1)), T(0));
    const Vec3<T> dpdu{T(-2 * kPi<T>) * l.y, T(2 * kPi<T>) * l.x, T(0)};
    const Vec3<T> dpdv = T(kPi<T>) * Vec3<T>{l.z * cphi, l.z * sphi, -rxy};
    return {hit, t, p, n, Vec2<T>{phi * T(0.5 * kInvPi<T>), theta * T(kInvPi<T>)}, dpdu, dpdv};
  }
};

// A finite open cylinder (tube) of `radius` around the axis frame.n through `center`, for axial
// coordinates z in [−half_length, half_length]; u = φ/(2π) about the axis (φ from frame.t),
// v = (z + half_length)/(2 half_length) (PBRT Sec. 3.3). Seen from inside, the nearer wall's
// inner side is hit and n still faces outward.
template <class T>
struct Cylinder {
  Vec3<T> center;
  Frame<T> frame;
  T radius;
  T half_length;

  GLINTLAB_FN SurfaceHit<T> intersect(const Ray<T>& r) const {
    const Vec3<T> o = frame.to_local(r.o - center);
    const Vec3<T> d = frame.to_local(r.d);
    const T a = d.x * d.x + d.y * d.y;
    const T b = o.x * d.x + o.y * d.y;
    const T c = o.x * o.x + o.y * o.y - radius * radius;
    const Mask<T> moving = a > T(0);
    const T aa = select(moving, a, T(1));
    const T disc = b * b - aa * c;
    const Mask<T> real = moving && disc >= T(0);
    const T sq = sqrt(select(real, disc, T(0)));
    const T q = -b - copysign(sq, b);
    const T t0 = q / aa;
    const T t1 = select(q != T(0), c / q, t0);
    const T tn = min(t0, t1), tf = max(t0, t1);
    const T zn = o.z + tn * d.z, zf = o.z + tf * d.z;
    const Mask<T> ok_n = tn > T(0) && abs(zn) <= half_length;
    const Mask<T> ok_f = tf > T(0) && abs(zf) <= half_length;
    const T t = select(ok_n, tn, tf);
    const Vec3<T> pl = o + t * d;
    T phi = atan2(pl.y, pl.x);
    phi = select(phi < T(0), phi + T(2 * kPi<T>), phi);
    const Vec3<T> nl{pl.x / radius, pl.y / radius, T(0)};
    const Vec3<T> dpdu_l{T(-2 * kPi<T>) * pl.y, T(2 * kPi<T>) * pl.x, T(0)};
    const Vec3<T> dpdv_l{T(0), T(0), T(2) * half_length};
    const T v = (pl.z + half_length) / (T(2) * half_length);
    return {real && (ok_n || ok_f),
            t,
            r.o + t * r.d,
            frame.to_world(nl),
            Vec2<T>{phi * T(0.5 * kInvPi<T>), v},
            frame.to_world(dpdu_l),
            frame.to_world(dpdv_l)};
  }
};

}  // namespace glintlab
