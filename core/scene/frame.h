// Orthonormal shading frame (tangent, bitangent, normal) and the change of basis to and from it.
#pragma once

#include "core/math/orthonormal_basis.h"
#include "core/math/vec.h"

namespace glintlab {

template <class T>
struct Frame {
  Vec3<T> t, b, n;

  GLINTLAB_FN Vec3<T> to_local(Vec3<T> w) const { return {dot(w, t), dot(w, b), dot(w, n)}; }
  GLINTLAB_FN Vec3<T> to_world(Vec3<T> w) const { return w.x * t + w.y * b + w.z * n; }
};

// The frame with normal n (unit) whose tangent is `tangent` made orthogonal to n (Gram–Schmidt);
// where `tangent` is (nearly) parallel to n — a sphere's pole — any tangent perpendicular to n.
template <class T>
GLINTLAB_FN Frame<T> frame_from_normal_tangent(Vec3<T> n, Vec3<T> tangent) {
  const Vec3<T> tp = tangent - dot(tangent, n) * n;
  const T l2 = dot(tp, tp);
  const Vec3<T> fallback = basis_from_z(n).x;  // Duff et al. 2017 (core/math/orthonormal_basis.h)
  const Mask<T> ok = l2 > T(1e-20);
  const Vec3<T> t = select(ok, rsqrt(select(ok, l2, T(1))) * tp, fallback);
  return {t, cross(n, t), n};
}

}  // namespace glintlab
