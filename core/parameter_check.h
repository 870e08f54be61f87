// Host-side validation of light and surface-detail parameters: one-line errors naming the parameter
// and its valid range, thrown at construction so kernels never see a bad value.
#pragma once

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "core/math/vec.h"

namespace glintlab {

// The error every constructor in core/lights and core/scene (and any other host-side constructor)
// throws; what() is one line, e.g. "disk light: radius = -1 is out of range (valid: radius > 0)".
// The CLI prefixes "glintlab: error: ".
class ParameterError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

namespace detail {

inline void require(bool ok, const std::string& what, const std::string& name, double value,
                    const char* valid) {
  if (!ok)
    throw ParameterError(
        fmt::format("{}: {} = {} is out of range (valid: {})", what, name, value, valid));
}

inline void require_finite(const std::string& what, const std::string& name, Vec3<double> v) {
  if (!(std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z)))
    throw ParameterError(fmt::format("{}: {} = ({}, {}, {}) is not finite (valid: finite numbers)",
                                     what, name, v.x, v.y, v.z));
}

// RGB radiance: finite and non-negative in every channel.
inline void require_radiance(const std::string& what, Vec3<double> L) {
  if (!(std::isfinite(L.x) && std::isfinite(L.y) && std::isfinite(L.z) && L.x >= 0 && L.y >= 0 &&
        L.z >= 0))
    throw ParameterError(fmt::format(
        "{}: radiance = ({}, {}, {}) is out of range (valid: finite, >= 0 in every channel)", what,
        L.x, L.y, L.z));
}

// A unit direction from a caller's non-zero vector.
inline Vec3<double> require_direction(const std::string& what, const std::string& name,
                                      Vec3<double> v) {
  require_finite(what, name, v);
  const double l = length(v);
  if (!(l > 0))
    throw ParameterError(
        fmt::format("{}: {} = (0, 0, 0) is out of range (valid: a non-zero vector)", what, name));
  return (1 / l) * v;
}

}  // namespace detail
}  // namespace glintlab
