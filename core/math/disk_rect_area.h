// Exact area of an axis-aligned rectangle intersected with a disk, for the marginal density of
// Kemppinen et al. 2025 Algorithm 2 (core/glints/kemppinen_sampling.h). Scalar code.
#pragma once

#include <algorithm>
#include <utility>

#include "core/math/config.h"
#include "core/math/ops.h"

namespace glintlab {

// Area of [x0, x1] × [y0, y1] ∩ {(x − cx)² + (y − cy)² ≤ r²}: ∫ of the chord length clipped to
// [y0, y1] over x, split where the circle crosses y = y0 and y = y1, each piece in closed form
// with ∫√(r² − u²) du = ½(u√(r² − u²) + r² asin(u/r)).
// Defined out of line (disk_rect_area.cpp, baseline flags): the SIMD ISA translation units call
// it lane by lane, and an inline copy there would be a weak symbol each ISA defines.
double disk_rect_area(double x0, double x1, double y0, double y1, double cx, double cy, double r);

// Its body: the out-of-line definition's, and a device thread's (which cannot call host code).
GLINTLAB_FN double disk_rect_area_inline(double x0, double x1, double y0, double y1, double cx,
                                          double cy, double r) {
  const double a = std::max(x0 - cx, -r), b = std::min(x1 - cx, r);
  if (!(b > a) || !(y1 > y0)) return 0;
  const double ly = y0 - cy, hy = y1 - cy;
  auto s = [r](double u) { return safe_sqrt(r * r - u * u); };
  auto big_s = [&](double u) { return 0.5 * (u * s(u) + r * r * atan2(u, s(u))); };
  double br[6] = {a, b, 0, 0, 0, 0};
  int nb = 2;
  for (double y : {ly, hy})
    if (std::abs(y) < r) {
      const double c = std::sqrt(r * r - y * y);
      for (double u : {-c, c})
        if (u > a && u < b) br[nb++] = u;
    }
  for (int i = 1; i < nb; ++i)  // insertion sort of at most 6 breakpoints
    for (int j = i; j > 0 && br[j - 1] > br[j]; --j) std::swap(br[j - 1], br[j]);
  // S at each breakpoint, computed once and only where a piece follows the circle (its atan2 is
  // most of this function's time; two neighbouring pieces share a breakpoint).
  double big_s_at[6];
  bool known[6] = {false, false, false, false, false, false};
  auto big_s_of = [&](int i) {
    if (!known[i]) big_s_at[i] = big_s(br[i]);
    known[i] = true;
    return big_s_at[i];
  };
  double area = 0;
  for (int i = 0; i + 1 < nb; ++i) {
    const double u0 = br[i], u1 = br[i + 1];
    if (!(u1 > u0)) continue;
    const double um = 0.5 * (u0 + u1), sm = s(um);
    // Between breakpoints the circle is on one side of each edge; ≤ keeps a tangent edge (|y| = r).
    const bool top_circle = sm <= hy, bottom_circle = -sm >= ly;
    const double top = top_circle ? sm : hy, bottom = bottom_circle ? -sm : ly;
    if (!(top > bottom)) continue;
    const double circ = top_circle || bottom_circle ? big_s_of(i + 1) - big_s_of(i) : 0.0;
    const double w = u1 - u0;
    area += (top_circle ? circ : hy * w) - (bottom_circle ? -circ : ly * w);
  }
  return area;
}

// What a kernel calls: the out-of-line copy on the host, the body itself on a CUDA device.
GLINTLAB_INLINE double disk_rect_area_in_kernel(double x0, double x1, double y0, double y1, double cx,
                                                double cy, double r) {
#if defined(__CUDA_ARCH__)
  return disk_rect_area_inline(x0, x1, y0, y1, cx, cy, r);
#else
  return disk_rect_area(x0, x1, y0, y1, cx, cy, r);
#endif
}

}  // namespace glintlab
