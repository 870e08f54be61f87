// Podee, Max, Iwasaki & Dobashi, "Micro-specular-highlight real-time rendering", Sec. 3: reflection
// vector selection (Sec. 3.1) and result weighting (Sec. 3.2) for a mirror-like pixel under a disk
// light, from the four reflection vectors at the pixel corners (Fig. 2, 3).
//
// All vectors are in one frame with the surface centre p at the origin. The light plane is the
// plane through p + l with normal l (l: unit vector toward the light's centre); a reflection
// vector r is projected onto it along itself, x = r / (r·l), so the disk's centre projects to the
// plane's origin and a disk of angular radius γ to a circle of radius tan γ ("we approximate the
// projected light source by a circle"). The four projected corners span the reflection space, a
// quadrilateral with straight edges ("the reflection space with a quad"): under the paper's
// bilinear assumption an edge holds combinations of two corner vectors, whose projections lie on
// the segment between the projected corners, so for a convex quad the reflection space is exactly
// the quad. The selected point is the point of the quad closest to the projected centre (the
// centre itself when inside); the result is lighting(selected vector) × area(circle ∩ quad) /
// area(quad), which is the pixel average of a mirror's reflected radiance when the Jacobian of the
// bilinear map is constant (Sec. 3.2). With a mirror and a uniform disk the lighting term is the
// light's radiance exactly where the selected point is inside the circle, i.e. where the weight is
// non-zero: selection is what lets a pixel whose centre misses the highlight still see it.
#pragma once

#include <array>
#include <cmath>

#include "core/math/orthonormal_basis.h"
#include "core/math/vec.h"
#include "core/shading/circle_intersection_area.h"

