// Mip-mapped texture of first and second slope moments (E[s_x], E[s_y], E[s_x²], E[s_y²],
// E[s_x s_y]) for LEAN mapping (Olano & Baker 2010 Sec. 3–4; Chermain et al. 2021 Sec. 5.1: "MIP
// maps of x_ñ, y_ñ, x_ñ², y_ñ², x_ñ y_ñ"). Level 0 averages the slope field over each texel by a
// stratified supersample grid; each coarser level is the 2×2 box filter of the one below, so a
// coarse texel is exactly the mean over its footprint of the finest data. Lookups are bilinear
// (periodic, texel centres at (i + ½)/n) and trilinear across levels, with the level of detail
// from the uv footprint (the isotropic rule of the OpenGL 4.6 spec, Sec. 8.14.1, Eq. 8.7–8.9:
// λ = log2 max(‖∂uv/∂x‖, ‖∂uv/∂y‖)·size).
#pragma once

#include <cmath>
#include <cstddef>
#include <functional>
#include <vector>

#include "core/math/vec.h"
#include "core/parameter_check.h"

namespace glintlab {

template <class T>
struct SlopeMoments {
  T mean_x, mean_y;  // E[s_x], E[s_y]
  T xx, yy, xy;      // E[s_x²], E[s_y²], E[s_x s_y]
};

template <class T>
GLINTLAB_FN SlopeMoments<T> lerp(const SlopeMoments<T>& a, const SlopeMoments<T>& b, T t) {
  return {a.mean_x + t * (b.mean_x - a.mean_x), a.mean_y + t * (b.mean_y - a.mean_y),
          a.xx + t * (b.xx - a.xx), a.yy + t * (b.yy - a.yy), a.xy + t * (b.xy - a.xy)};
}

class SlopeMomentMap {
 public:
  using SlopeField = std::function<Vec2<double>(double u, double v)>;

  // `size` × `size` texels at level 0 (a power of two), each the mean over
  // `supersample` × `supersample` stratified points of the slope field (∂h/∂u, ∂h/∂v) at uv.
  SlopeMomentMap(const SlopeField& slopes, int size, int supersample = 4) {
    const char* what = "slope moment map";
    detail::require(size >= 1 && size <= (1 << 14) && (size & (size - 1)) == 0, what, "size", size,
                    "a power of two from 1 to 16384");
    detail::require(supersample >= 1 && supersample <= 64, what, "supersample", supersample,
                    "1 to 64");
    std::vector<SlopeMoments<double>> base(std::size_t(size) * size);
    const double inv = 1.0 / (double(supersample) * supersample);
    for (int j = 0; j < size; ++j)
      for (int i = 0; i < size; ++i) {
        SlopeMoments<double> m{0, 0, 0, 0, 0};
        for (int b = 0; b < supersample; ++b)
          for (int a = 0; a < supersample; ++a) {
            const double u = (i + (a + 0.5) / supersample) / size;
            const double v = (j + (b + 0.5) / supersample) / size;
            const Vec2<double> s = slopes(u, v);
            m = {m.mean_x + s.x, m.mean_y + s.y, m.xx + s.x * s.x, m.yy + s.y * s.y,
                 m.xy + s.x * s.y};
          }
        base[std::size_t(j) * size + i] = {inv * m.mean_x, inv * m.mean_y, inv * m.xx, inv * m.yy,
                                           inv * m.xy};
      }
    levels_.push_back(std::move(base));
    for (int n = size / 2; n >= 1; n /= 2) {
      const std::vector<SlopeMoments<double>>& fine = levels_.back();
      std::vector<SlopeMoments<double>> coarse(std::size_t(n) * n);
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
          const auto& a = fine[std::size_t(2 * j) * (2 * n) + 2 * i];
          const auto& b = fine[std::size_t(2 * j) * (2 * n) + 2 * i + 1];
          const auto& c = fine[std::size_t(2 * j + 1) * (2 * n) + 2 * i];
          const auto& d = fine[std::size_t(2 * j + 1) * (2 * n) + 2 * i + 1];
          coarse[std::size_t(j) * n + i] = {0.25 * (a.mean_x + b.mean_x + c.mean_x + d.mean_x),
                                            0.25 * (a.mean_y + b.mean_y + c.mean_y + d.mean_y),
                                            0.25 * (a.xx + b.xx + c.xx + d.xx),
                                            0.25 * (a.yy + b.yy + c.yy + d.yy),
                                            0.25 * (a.xy + b.xy + c.xy + d.xy)};
        }
      levels_.push_back(std::move(coarse));
    }
    size_ = size;
  }

  int size() const { return size_; }
  int levels() const { return int(levels_.size()); }  // log2(size) + 1
  int level_size(int level) const { return size_ >> level; }
  const SlopeMoments<double>& texel(int level, int i, int j) const {
    return levels_[level][std::size_t(j) * level_size(level) + i];
  }

  // Bilinear at one level, periodic in u and v (the maps tile the unit square).
  template <class T>
  SlopeMoments<T> bilinear(int level, T u, T v) const {
    const int n = level_size(level);
    const T x = u * T(n) - T(0.5), y = v * T(n) - T(0.5);
    const T fx = std::floor(x), fy = std::floor(y);
    const T tx = x - fx, ty = y - fy;
    const int i0 = wrap(int(fx), n), j0 = wrap(int(fy), n);
    const int i1 = wrap(i0 + 1, n), j1 = wrap(j0 + 1, n);
    const SlopeMoments<T> a = cast<T>(texel(level, i0, j0)), b = cast<T>(texel(level, i1, j0));
    const SlopeMoments<T> c = cast<T>(texel(level, i0, j1)), d = cast<T>(texel(level, i1, j1));
    return lerp(lerp(a, b, tx), lerp(c, d, tx), ty);
  }

  // Trilinear: bilinear at ⌊λ⌋ and ⌊λ⌋ + 1, blended by the fraction; λ clamped to the pyramid.
  template <class T>
  SlopeMoments<T> trilinear(T u, T v, T lod) const {
    const T l = clamp(lod, T(0), T(levels() - 1));
    const int l0 = int(std::floor(l));
    const int l1 = std::min(l0 + 1, levels() - 1);
    return lerp(bilinear(l0, u, v), bilinear(l1, u, v), l - T(l0));
  }

  // λ from the uv footprint of a pixel: the columns ∂uv/∂x and ∂uv/∂y of the uv Jacobian.
  template <class T>
  T lod(Vec2<T> duv_dx, Vec2<T> duv_dy) const {
    const T rho = T(size_) * sqrt(max(dot(duv_dx, duv_dx), dot(duv_dy, duv_dy)));
    return max(log(max(rho, T(1e-30))) / T(0.69314718055994530942), T(0));
  }

  template <class T>
  SlopeMoments<T> lookup(T u, T v, Vec2<T> duv_dx, Vec2<T> duv_dy) const {
    return trilinear(u, v, lod(duv_dx, duv_dy));
  }

 private:
  static int wrap(int i, int n) { return ((i % n) + n) % n; }
  template <class T>
  static SlopeMoments<T> cast(const SlopeMoments<double>& m) {
    return {T(m.mean_x), T(m.mean_y), T(m.xx), T(m.yy), T(m.xy)};
  }

  int size_ = 0;
  std::vector<std::vector<SlopeMoments<double>>> levels_;  // level 0 (finest) first
};

}  // namespace glintlab
