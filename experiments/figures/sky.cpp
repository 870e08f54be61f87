// Procedural lat-long sky; see sky.h.
#include "experiments/figures/sky.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace glintlab::experiments {

Vec3<double> LatLongImage::lookup(Vec3<double> d) const {
  double phi = std::atan2(d.y, d.x);
  if (phi < 0) phi += 2 * std::numbers::pi;
  const double theta = std::acos(std::clamp(d.z, -1.0, 1.0));
  const double fx = phi / (2 * std::numbers::pi) * width - 0.5;
  const double fy = std::clamp(theta / std::numbers::pi * height - 0.5, 0.0, height - 1.0);
  const double x0f = std::floor(fx), y0f = std::floor(fy);
  const double tx = fx - x0f, ty = fy - y0f;
  const int x0 = (static_cast<int>(x0f) % width + width) % width, x1 = (x0 + 1) % width;
  const int y0 = static_cast<int>(y0f), y1 = std::min(y0 + 1, height - 1);
  const auto px = [&](int x, int y) {
    const float* p = &rgb[(static_cast<std::size_t>(y) * width + x) * 3];
    return Vec3<double>{p[0], p[1], p[2]};
  };
  return ((1 - ty) * (1 - tx)) * px(x0, y0) + ((1 - ty) * tx) * px(x1, y0) +
         (ty * (1 - tx)) * px(x0, y1) + (ty * tx) * px(x1, y1);
}

LatLongImage procedural_sky(int width, int height) {
  LatLongImage img{width, height, std::vector<float>(static_cast<std::size_t>(width) * height * 3)};
  constexpr double kPi = std::numbers::pi;
  const double sun_elev = 40 * kPi / 180, sun_az = 30 * kPi / 180;
  const Vec3<double> sun{std::cos(sun_elev) * std::cos(sun_az),
                         std::cos(sun_elev) * std::sin(sun_az), std::sin(sun_elev)};
  const double cos_sun = std::cos(5.0 * kPi / 180);
  for (int j = 0; j < height; ++j) {
    for (int i = 0; i < width; ++i) {
      const double phi = (i + 0.5) / width * 2 * kPi;
      const double theta = (j + 0.5) / height * kPi;
      const Vec3<double> d{std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                           std::cos(theta)};
      Vec3<double> c;
      if (d.z >= 0) {
        const double t = std::sqrt(d.z);
        c = (1 - t) * Vec3<double>{0.9, 0.95, 1.0} + t * Vec3<double>{0.25, 0.45, 0.9};
        if (dot(d, sun) >= cos_sun) c = Vec3<double>{40.0, 38.0, 34.0};
      } else {
        const bool check = (static_cast<int>(std::floor(phi / kPi * 8)) +
                            static_cast<int>(std::floor(theta / kPi * 16))) %
                               2 ==
                           0;
        c = check ? Vec3<double>{0.30, 0.26, 0.22} : Vec3<double>{0.08, 0.07, 0.06};
      }
      float* p = &img.rgb[(static_cast<std::size_t>(j) * width + i) * 3];
      p[0] = static_cast<float>(c.x);
      p[1] = static_cast<float>(c.y);
      p[2] = static_cast<float>(c.z);
    }
  }
  return img;
}

}  // namespace glintlab::experiments