namespace glintlab::podee {

// How area(circle ∩ reflection space) is computed (Sec. 3.2). kExact: the exact area of the
// circle ∩ the quad; kQuadAsCircle: the quad replaced by the circle of equal area about its area
// centroid, a closed-form lens (the cheaper approximation); kNone: weight 1 (selection only, an
// ablation: brightest-sample shading without result weighting).
enum class Weighting : int { kExact = 0, kQuadAsCircle = 1, kNone = 2 };

// Which point of the reflection space is lit (Sec. 3.1). kClosestPoint is the paper's; the other
// two are plausible-looking wrong rules kept as negative controls: the corner nearest the
// projected centre, and the quad's vertex average.
enum class Selection : int { kClosestPoint = 0, kNearestCorner = 1, kCentroid = 2 };

template <class T>
struct Result {
  Vec3<T> r;       // the selected (most intense) reflection vector, unit
  Vec2<T> point;   // its projection on the light plane (light-plane coordinates)
  T distance;      // |point − projected disk centre| on the light plane
  T weight;        // area(circle ∩ quad) / area(quad), in [0, 1]
  T lit;           // 1 where the selected vector points into the disk, else 0
  T value;         // lit × weight: the pixel's reflected radiance for unit light radiance
  T quad_area;     // area of the reflection space on the light plane
  Mask<T> inside;  // the projected centre is inside the reflection space
};

// Reflection vectors with r·l below this are projected as if r·l were this: they point away from
// the light plane (the projection is at infinity), and a far point in the right direction keeps
// the quad's shape on the light's side.
inline constexpr double kMinCosine = 1e-6;

// A point's coordinates on the light plane: (r·e1, r·e2) / (r·l).
template <class T>
GLINTLAB_FN Vec2<T> project_to_plane(Vec3<T> r, const OrthonormalBasis<T>& plane) {
  const T inv = T(1) / max(dot(r, plane.z), T(kMinCosine));
  return {dot(r, plane.x) * inv, dot(r, plane.y) * inv};
}

// Closest point of segment [a, b] to the origin.
template <class T>
GLINTLAB_FN Vec2<T> closest_on_segment(Vec2<T> a, Vec2<T> b) {
  const Vec2<T> d = b - a;
  const T dd = dot(d, d);
  const T t = clamp(safe_div(-dot(a, d), dd), T(0), T(1));
  return a + t * d;
}

// The projected reflection space: the four corners in polygon order. Corners come in the order of
// core/scene/footprint.h ((x−½, y−½), (x+½, y−½), (x−½, y+½), (x+½, y+½)), so the quad's boundary
// runs 0, 1, 3, 2.
template <class T>
GLINTLAB_FN void reflection_space(const std::array<Vec3<T>, 4>& corner_r,
                                  const OrthonormalBasis<T>& plane, Vec2<T> (&q)[4]) {
  q[0] = project_to_plane(corner_r[0], plane);
  q[1] = project_to_plane(corner_r[1], plane);
  q[2] = project_to_plane(corner_r[3], plane);
  q[3] = project_to_plane(corner_r[2], plane);
}

// Sec. 3.1 and 3.2 for one pixel and one disk light: `l` the unit direction toward the disk's
// centre, `tan_radius` = tan γ of its angular radius γ (the projected circle's radius).
template <class T>
GLINTLAB_FN Result<T> shade(const std::array<Vec3<T>, 4>& corner_r, Vec3<T> l, T tan_radius,
                            Weighting weighting = Weighting::kExact,
                            Selection selection = Selection::kClosestPoint) {
  const OrthonormalBasis<T> plane = basis_from_z(l);
  Vec2<T> q[4];
  reflection_space(corner_r, plane, q);

  // Inside test by the winding number about the centre (any simple polygon, either orientation).
  T winding = T(0);
  Vec2<T> nearest = q[0];
  T nearest_d2 = dot(q[0], q[0]);
  Vec2<T> corner = q[0];
  T corner_d2 = nearest_d2;
  Vec2<T> centroid{T(0), T(0)};
  for (int i = 0; i < 4; ++i) {
    const Vec2<T> a = q[i], b = q[(i + 1) % 4];
    winding = winding + atan2(perp_dot(a, b), dot(a, b));
    const Vec2<T> c = closest_on_segment(a, b);
    const T d2 = dot(c, c);
    const Mask<T> closer = d2 < nearest_d2;
    nearest = {select(closer, c.x, nearest.x), select(closer, c.y, nearest.y)};
    nearest_d2 = select(closer, d2, nearest_d2);
    const T a2 = dot(a, a);
    const Mask<T> corner_closer = a2 < corner_d2;
    corner = {select(corner_closer, a.x, corner.x), select(corner_closer, a.y, corner.y)};
    corner_d2 = select(corner_closer, a2, corner_d2);
    centroid = centroid + T(0.25) * a;
  }
  const Mask<T> inside = abs(winding) > T(kPi<T>);

  Vec2<T> point{select(inside, T(0), nearest.x), select(inside, T(0), nearest.y)};
  if (selection == Selection::kNearestCorner) point = corner;  // uniform choice, not per lane
  if (selection == Selection::kCentroid) point = centroid;

  Result<T> res;
  res.point = point;
  res.distance = sqrt(dot(point, point));
  res.r = normalize(plane.z + point.x * plane.x + point.y * plane.y);
  res.lit = select(res.distance <= tan_radius, T(1), T(0));
  res.inside = inside;

  const T signed_area = polygon_signed_area(q);
  const T area = abs(signed_area);
  res.quad_area = area;
  // A quad of (numerically) zero area is a single reflection direction: the pixel sees the light
  // fully or not at all.
  const Mask<T> degenerate = !(area > T(1e-12) * max(tan_radius * tan_radius, T(1e-12)));
  const T safe_area = select(degenerate, T(1), area);
  T covered;
  if (weighting == Weighting::kExact) {
    covered = circle_polygon_area(q, Vec2<T>{T(0), T(0)}, tan_radius);
  } else if (weighting == Weighting::kQuadAsCircle) {
    // Area centroid of the quad (shoelace-weighted), the vertex average where the area vanishes.
    Vec2<T> c{T(0), T(0)};
    for (int i = 0; i < 4; ++i) {
      const Vec2<T> a = q[i], b = q[(i + 1) % 4];
      c = c + perp_dot(a, b) * (a + b);
    }
    const T s6 = T(6) * select(degenerate, T(1), signed_area);
    const Vec2<T> ca{c.x / s6, c.y / s6};
    const Vec2<T> cq{select(degenerate, centroid.x, ca.x), select(degenerate, centroid.y, ca.y)};
    covered =
        circle_circle_area(Vec2<T>{T(0), T(0)}, tan_radius, cq, sqrt(safe_area * T(kInvPi<T>)));
  } else {
    covered = safe_area;
  }
  res.weight = select(degenerate, res.lit, clamp(covered / safe_area, T(0), T(1)));
  res.value = res.lit * res.weight;
  return res;
}

// tan γ of a cone of half-angle γ given its cosine (the projected circle's radius, Sec. 3.1).
template <class T>
GLINTLAB_FN T tan_radius(T cos_half_angle) {
  const T c = clamp(cos_half_angle, T(-1), T(1));
  return safe_sqrt(T(1) - c * c) / max(c, T(1e-30));
}

}  // namespace glintlab::podee
