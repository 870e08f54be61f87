// Pixel footprint from ray differentials: hit point, uv, the uv Jacobian ∂uv/∂(pixel), shading
// frame, and the half and reflection vectors at the four pixel corners with their screen-space
// derivatives (the inputs of GGAA, Chermain et al., and of Podee's micro-specular filtering).
// Ray differentials as in Igehy 1999 ("Tracing ray differentials") and PBRT 3rd ed. Sec. 10.1.1:
// the offset rays are intersected with the tangent plane at the hit point.
#pragma once

#include <array>

#include "core/model.h"
#include "core/ndf/microfacet.h"
#include "core/scene/camera.h"

namespace glintlab {

// A point light (position) or a directional light (direction toward the light).
template <class T>
struct LightPoint {
  Vec3<T> position_or_direction;
  bool directional;
};

template <class T>
struct PixelFootprint {
  SurfaceHit<T> surface;        // primary hit through the pixel centre; surface.hit = whether any
  Frame<T> frame;               // shading frame at the hit
  Vec3<T> wi;                   // toward the eye, local frame
  Vec3<T> wl;                   // toward the light, local frame
  FootprintQuery<T> footprint;  // uv and ∂uv/∂x, ∂uv/∂y
  // Corners in the order (x−½, y−½), (x+½, y−½), (x−½, y+½), (x+½, y+½). Each corner ray is
  // intersected with the shape (its tangent plane at the centre hit where it misses); h is the
  // half vector in that corner's own shading frame (where the NDF is evaluated), r the mirror
  // reflection of the view direction in world space.
  std::array<Vec3<T>, 4> corner_h;
  std::array<Vec3<T>, 4> corner_r;
  Vec3<T> dh_dx, dh_dy;  // ∂h/∂x, ∂h/∂y: corner differences averaged over the two pixel edges
  Vec3<T> dr_dx, dr_dy;  // ∂r/∂x, ∂r/∂y
};

namespace detail {

// The point where ray r meets the plane through p with normal n (the ray's origin where parallel).
template <class T>
GLINTLAB_FN Vec3<T> on_tangent_plane(const Ray<T>& r, Vec3<T> p, Vec3<T> n) {
  const T dn = dot(r.d, n);
  const Mask<T> ok = abs(dn) > T(0);
  const T t = select(ok, dot(p - r.o, n) / select(ok, dn, T(1)), T(0));
  return r.o + t * r.d;
}

template <class T>
GLINTLAB_FN Vec3<T> toward_light(const LightPoint<T>& light, Vec3<T> p) {
  return light.directional ? normalize(light.position_or_direction)
                           : normalize(light.position_or_direction - p);
}

// (du, dv) with dpdu du + dpdv dv closest to dp (least squares on the 2×2 normal equations);
// zero where ∂p/∂u, ∂p/∂v are degenerate (a pole).
template <class T>
GLINTLAB_FN Vec2<T> solve_uv(Vec3<T> dpdu, Vec3<T> dpdv, Vec3<T> dp) {
  const T a11 = dot(dpdu, dpdu), a12 = dot(dpdu, dpdv), a22 = dot(dpdv, dpdv);
  const T b1 = dot(dpdu, dp), b2 = dot(dpdv, dp);
  const T det = a11 * a22 - a12 * a12;
  const Mask<T> ok = abs(det) > T(1e-30) * (a11 * a22 + T(1e-300));
  const T inv = T(1) / select(ok, det, T(1));
  return {select(ok, (a22 * b1 - a12 * b2) * inv, T(0)),
          select(ok, (a11 * b2 - a12 * b1) * inv, T(0))};
}

}  // namespace detail

// The footprint of pixel coordinates (x, y) (the pixel centre for x = i + ½) on `shape`.
template <class Shape, class T>
GLINTLAB_FN PixelFootprint<T> pixel_footprint(const PinholeCamera<T>& camera, const Shape& shape, T x, T y,
                                  const LightPoint<T>& light) {
  PixelFootprint<T> f{};
  f.surface = shape.intersect(camera.ray(x, y));
  const SurfaceHit<T>& s = f.surface;
  f.frame = s.frame();
  f.wi = f.frame.to_local(normalize(camera.eye - s.p));
  f.wl = f.frame.to_local(detail::toward_light(light, s.p));

  constexpr T kOffset[4][2] = {{-0.5, -0.5}, {0.5, -0.5}, {-0.5, 0.5}, {0.5, 0.5}};
  std::array<Vec3<T>, 4> plane_p{};
  for (int c = 0; c < 4; ++c) {
    const Ray<T> r = camera.ray(x + kOffset[c][0], y + kOffset[c][1]);
    plane_p[c] = detail::on_tangent_plane(r, s.p, s.n);
    const SurfaceHit<T> hc = shape.intersect(r);
    const Mask<T> own = hc.hit;
    const Vec3<T> pc = select(own, hc.p, plane_p[c]);
    const Frame<T> fc = hc.frame();
    const Frame<T> frame_c{select(own, fc.t, f.frame.t), select(own, fc.b, f.frame.b),
                           select(own, fc.n, f.frame.n)};
    const Vec3<T> v = normalize(camera.eye - pc);
    const Vec3<T> l = detail::toward_light(light, pc);
    f.corner_h[c] = frame_c.to_local(half_vector(v, l));
    f.corner_r[c] = reflect(v, frame_c.n);
  }
  const auto dx = [](const std::array<Vec3<T>, 4>& a) {
    return T(0.5) * ((a[1] - a[0]) + (a[3] - a[2]));
  };
  const auto dy = [](const std::array<Vec3<T>, 4>& a) {
    return T(0.5) * ((a[2] - a[0]) + (a[3] - a[1]));
  };
  f.footprint.uv = s.uv;
  f.footprint.duv_dx = detail::solve_uv(s.dpdu, s.dpdv, dx(plane_p));
  f.footprint.duv_dy = detail::solve_uv(s.dpdu, s.dpdv, dy(plane_p));
  f.dh_dx = dx(f.corner_h);
  f.dh_dy = dy(f.corner_h);
  f.dr_dx = dx(f.corner_r);
  f.dr_dy = dy(f.corner_r);
  return f;
}

}  // namespace glintlab
