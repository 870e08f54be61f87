// Pinhole camera: primary rays through continuous pixel coordinates (x right, y down; pixel (i, j)
// covers [i, i+1] × [j, j+1], its centre at (i + ½, j + ½)).
#pragma once

#include "core/scene/frame.h"
#include "core/scene/shapes.h"

namespace glintlab {

template <class T>
struct PinholeCamera {
  Vec3<T> eye;
  Frame<T> frame;  // t = right, b = up, n = viewing direction
  T tan_half_fov_y;
  int width, height;

  // Camera at `eye` looking at `target`, `up` roughly up, vertical field of view in degrees.
  static PinholeCamera look_at(Vec3<T> eye, Vec3<T> target, Vec3<T> up, T fov_y_degrees, int width,
                               int height) {
    const Vec3<T> f = normalize(target - eye);
    const Vec3<T> r = normalize(cross(f, up));
    return {eye, Frame<T>{r, cross(r, f), f}, tan(fov_y_degrees * T(kPi<T> / 180) / T(2)), width,
            height};
  }

  // The ray through pixel coordinates (x, y); its direction is not normalized (unit z in camera
  // space), so ray differentials are linear in (x, y).
  GLINTLAB_FN Ray<T> ray(T x, T y) const {
    const T aspect = T(width) / T(height);
    const T sx = (T(2) * x / T(width) - T(1)) * tan_half_fov_y * aspect;
    const T sy = (T(1) - T(2) * y / T(height)) * tan_half_fov_y;
    return {eye, frame.n + sx * frame.t + sy * frame.b};
  }
};

}  // namespace glintlab
