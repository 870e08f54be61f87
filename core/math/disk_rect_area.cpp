// Exact area of an axis-aligned rectangle intersected with a disk (core/math/disk_rect_area.h),
// for the marginal density of Kemppinen et al. 2025 Algorithm 2.
#include "core/math/disk_rect_area.h"

#include <algorithm>
#include <utility>

#include "core/math/ops.h"

namespace glintlab {

double disk_rect_area(double x0, double x1, double y0, double y1, double cx, double cy, double r) {
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
  double area = 0;
  for (int i = 0; i + 1 < nb; ++i) {
    const double u0 = br[i], u1 = br[i + 1];
    if (!(u1 > u0)) continue;
    const double um = 0.5 * (u0 + u1), sm = s(um);
    // Between breakpoints the circle is on one side of each edge; ≤ keeps a tangent edge (|y| = r).
    const bool top_circle = sm <= hy, bottom_circle = -sm >= ly;
    const double top = top_circle ? sm : hy, bottom = bottom_circle ? -sm : ly;
    if (!(top > bottom)) continue;
    const double circ = big_s(u1) - big_s(u0);
    const double w = u1 - u0;
    area += (top_circle ? circ : hy * w) - (bottom_circle ? -circ : ly * w);
  }
  return area;
}

}  // namespace glintlab
