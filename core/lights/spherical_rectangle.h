// Solid-angle sampling of a planar rectangle: Ureña, Fajardo & King 2013, "An Area-Preserving
// Parametrization for Spherical Rectangles" (EGSR), Sec. 3 (setup, solid angle S, Eq. 4–5) and
// Sec. 4 (the inverse of the parametrization, Eq. 8–12). The map is area preserving: uniform u
// gives directions uniformly distributed over the rectangle's spherical projection, pdf = 1/S.
#pragma once

#include "core/math/vec.h"
#include "core/samplers/sample.h"

namespace glintlab {

// The rectangle seen from p in its local frame (x, y along the edges, z towards p's far side so
// that z0 < 0): everything the sampler and the solid angle need (Ureña et al. Sec. 3).
template <class T>
struct SphericalRectangle {
  Vec3<T> p, x, y, z;  // origin and local frame
  T x0, y0, z0, x1, y1;
  T b0, b1, k;    // Ureña et al. Sec. 4 constants
  T solid_angle;  // S = γ0 + γ1 + γ2 + γ3 − 2π (Sec. 3)
};

// corner s, edge vectors ex, ey (orthogonal), point p.
template <class T>
GLINTLAB_FN SphericalRectangle<T> spherical_rectangle(Vec3<T> s, Vec3<T> ex, Vec3<T> ey,
                                                      Vec3<T> p) {
  SphericalRectangle<T> r;
  const T exl = length(ex), eyl = length(ey);
  r.p = p;
  r.x = (T(1) / exl) * ex;
  r.y = (T(1) / eyl) * ey;
  const Vec3<T> zz = cross(r.x, r.y);
  const Vec3<T> d = s - p;
  const T z0 = dot(d, zz);
  // Flip z so that the rectangle lies at z0 < 0 (Sec. 3).
  const Mask<T> flip = z0 > T(0);
  r.z = select(flip, -zz, zz);
  r.z0 = select(flip, -z0, z0);
  r.x0 = dot(d, r.x);
  r.y0 = dot(d, r.y);
  r.x1 = r.x0 + exl;
  r.y1 = r.y0 + eyl;
  const Vec3<T> v00{r.x0, r.y0, r.z0}, v01{r.x0, r.y1, r.z0}, v10{r.x1, r.y0, r.z0},
      v11{r.x1, r.y1, r.z0};
  // Normals of the four planes through p and an edge, pointing inwards (Sec. 3).
  const Vec3<T> n0 = normalize(cross(v00, v10));
  const Vec3<T> n1 = normalize(cross(v10, v11));
  const Vec3<T> n2 = normalize(cross(v11, v01));
  const Vec3<T> n3 = normalize(cross(v01, v00));
  const T g0 = safe_acos(-dot(n0, n1));
  const T g1 = safe_acos(-dot(n1, n2));
  const T g2 = safe_acos(-dot(n2, n3));
  const T g3 = safe_acos(-dot(n3, n0));
  r.b0 = n0.z;
  r.b1 = n2.z;
  r.k = T(2 * kPi<T>) - g2 - g3;
  r.solid_angle = max(g0 + g1 - r.k, T(0));
  return r;
}

// The direction for u in [0, 1)² (Ureña et al. Sec. 4: u → x_u by Eq. 8–10, v → y_v by Eq. 11–12).
template <class T>
GLINTLAB_FN Vec3<T> sample_spherical_rectangle(const SphericalRectangle<T>& r, Vec2<T> u) {
  const T au = u.x * r.solid_angle + r.k;
  T sau, cau;
  sincos(au, &sau, &cau);
  const T fu = (cau * r.b0 - r.b1) / select(sau != T(0), sau, T(1));
  const T cu = clamp(sign_not_zero(fu) * rsqrt(fu * fu + r.b0 * r.b0), T(-1), T(1));
  const T xu = clamp(-(cu * r.z0) * rsqrt(max(T(1) - cu * cu, T(1e-30))), r.x0, r.x1);
  const T d = sqrt(xu * xu + r.z0 * r.z0);
  const T h0 = r.y0 / sqrt(d * d + r.y0 * r.y0);
  const T h1 = r.y1 / sqrt(d * d + r.y1 * r.y1);
  const T hv = h0 + u.y * (h1 - h0);
  const T hv2 = hv * hv;
  const Mask<T> inner = hv2 < T(1) - T(1e-12);
  const T yv = select(inner, hv * d * rsqrt(select(inner, T(1) - hv2, T(1))), r.y1);
  return normalize(xu * r.x + yv * r.y + r.z0 * r.z);
}

}  // namespace glintlab
