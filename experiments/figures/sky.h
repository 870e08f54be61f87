// Procedural lat-long sky (RGB, radiance) and its bilinear lookup: the environment light of the
// Eto & Tokuyoshi 2023 Fig. 4 scene until the environment-map light of core/lights/ replaces it
// (swap eto_environment() in eto_tokuyoshi2023.cpp).
#pragma once

#include <vector>

#include "core/math/vec.h"

namespace glintlab::experiments {

// World frame z up. A direction with polar angle θ (from +z) and azimuth φ = atan2(y, x) in
// [0, 2π) maps to u = φ/(2π), v = θ/π; pixel (i, j) has its centre at ((i + ½)/W, (j + ½)/H).
struct LatLongImage {
  int width = 0, height = 0;
  std::vector<float> rgb;  // row-major, 3 floats per pixel

  // Bilinear radiance along the unit direction d (wraps in u, clamps in v).
  Vec3<double> lookup(Vec3<double> d) const;
};

// Sky: a horizon-to-zenith gradient, a sun disk of angular radius 5° at 40° elevation and
// radiance 40 (the bright source that makes rough reflections noisy, as in the paper's HDR
// environments, yet large enough that its hits are not so rare that a 16-spp image's RMSE is
// itself mostly noise), and a dark checkered ground below the horizon.
LatLongImage procedural_sky(int width, int height);

}  // namespace glintlab::experiments
