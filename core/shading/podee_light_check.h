// Host-side check of Podee et al.'s assumptions about its light, apart from the kernels of
// core/shading/podee_shade.h: it formats its message (core/parameter_check.h, fmt), which a device
// compiler does not take, so the shading kernels stay free of it and compile for a GPU too.
#pragma once

#include <cmath>
#include <string>

#include "core/parameter_check.h"

namespace glintlab::podee {

// One-line ParameterError unless the light is a disk of positive radius whose centre lies above
// the shaded surface (the light plane at p + l faces the surface's side, Sec. 3.1).
inline void require_light(const std::string& what, double radius, double centre_height) {
  glintlab::detail::require(std::isfinite(radius) && radius > 0, what, "disk radius", radius,
                            "a finite radius > 0");
  glintlab::detail::require(std::isfinite(centre_height) && centre_height > 0, what,
                            "light height above the surface", centre_height,
                            "> 0: the disk's centre above the surface");
}

}  // namespace glintlab::podee
