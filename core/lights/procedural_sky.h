// A deterministic analytic sky with a sun, and its lat-long image for EnvironmentMap. No paper
// model: a documented stand-in for a clear sky (linear zenith-to-horizon gradient in cos θ, a
// constant ground, a uniform solar disc), simple enough that its integrals are known in closed
// form: ∫ L dω = π (zenith + horizon) + 2π ground + 2π(1 − cos γ_sun) sun.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>

#include "core/lights/environment_map.h"
#include "core/lights/spherical_cap.h"
#include "core/parameter_check.h"

namespace glintlab {

struct SkyParameters {
  Vec3<double> sun_direction{0.5, 0.0, 0.8660254037844386};  // towards the sun (30° from zenith)
  double sun_half_angle = 0.004654;                          // rad: the solar disc, 0.2667°
  Vec3<double> sun_radiance{2.0e4, 1.9e4, 1.7e4};
  Vec3<double> zenith{0.25, 0.45, 1.0};   // sky radiance at θ = 0
  Vec3<double> horizon{0.8, 0.85, 0.9};   // sky radiance at θ = 90°
  Vec3<double> ground{0.15, 0.15, 0.15};  // below the horizon
};

// L(ω) = zenith·z + horizon·(1 − z) for z ≥ 0, ground for z < 0, plus sun inside its cap.
inline Vec3<double> sky_radiance(const SkyParameters& s, const Vec3<double>& w) {
  Vec3<double> L = w.z >= 0 ? w.z * s.zenith + (1 - w.z) * s.horizon : s.ground;
  const SphericalCap<double> sun{normalize(s.sun_direction), one_minus_cos(s.sun_half_angle)};
  if (cap_contains(sun, w)) L = L + s.sun_radiance;
  return L;
}

// ∫ L dω over the sphere, per channel (closed form above).
inline Vec3<double> sky_integral(const SkyParameters& s) {
  const double pi = 3.14159265358979323846;
  return pi * (s.zenith + s.horizon) + (2 * pi) * s.ground +
         (2 * pi * one_minus_cos(s.sun_half_angle)) * s.sun_radiance;
}

// The sky's lat-long image (EnvironmentMap's convention): each pixel holds the mean of L over the
// pixel's solid angle. The sky and ground use `supersample` points uniform in cos θ (L does not
// depend on φ) (exact for the linear gradient inside a row, so rows meeting at the horizon are
// exact too when the height is even); the sun is splatted: a 64 × 64 stratified grid over its cap,
// each point carrying L_sun Ω_sun / 4096 of energy into the pixel it falls in, so its energy is
// exact and its position resolved even when the disc is much smaller than a pixel.
inline LatLongImage make_procedural_sky(const SkyParameters& s, int width, int height,
                                        int supersample = 4) {
  const char* what = "procedural sky";
  detail::require(width >= 1, what, "width", width, "width >= 1 pixel");
  detail::require(height >= 1, what, "height", height, "height >= 1 pixel");
  detail::require(supersample >= 1 && supersample <= 64, what, "supersample", supersample,
                  "1 to 64");
  detail::require(std::isfinite(s.sun_half_angle) && s.sun_half_angle > 0 &&
                      s.sun_half_angle < 1.5707963267948966,
                  what, "sun_half_angle", s.sun_half_angle, "0 < sun_half_angle < pi/2 rad");
  detail::require_direction(what, "sun_direction", s.sun_direction);
  detail::require_radiance(std::string(what) + " sun", s.sun_radiance);
  detail::require_radiance(std::string(what) + " zenith", s.zenith);
  detail::require_radiance(std::string(what) + " horizon", s.horizon);
  detail::require_radiance(std::string(what) + " ground", s.ground);
  const double pi = 3.14159265358979323846;
  const int n = supersample;
  std::vector<Vec3<double>> acc(std::size_t(width) * height, Vec3<double>{0, 0, 0});
  std::vector<double> omega(height);
  for (int j = 0; j < height; ++j) {
    const double c0 = std::cos(pi * j / height), c1 = std::cos(pi * (j + 1) / height);
    omega[j] = 2 * pi / width * (c0 - c1);
    for (int i = 0; i < width; ++i) {
      Vec3<double> sum{0, 0, 0};
      for (int b = 0; b < n; ++b) {  // the sky does not depend on φ: one column of the grid
        const double z = c0 + (c1 - c0) * (b + 0.5) / n;
        sum = sum + (z >= 0 ? z * s.zenith + (1 - z) * s.horizon : s.ground);
      }
      acc[std::size_t(j) * width + i] = (1.0 / n) * sum;
    }
  }
  const SphericalCap<double> sun{normalize(s.sun_direction), one_minus_cos(s.sun_half_angle)};
  constexpr int kSun = 64;
  const double share = cap_solid_angle(sun) / (kSun * kSun);
  const EnvironmentMap::Grid grid{width, height};
  for (int b = 0; b < kSun; ++b)
    for (int a = 0; a < kSun; ++a) {
      const Vec3<double> w = sample_cap(sun, Vec2<double>{(a + 0.5) / kSun, (b + 0.5) / kSun});
      int i, j;
      grid.pixel_of(w, &i, &j);
      acc[std::size_t(j) * width + i] =
          acc[std::size_t(j) * width + i] + (share / omega[j]) * s.sun_radiance;
    }
  LatLongImage img;
  img.width = width;
  img.height = height;
  img.rgb.resize(std::size_t(3) * width * height);
  for (std::size_t k = 0; k < acc.size(); ++k) {
    img.rgb[3 * k] = float(acc[k].x);
    img.rgb[3 * k + 1] = float(acc[k].y);
    img.rgb[3 * k + 2] = float(acc[k].z);
  }
  return img;
}

}  // namespace glintlab
