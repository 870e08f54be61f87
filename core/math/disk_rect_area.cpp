// Exact area of an axis-aligned rectangle intersected with a disk (core/math/disk_rect_area.h),
// for the marginal density of Kemppinen et al. 2025 Algorithm 2.
#include "core/math/disk_rect_area.h"

namespace glintlab {

double disk_rect_area(double x0, double x1, double y0, double y1, double cx, double cy, double r) {
  return disk_rect_area_inline(x0, x1, y0, y1, cx, cy, r);
}

}  // namespace glintlab
