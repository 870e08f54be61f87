// Host-side validation of a polygon handed to the LTC integral (core/ltc/ltc.h, Heitz et al. 2016
// Sec. 3.2 assumes a convex polygon): one-line ParameterError for a bad one.
#pragma once

#include <fmt/format.h>

#include <cmath>
#include <span>

#include "core/lights/polygon_light_check.h"
#include "core/parameter_check.h"

namespace glintlab {

// Throws ParameterError unless `vertices` (positions relative to the shading point, local frame)
// form a polygon ltc_polygon_integral handles: 3 to kMaxPolygonVertices finite, planar,
// non-degenerate, strictly convex vertices (the checks of make_polygon_light), whose plane does
// not pass through the shading point (there the spherical polygon collapses to an arc).
inline void check_ltc_polygon(std::span<const Vec3<double>> vertices) {
  const PolygonLight<double> poly = make_polygon_light<double>(vertices, {1.0, 1.0, 1.0});
  double diameter = 0;
  for (const Vec3<double>& a : vertices)
    for (const Vec3<double>& b : vertices) diameter = std::max(diameter, length(a - b));
  const double distance = std::abs(dot(poly.vertex[0], poly.normal));
  if (!(distance > 1e-9 * diameter))
    throw ParameterError(fmt::format(
        "LTC polygon: the shading point lies in the polygon's plane (distance {}; valid: > 1e-9 "
        "of the diameter {})",
        distance, diameter));
}

}  // namespace glintlab
