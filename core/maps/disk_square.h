// U_Ω, the disk inscribed in the unit square, for the NDF→disk maps (Kemppinen 2025 Sec. 3.2).
#pragma once

#include "core/math/vec.h"

namespace glintlab {

// Convention shared by every map in core/maps/: the paper's maps land in the unit disk
// {|q| ≤ 1}; glintlab stores a unit-disk point q as p = (q + 1)/2, the disk of radius ½ centred at
// (½, ½) inscribed in [0,1]², so that the jittered grid of Sec. 3.3.1 samples [0,1)² directly.
// This scaling multiplies areas by ¼: |U_Ω| = π/4 in square units.
template <class T>
inline constexpr Scalar<T> kMapDomainArea = Scalar<T>(0.78539816339744830962);  // π/4

// Area factor of the disk→square scaling (each axis ×½).
template <class T>
inline constexpr Scalar<T> kDiskToSquareJacobian = Scalar<T>(0.25);

template <class T>
GLINTLAB_FN Vec2<T> disk_to_square(Vec2<T> q) {
  return {fma(q.x, T(0.5), T(0.5)), fma(q.y, T(0.5), T(0.5))};
}

template <class T>
GLINTLAB_FN Vec2<T> square_to_disk(Vec2<T> p) {
  // 2p − 1 is exact for p ∈ [¼, 1] (Sterbenz), i.e. near the disk centre where q is small.
  return {fma(p.x, T(2), T(-1)), fma(p.y, T(2), T(-1))};
}

}  // namespace glintlab
