// Exact area of an axis-aligned rectangle intersected with a disk, for the marginal density of
// Kemppinen et al. 2025 Algorithm 2 (core/glints/kemppinen_sampling.h). Host-side scalar code.
#pragma once

namespace glintlab {

// Area of [x0, x1] × [y0, y1] ∩ {(x − cx)² + (y − cy)² ≤ r²}: ∫ of the chord length clipped to
// [y0, y1] over x, split where the circle crosses y = y0 and y = y1, each piece in closed form
// with ∫√(r² − u²) du = ½(u√(r² − u²) + r² asin(u/r)).
// Defined out of line (disk_rect_area.cpp, baseline flags): the SIMD ISA translation units call
// it lane by lane, and an inline copy there would be a weak symbol each ISA defines.
double disk_rect_area(double x0, double x1, double y0, double y1, double cx, double cy, double r);

}  // namespace glintlab
