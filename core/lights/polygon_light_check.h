// The host-side factory of core/lights/polygon_light.h: a polygon light built from its vertices,
// validated with messages that name the bad field and its valid range (ParameterError). Kept out
// of the light's own header so that kernels reading a PolygonLight compile without fmt (nvcc).
#pragma once

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <span>

#include "core/lights/polygon_light.h"
#include "core/parameter_check.h"

namespace glintlab {

// A validated convex polygon light (host side). The vertices, 3 to kMaxPolygonVertices, must be
// finite, planar (off their plane by at most 1e-9 of the polygon's diameter), non-degenerate (no
// coincident vertices, no three consecutive collinear ones, area > 0) and convex (every turn the
// same way, once around). Either winding is accepted: the light emits towards the side from which
// its vertices appear counter-clockwise (the right-hand normal).
template <class T = double>
PolygonLight<T> make_polygon_light(std::span<const Vec3<double>> vertices, Vec3<double> radiance,
                                   AreaSampling sampling = AreaSampling::kSolidAngle) {
  const char* what = "polygon light";
  const int n = static_cast<int>(vertices.size());
  detail::require(n >= 3 && n <= kMaxPolygonVertices, what, "the vertex count", n,
                  "3 to 8 vertices");
  double diameter = 0;
  for (int k = 0; k < n; ++k) {
    detail::require_finite(what, fmt::format("vertex {}", k), vertices[k]);
    for (int j = 0; j < n; ++j) diameter = std::max(diameter, length(vertices[k] - vertices[j]));
  }
  detail::require(diameter > 0, what, "the polygon's diameter", diameter,
                  "> 0: the vertices must not all coincide");
  const auto vk = [&](int k) { return vertices[((k % n) + n) % n]; };
  for (int k = 0; k < n; ++k)
    if (!(length(vk(k + 1) - vk(k)) > 1e-12 * diameter))
      throw ParameterError(
          fmt::format("{}: vertices {} and {} coincide (valid: distinct consecutive vertices)",
                      what, k, (k + 1) % n));
  // Newell's normal: twice the vector area, exact for a planar polygon.
  Vec3<double> newell{0, 0, 0};
  for (int k = 0; k < n; ++k) newell = newell + cross(vk(k), vk(k + 1));
  const double area = 0.5 * length(newell);
  detail::require(area > 1e-12 * diameter * diameter, what, "the polygon's area", area,
                  "> 1e-12 diameter^2: the vertices must not be collinear");
  const Vec3<double> normal = (1 / length(newell)) * newell;
  for (int k = 0; k < n; ++k) {
    const double off = dot(vk(k) - vk(0), normal);
    if (!(std::abs(off) <= 1e-9 * diameter))
      throw ParameterError(fmt::format(
          "{}: vertex {} is off the polygon's plane by {} (valid: planar within 1e-9 of the "
          "diameter {})",
          what, k, off, diameter));
  }
  double turning = 0;
  for (int k = 0; k < n; ++k) {
    const Vec3<double> e0 = vk(k) - vk(k - 1), e1 = vk(k + 1) - vk(k);
    const double s = dot(cross(e0, e1), normal), c = dot(e0, e1);
    if (!(s > 1e-12 * length(e0) * length(e1)))
      throw ParameterError(fmt::format(
          "{}: the polygon is {} at vertex {} (valid: a strictly convex polygon, every turn the "
          "same way)",
          what,
          std::abs(s) <= 1e-12 * length(e0) * length(e1) ? "degenerate (collinear edges)"
                                                         : "not convex",
          k));
    turning += std::atan2(s, c);
  }
  detail::require(std::abs(turning - 2 * 3.14159265358979323846) < 1e-6, what,
                  "the total turning angle", turning,
                  "2 pi: a convex polygon winds once (a star polygon winds more)");
  detail::require_radiance(what, radiance);
  PolygonLight<T> light{};
  light.count = n;
  for (int k = 0; k < n; ++k) light.vertex[k] = cast<T>(vertices[k]);
  light.normal = cast<T>(normal);
  light.area = T(area);
  double acc = 0;
  for (int j = 0; j < n - 2; ++j) {
    acc += 0.5 * length(cross(vertices[j + 1] - vertices[0], vertices[j + 2] - vertices[0]));
    light.fan_cdf[j] = T(j == n - 3 ? 1.0 : acc / area);
  }
  light.emitted = cast<T>(radiance);
  light.sampling = sampling;
  return light;
}

}  // namespace glintlab
