// Areas of a circle's intersection with a polygon and with another circle, in the plane: the
// result weights of Podee et al. (Sec. 3.2), area(projected light ∩ reflection space). The polygon
// area is the sum over its edges (a, b) of the signed area of circle ∩ triangle(centre, a, b), each
// split at the segment's circle crossings into circular sectors and one triangle (the standard
// decomposition for circle–polygon clipping; exact for any simple polygon, convex or not). The
// lens of two circles is the two circular segments cut by their common chord.
#pragma once

#include "core/math/ops.h"
#include "core/math/vec.h"

namespace glintlab {

template <class T>
GLINTLAB_FN T perp_dot(Vec2<T> a, Vec2<T> b) {
  return a.x * b.y - a.y * b.x;
}

// Signed area of the sector of the circle of radius `radius` about the origin between the rays
// through a and b (turning the short way from a to b): radius²/2 · ∠(a, b).
template <class T>
GLINTLAB_FN T signed_sector_area(Vec2<T> a, Vec2<T> b, T radius) {
  return T(0.5) * radius * radius * atan2(perp_dot(a, b), dot(a, b));
}

// Signed area of (circle of `radius` about the origin) ∩ triangle(origin, a, b): positive when
// (a, b) turns counter-clockwise. The segment a + t (b − a) meets the circle at t1 ≤ t2; clipped to
// [0, 1], the parts of the edge outside the circle contribute sectors and the inside part a
// triangle. Without real crossings both clipped parameters are 1 (the whole edge is a sector).
template <class T>
GLINTLAB_FN T circle_triangle_signed_area(Vec2<T> a, Vec2<T> b, T radius) {
  const Vec2<T> d = b - a;
  const T dd = dot(d, d);
  const Mask<T> moves = dd > T(0);
  const T inv = T(1) / select(moves, dd, T(1));
  const T mid = -dot(a, d) * inv;  // parameter of the point closest to the centre
  const T disc = mid * mid - (dot(a, a) - radius * radius) * inv;
  const Mask<T> crosses = moves && disc > T(0);
  const T half = sqrt(select(crosses, disc, T(0)));
  const T s1 = select(crosses, clamp(mid - half, T(0), T(1)), T(1));
  const T s2 = select(crosses, clamp(mid + half, T(0), T(1)), T(1));
  const Vec2<T> p1 = a + s1 * d, p2 = a + s2 * d;
  return signed_sector_area(a, p1, radius) + T(0.5) * perp_dot(p1, p2) +
         signed_sector_area(p2, b, radius);
}

// Signed (shoelace) area of the polygon q[0], …, q[N−1].
template <int N, class T>
GLINTLAB_FN T polygon_signed_area(const Vec2<T> (&q)[N]) {
  T s = T(0);
  for (int i = 0; i < N; ++i) s = s + perp_dot(q[i], q[(i + 1) % N]);
  return T(0.5) * s;
}

// Exact area of (circle of `radius` about `centre`) ∩ polygon q (a simple polygon, either
// orientation). For a self-intersecting polygon it is the winding-number-weighted area, in
// absolute value.
template <int N, class T>
GLINTLAB_FN T circle_polygon_area(const Vec2<T> (&q)[N], Vec2<T> centre, T radius) {
  T s = T(0);
  for (int i = 0; i < N; ++i)
    s = s + circle_triangle_signed_area(q[i] - centre, q[(i + 1) % N] - centre, radius);
  return abs(s);
}

// Area of the lens where circles (c1, r1) and (c2, r2) overlap: 0 when apart, the smaller disk
// when one contains the other, else r_i² acos(x_i / r_i) − x_i √(r_i² − x_i²) summed over both,
// x_i the signed distance of the common chord from centre i.
template <class T>
GLINTLAB_FN T circle_circle_area(Vec2<T> c1, T r1, Vec2<T> c2, T r2) {
  const Vec2<T> dc = c2 - c1;
  const T d = sqrt(dot(dc, dc));
  const T rmin = min(r1, r2);
  const Mask<T> apart = d >= r1 + r2;
  const Mask<T> nested = d <= abs(r1 - r2);
  const T ds = select(apart || nested, T(1), d);
  const T x1 = (ds * ds + r1 * r1 - r2 * r2) / (T(2) * ds);
  const T x2 = ds - x1;
  const T seg1 = r1 * r1 * safe_acos(x1 / r1) - x1 * safe_sqrt(r1 * r1 - x1 * x1);
  const T seg2 = r2 * r2 * safe_acos(x2 / r2) - x2 * safe_sqrt(r2 * r2 - x2 * x2);
  return select(apart, T(0), select(nested, T(kPi<T>) * rmin * rmin, seg1 + seg2));
}

}  // namespace glintlab
